//! `knotlab fluid cavity` and `knotlab fluid primitive` end to end: the binary run on small problems,
//! its files read back and checked.

use super::common;

use std::path::{Path, PathBuf};

use serde_json::Value;

use common::{json, knotlab};

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-cli-fluid-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    fn path(&self, name: &str) -> String {
        self.0.join(name).to_str().expect("utf-8 path").to_owned()
    }

    fn write(&self, name: &str, text: &str) -> String {
        let path = self.path(name);
        std::fs::write(&path, text).expect("write file");
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
    v.get(key).unwrap_or_else(|| panic!("no '{key}' in {v}"))
}

fn number(v: &Value, key: &str) -> f64 {
    field(v, key).as_f64().unwrap_or_else(|| panic!("'{key}' is not a number in {v}"))
}

/// Rows of a CSV file after its header, split at commas.
fn csv(path: &str) -> (String, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).expect("read csv");
    let mut lines = text.lines();
    let header = lines.next().expect("header").to_owned();
    (header, lines.map(|l| l.split(',').map(str::to_owned).collect()).collect())
}

fn ghia_table() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/reference/ghia1982-cavity.csv")
}

/// `fluid cavity` at Re 100 on 32 x 32 cells reaches a steady, divergence-free flow within 0.02 of Ghia's
/// table and writes the centreline profiles at the table's stations, the lid's and walls' values exact.
#[test]
fn cavity_writes_the_centreline_profiles_at_ghias_stations() {
    let dir = TempDir::new("cavity");
    let out = dir.path("profiles.csv");
    let reference = ghia_table();
    let (code, v) = json(&[
        "fluid",
        "cavity",
        "--re",
        "100",
        "--n",
        "32",
        "--out",
        &out,
        "--reference",
        reference.to_str().expect("utf-8"),
        "--json",
    ]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(field(&v, "steady"), true);
    assert!(number(&v, "max_divergence") <= number(&v, "divergence_tolerance"));
    // Even on 32 x 32 cells the profiles are within 0.02 of the table.
    assert!(number(&v, "max_error") < 0.02, "{v}");
    let (header, rows) = csv(&out);
    assert_eq!(header, "profile,coord,value");
    assert_eq!(rows.len(), 34);
    // The stations are the table's, in its order.
    let table = std::fs::read_to_string(&reference).expect("table");
    let stations: Vec<(String, f64)> = table
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("profile"))
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            (f[0].to_owned(), f[1].parse().expect("coord"))
        })
        .collect();
    for (row, (profile, coord)) in rows.iter().zip(&stations) {
        assert_eq!(&row[0], profile);
        assert!((row[1].parse::<f64>().expect("coord") - coord).abs() < 1e-12);
    }
    // The lid drags the top at u = 1, the walls hold the fluid still.
    let value = |p: &str, c: f64| {
        rows.iter()
            .find(|r| r[0] == p && (r[1].parse::<f64>().expect("coord") - c).abs() < 1e-12)
            .map(|r| r[2].parse::<f64>().expect("value"))
            .expect("station")
    };
    assert!((value("u", 1.0) - 1.0).abs() < 1e-12);
    assert!(value("u", 0.0).abs() < 1e-12 && value("v", 0.0).abs() < 1e-12 && value("v", 1.0).abs() < 1e-12);
    assert!(value("u", 0.5) < -0.1, "the vortex turns back along the centre");
}

