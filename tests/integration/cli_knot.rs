//! `knotlab knot classify` end to end: centreline files written to a temp dir, the binary run on them.

use super::common;

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

use serde_json::Value;

use common::{json, knotlab};

struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("knotlab-cli-knot-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    fn write(&self, name: &str, text: &str) -> String {
        let path = self.0.join(name);
        std::fs::write(&path, text).expect("write csv");
        path.to_str().expect("utf-8 path").to_owned()
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

/// A CSV with a header: the (2, q) torus knot scaled to `scale_m`, cut open at its outermost point.
fn torus_csv(q: f64, n: usize, scale_m: f64) -> String {
    let mut text = String::from("x,y,z\n");
    for i in 0..n {
        let t = TAU * i as f64 / n as f64;
        let r = 2.0 + (q * t).cos();
        let (x, y, z) = (r * (2.0 * t).cos(), r * (2.0 * t).sin(), (q * t).sin());
        text += &format!("{},{},{}\n", x * scale_m, y * scale_m, 0.8 + z * scale_m);
    }
    text
}

fn field<'a>(v: &'a Value, key: &str) -> &'a Value {
    v.get(key).unwrap_or_else(|| panic!("no '{key}' in {v}"))
}

/// `knot classify` names a trefoil, and the (2, 5) torus knot as a surgeon's knot, with their crossings,
/// determinant and writhe, all 13 projection directions agreeing, in JSON and in text.
#[test]
fn classify_a_trefoil_and_a_cinquefoil() {
    let dir = TempDir::new("knots");
    let trefoil = dir.write("trefoil.csv", &torus_csv(3.0, 200, 0.002));
    let (code, v) = json(&["knot", "classify", &trefoil, "--json"]);
    assert_eq!(code, 0, "{v}");
    assert_eq!(field(&v, "knot"), "trefoil");
    assert_eq!(field(&v, "determinant"), 3);
    assert_eq!(field(&v, "writhe").as_i64().unwrap().abs(), 3);
    assert_eq!(field(&v, "crossings"), 3);
    assert_eq!(field(&v, "agreement").as_f64(), Some(1.0));
    assert_eq!(field(&v, "points"), 200);
    let votes = field(&v, "directions").as_array().unwrap();
    assert_eq!(votes.len(), 13);
    assert!(votes.iter().all(|d| d["knot"] == "trefoil"));
    let span = field(&v, "span");
    assert!(span["start_m"].as_f64().unwrap() < span["end_m"].as_f64().unwrap());
    assert!((span["centre_m"][2].as_f64().unwrap() - 0.8).abs() < 0.002, "{span}");

    let double = dir.write("double.csv", &torus_csv(5.0, 250, 0.002));
    let (code, v) = json(&["knot", "classify", &double, "--json"]);
    assert_eq!(code, 0);
    assert_eq!((field(&v, "knot"), field(&v, "determinant")), (&Value::from("surgeons"), &Value::from(5)));
    assert_eq!(field(&v, "writhe").as_i64().unwrap().abs(), 5);

    let (code, text, _) = knotlab(&["knot", "classify", &trefoil]);
    assert_eq!(code, 0);
    assert!(text.contains("trefoil (3 crossings after reduction, determinant 3"), "{text}");
    assert!(text.contains("13 of 13 directions agree"), "{text}");
}

/// A wavy, untied thread (its file with a comment and a blank line) is the unknot: no crossings, no span.
#[test]
fn an_untied_thread_is_the_unknot() {
    let dir = TempDir::new("unknot");
    let mut text = String::from("# a wavy thread lying on the tissue\n\n");
    for i in 0..50 {
        let x = i as f64 * 0.002;
        text += &format!("{x}, {}, 0.8\n", 0.003 * (x * 300.0).sin());
    }
    let path = dir.write("wavy.csv", &text);
    let (code, v) = json(&["knot", "classify", &path, "--json"]);
    assert_eq!(code, 0);
    assert_eq!((field(&v, "knot"), field(&v, "crossings")), (&Value::from("unknot"), &Value::from(0)));
    assert_eq!(field(&v, "determinant"), 1);
    assert!(field(&v, "span").is_null());
}