/// `fluid cavity` refuses a non-positive `--re` and one beyond the steady cavity's (1e12 ran 48,000
/// steps to report a flow that means nothing), too small an `--n` and a reference table with a bad
/// number (naming the file and line), and writes nothing.
#[test]
fn cavity_refuses_bad_flags() {
    let dir = TempDir::new("cavity-bad");
    let out = dir.path("x.csv");
    let (code, _, stderr) = knotlab(&["fluid", "cavity", "--re", "-1", "--n", "32", "--out", &out]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--re: must be above 0 and at most 10000, got -1"), "{stderr}");
    let (code, _, stderr) = knotlab(&["fluid", "cavity", "--re", "1e12", "--n", "32", "--out", &out]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--re: must be above 0 and at most 10000, got 1000000000000"), "{stderr}");
    let (code, _, stderr) = knotlab(&["fluid", "cavity", "--re", "100", "--n", "2", "--out", &out]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--n:"), "{stderr}");
    let bad = dir.write("bad.csv", "profile,coord,re100,re1000\nu,0.5,oops,1\n");
    let (code, _, stderr) =
        knotlab(&["fluid", "cavity", "--re", "100", "--n", "16", "--out", &out, "--reference", &bad]);
    assert_eq!(code, 1);
    assert!(stderr.contains("bad.csv:2") && stderr.contains("oops"), "{stderr}");
    assert!(!Path::new(&out).exists(), "nothing written on bad input");
}

/// `fluid primitive` detours round a box obstacle with clearance in a divergence-free flow, and writes a path
/// with no point in a blocked cell of the grid file, timed from 0 to the reported duration.
#[test]
fn primitive_writes_the_path_and_the_grid_around_an_obstacle() {
    let dir = TempDir::new("primitive");
    let (path, grid) = (dir.path("path.csv"), dir.path("grid.csv"));
    let obstacles =
        dir.write("obstacles.toml", "[[box]]\nmin_m = [-0.003, -0.03]\nmax_m = [0.003, -0.008]\n");
    let (code, v) = json(&[
        "fluid",
        "primitive",
        "--obstacles-file",
        &obstacles,
        "--site",
        "0.1,0,-0.05,0,0,0.5",
        "--out",
        &path,
        "--grid",
        &grid,
        "--json",
    ]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(number(&v, "n"), 50.0);
    assert!(number(&v, "blocked_cells") > 50.0);
    assert!(number(&v, "detours") >= 2.0);
    assert!(number(&v, "max_divergence_per_s") <= number(&v, "divergence_tol_per_s"));
    let cell = number(&v, "cell_m");
    assert!(number(&v, "min_clearance_m") >= 0.5 * cell);
    let (header, points) = csv(&path);
    assert_eq!(header, "t_s,plane_x_m,plane_y_m,x_m,y_m,z_m");
    assert_eq!(points.len() as f64, number(&v, "points"));
    let (header, cells) = csv(&grid);
    assert_eq!(header, "i,j,plane_x_m,plane_y_m,blocked,u_mps,v_mps");
    assert_eq!(cells.len(), 2500);
    // No path point in a blocked cell of the grid file.
    let origin = field(&v, "region_origin_m");
    let (ox, oy) = (origin[0].as_f64().expect("x"), origin[1].as_f64().expect("y"));
    let blocked: Vec<bool> = cells.iter().map(|c| c[4] == "1").collect();
    for p in &points {
        let (x, y): (f64, f64) = (p[1].parse().expect("x"), p[2].parse().expect("y"));
        let (i, j) = (((x - ox) / cell).floor() as usize, ((y - oy) / cell).floor() as usize);
        assert!(!blocked[j * 50 + i], "path point in blocked cell ({i}, {j})");
    }
    // The world points are the plane points carried by the site: at z = 0.85 - 0.05, in a horizontal plane.
    for p in &points {
        assert!((p[5].parse::<f64>().expect("z") - 0.80).abs() < 1e-12);
    }
    // Times run from 0 every 10 ms to the end.
    let t: Vec<f64> = points.iter().map(|p| p[0].parse().expect("t")).collect();
    assert_eq!(t[0], 0.0);
    assert!((t[t.len() - 1] - number(&v, "duration_s")).abs() < 1e-12);
}

/// `fluid primitive --path-file` follows the file's path to its end; a short row, a zero speed, a bad
/// obstacles file or a malformed `--obstacle` is refused, naming the file, line or field.
#[test]
fn primitive_reads_a_path_file_and_names_bad_input() {
    let dir = TempDir::new("primitive-file");
    let path_file = dir.write("path.csv", "x_m,y_m,speed_mps\n0,0,0.02\n0.01,0.002,0.02\n0.02,0,0.03\n");
    let (code, v) = json(&["fluid", "primitive", "--path-file", &path_file, "--n", "32", "--json"]);
    assert_eq!(code, 0, "{v}");
    let end = field(&v, "end_world_m");
    assert!((end[0].as_f64().expect("x") - 0.02).abs() < 1e-3, "{v}");
    let bad_path = dir.write("bad_path.csv", "0,0,0.02\n0.01,0.002\n");
    let (code, _, stderr) = knotlab(&["fluid", "primitive", "--path-file", &bad_path]);
    assert_eq!(code, 1);
    assert!(stderr.contains("bad_path.csv:2") && stderr.contains("got 2 numbers"), "{stderr}");
    let slow = dir.write("slow.csv", "0,0,0.02\n0.01,0.002,0\n");
    let (code, _, stderr) = knotlab(&["fluid", "primitive", "--path-file", &slow]);
    assert_eq!(code, 1);
    assert!(stderr.contains("path.speed_mps[1]"), "{stderr}");
    let bad_toml = dir.write("bad.toml", "[[box]]\nmin_m = [0.0, 0.0]\nmax = [1.0, 1.0]\n");
    let (code, _, stderr) = knotlab(&["fluid", "primitive", "--obstacles-file", &bad_toml]);
    assert_eq!(code, 1);
    assert!(stderr.contains("bad.toml:3: box[0].max: unknown field `max`"), "{stderr}");
    let (code, _, stderr) = knotlab(&["fluid", "primitive", "--obstacle", "0,0,1"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("x0,y0,x1,y1"), "{stderr}");
}

/// 3D solids (a capsule and a tilted box) cutting the plane block cells that the path detours round with
/// clearance; a solid with a negative radius is refused, naming the solid and the field.
#[test]
fn primitive_avoids_solids_cutting_the_plane() {
    let dir = TempDir::new("primitive-solids");
    // A shaft straight down through the outer loop and a tilted post, in the world at the (unmoved) site;
    // the plane is z = 0.85.
    let solids = dir.write(
        "solids.toml",
        "[[capsule]]\na_m = [0.0, 0.012, 0.80]\nb_m = [0.0, 0.012, 0.90]\nradius_m = 0.0015\n\n\
         [[box3d]]\ncentre_m = [-0.008, 0.0, 0.85]\nhalf_extents_m = [0.002, 0.002, 0.05]\nrpy_rad = [0.3, 0.0, 0.0]\n",
    );
    let (code, v) = json(&["fluid", "primitive", "--obstacles-file", &solids, "--json"]);
    assert_eq!(code, 0, "{v}");
    assert!(number(&v, "blocked_cells") >= 20.0, "{v}");
    assert!(number(&v, "detours") >= 1.0, "{v}");
    assert!(number(&v, "min_clearance_m") >= 0.5 * number(&v, "cell_m"), "{v}");
    let bad =
        dir.write("bad.toml", "[[capsule]]\na_m = [0.0, 0.0, 0.8]\nb_m = [0.0, 0.0, 0.9]\nradius_m = -1.0\n");
    let (code, _, stderr) = knotlab(&["fluid", "primitive", "--obstacles-file", &bad]);
    assert_eq!(code, 1);
    assert!(stderr.contains("bad.toml:1: capsule[0].radius_m: -1 must be finite and positive"), "{stderr}");
}

/// An obstacle box given the wrong way round (its first corner beyond the second) blocked nothing and
/// was silently accepted; now it is refused, on the command line naming the flag and in an obstacle
/// file naming the file, the line and the box, as are a solid's negative half extent and radius.
#[test]
fn an_inverted_box_or_a_negative_solid_is_refused() {
    let dir = TempDir::new("inverted-box");
    let out = dir.path("path.csv");
    let base = ["fluid", "primitive", "--path", "double-loop", "--n", "32", "--out", &out];
    let (code, _, stderr) = knotlab(&[&base[..], &["--obstacle", "0.01,0.01,-0.01,-0.01"]].concat());
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--obstacle") && stderr.contains("lies beyond max_m"), "{stderr}");
    let file = dir.write(
        "obstacles.toml",
        "[[box]]\nmin_m = [0.0, 0.0]\nmax_m = [0.01, 0.01]\n\n[[box]]\nmin_m = [0.01, 0.0]\nmax_m = [0.0, 0.01]\n\n[[capsule]]\na_m = [0.0, 0.0, 0.0]\nb_m = [0.0, 0.0, 0.1]\nradius_m = -0.01\n",
    );
    let (code, _, stderr) = knotlab(&[&base[..], &["--obstacles-file", &file]].concat());
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("obstacles.toml:5: box[1]: min_m [0.01, 0.0] lies beyond max_m [0.0, 0.01]"),
        "{stderr}"
    );
    assert!(
        stderr.contains("obstacles.toml:9: capsule[0].radius_m: -0.01 must be finite and positive"),
        "{stderr}"
    );
    assert!(!Path::new(&out).exists(), "nothing written on bad input");
}