/// Given the tissue plane and stitch, `knot classify` says whether the knot is down on the tissue and its
/// height when not; only some of the three flags, or a zero normal, is refused.
#[test]
fn knot_down_on_the_tissue_or_not() {
    let dir = TempDir::new("down");
    // A 2 mm trefoil centred 0.8 m up, 1 mm thick in z: the tissue at z = 0.7985, normal +z.
    let path = dir.write("trefoil.csv", &torus_csv(3.0, 200, 0.0005));
    let args = |tissue_z: &str| {
        let point = format!("0,0,{tissue_z}");
        json(&[
            "knot",
            "classify",
            &path,
            "--json",
            "--tissue-point",
            &point,
            "--tissue-normal",
            "0,0,1",
            "--stitch",
            &point,
        ])
    };
    let (code, v) = args("0.7994");
    assert_eq!(code, 0, "{v}");
    assert_eq!(v["placement"]["down"], true, "{v}");
    let (code, v) = args("0.79");
    assert_eq!(code, 0);
    assert_eq!(v["placement"]["down"], false, "{v}");
    assert!((v["placement"]["height_m"].as_f64().unwrap() - 0.0095).abs() < 0.0006, "{v}");
    // All three or none.
    let (code, _, stderr) = knotlab(&["knot", "classify", &path, "--stitch", "0,0,0.8"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("--tissue-point"), "{stderr}");
    let (code, _, stderr) = knotlab(&[
        "knot",
        "classify",
        &path,
        "--tissue-point",
        "0,0,0.8",
        "--tissue-normal",
        "0,0,0",
        "--stitch",
        "0,0,0.8",
    ]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--tissue-normal") && stderr.contains("zero"), "{stderr}");
}

fn refused(dir: &TempDir, name: &str, text: &str, message: &str) {
    let path = dir.write(name, text);
    let (code, stdout, stderr) = knotlab(&["knot", "classify", &path]);
    assert_eq!(code, 1, "{stdout}");
    assert!(stderr.contains(&format!("{name}: {message}")), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let (code, v) = json(&["knot", "classify", &path, "--json"]);
    assert_eq!((code, &v["ok"]), (1, &Value::Bool(false)));
    assert!(v["error"].as_str().expect("error text").contains(message), "{v}");
    assert!(Path::new(v["file"].as_str().expect("file name")).ends_with(name));
}

/// A centreline file with too few points, a repeated point, a non-finite or non-numeric value or a short
/// line, or a missing file, is refused without a panic, naming the file, the line and the reason.
#[test]
fn bad_files_are_named_with_line_and_reason() {
    let dir = TempDir::new("bad");
    refused(&dir, "three.csv", "x,y,z\n0,0,0\n1,0,0\n1,1,0\n", "line 4: end of file after only 3 point(s)");
    refused(&dir, "dup.csv", "0,0,0\n1,0,0\n1,0,0\n1,1,0\n0,1,0\n", "line 3: repeats the point on line 2");
    refused(&dir, "nan.csv", "0,0,0\n1,0,0\n\n1,NaN,0\n1,1,0\n", "line 4: y = 'NaN' is not finite");
    refused(&dir, "inf.csv", "0,0,0\n1,0,0\n1,1,inf\n0,1,0\n", "line 3: z = 'inf' is not finite");
    refused(
        &dir,
        "words.csv",
        "x,y,z\n0,0,0\n1,0,zero\n1,1,0\n0,1,0\n",
        "line 3: z = 'zero' is not a number",
    );
    refused(
        &dir,
        "short_line.csv",
        "0,0,0\n1,0,0\n1,1\n0,1,0\n",
        "line 3: expected 3 comma-separated numbers",
    );
    let missing = dir.0.join("missing.csv");
    let (code, _, stderr) = knotlab(&["knot", "classify", missing.to_str().unwrap()]);
    assert_eq!(code, 1);
    assert!(stderr.contains("missing.csv: cannot read"), "{stderr}");
}
