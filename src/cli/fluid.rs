//! `knotlab fluid`: the Navier-Stokes solver's lid-driven cavity (validation against Ghia et al.) and the
//! instantiation of a 2D primitive by stirring a fluid (the built-in double wrap, or a path file), around
//! obstacles given as boxes in the plane.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, bail};
use clap::{Args, Subcommand, ValueEnum};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use knotlab_learner::fluid::{
    CavityConfig, FluidError, GHIA_U_Y, GHIA_V_X, GridRegion, InstantiateSettings, Instantiation,
    ObstacleMask, PlanarDemonstration, PlaneFrame, PressureSolverKind, Solid, SpeedPath, block_solid,
    instantiate, run_cavity,
};

use super::csv_file;
use super::numbers::{parse_list, parse_vector3};
use super::output::{Output, outln};

#[derive(Debug, Subcommand)]
pub enum FluidCommand {
    /// Run the lid-driven cavity to its steady state and write the centreline profiles (CSV
    /// `profile,coord,value`: `u` along x = 0.5 at the heights y, `v` along y = 0.5 at the abscissae x of
    /// Ghia, Ghia and Shin 1982).
    Cavity(CavityArgs),
    /// Instantiate a 2D primitive: stir a fluid along the path at the new site, throw a particle in, and
    /// write the particle's path (and the grid).
    Primitive(Box<PrimitiveArgs>),
}

#[derive(Debug, Clone, Copy, ValueEnum)]
enum Solver {
    /// Sparse Cholesky, factored once (the default).
    Direct,
    /// Successive over-relaxation, the reference.
    Sor,
}

impl From<Solver> for PressureSolverKind {
    fn from(s: Solver) -> Self {
        match s {
            Solver::Direct => PressureSolverKind::Direct,
            Solver::Sor => PressureSolverKind::Sor,
        }
    }
}

#[derive(Debug, Args)]
pub struct CavityArgs {
    /// Reynolds number (lid speed 1, side 1).
    #[arg(long, allow_hyphen_values = true)]
    re: f64,
    /// Cells per side.
    #[arg(long, default_value_t = 128)]
    n: usize,
    /// The CSV file to write.
    #[arg(long)]
    out: PathBuf,
    /// The pressure solver.
    #[arg(long, value_enum, default_value_t = Solver::Direct)]
    solver: Solver,
    /// The Ghia table (CSV `profile,coord,re100,re1000`, e.g. scenarios/reference/ghia1982-cavity.csv,
    /// which `knotlab shipped dump` writes out): report the largest error against its column for --re
    /// 100 or 1000.
    #[arg(long)]
    reference: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// The built-in test paths.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum BuiltInPath {
    /// The knot's double wrap: two turns around the centre of the plane, lead in and lead out.
    DoubleLoop,
}

#[derive(Debug, Args)]
pub struct PrimitiveArgs {
    /// The built-in path (ignored with --path-file).
    #[arg(long, value_enum, default_value_t = BuiltInPath::DoubleLoop)]
    path: BuiltInPath,
    /// A path file instead: CSV `x_m,y_m,speed_mps` per line in plane coordinates (header line, blank
    /// lines and `#` comments allowed).
    #[arg(long)]
    path_file: Option<PathBuf>,
    /// Diameter of the built-in double wrap's outer turn, m.
    #[arg(long, default_value_t = 0.024)]
    diameter_m: f64,
    /// Speed of the built-in path, m/s.
    #[arg(long, default_value_t = 0.02)]
    speed_mps: f64,
    /// Cells per side of the grid.
    #[arg(long, default_value_t = 50)]
    n: usize,
    /// Free margin around the path's bounding box, m.
    #[arg(long, default_value_t = 0.006)]
    margin_m: f64,
    /// The demonstration plane's origin x,y,z in the world, m.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, default_value = "0,0,0.85")]
    plane_origin: Vector3<f64>,
    /// The plane's first axis x,y,z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, default_value = "1,0,0")]
    plane_x: Vector3<f64>,
    /// The plane's second axis x,y,z.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, default_value = "0,1,0")]
    plane_y: Vector3<f64>,
    /// The new site: the rigid motion of the world carrying the demonstration there, `x,y,z` (m) or
    /// `x,y,z,roll,pitch,yaw` (rad).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_site)]
    site: Option<Site>,
    /// An obstacle: the box `x0,y0,x1,y1` in plane coordinates (m); every cell it touches is blocked.
    /// Repeat for more.
    #[arg(long = "obstacle", allow_hyphen_values = true, value_parser = parse_box)]
    obstacles: Vec<Rect>,
    /// Obstacles from a TOML file: `[[box]]` tables with `min_m = [x, y]` and `max_m = [x, y]` (plane
    /// coordinates); solids in the world at the new site cutting the plane: `[[box3d]]` with
    /// `centre_m = [x, y, z]`, `half_extents_m = [x, y, z]` and optional `rpy_rad = [roll, pitch, yaw]`,
    /// `[[capsule]]` with `a_m`, `b_m` (axis ends) and `radius_m`.
    #[arg(long)]
    obstacles_file: Option<PathBuf>,
    /// The pressure solver.
    #[arg(long, value_enum, default_value_t = Solver::Direct)]
    solver: Solver,
    /// Time between two output points, s.
    #[arg(long, default_value_t = 0.01)]
    output_dt_s: f64,
    /// Write the path here: CSV `t_s,plane_x_m,plane_y_m,x_m,y_m,z_m`.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write the grid here: CSV `i,j,plane_x_m,plane_y_m,blocked,u_mps,v_mps` (cell centres, final flow).
    #[arg(long)]
    grid: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    rerun: crate::rerun_log::RerunArgs,
}

/// A rigid motion from the command line.
#[derive(Debug, Clone, Copy)]
pub struct Site(Isometry3<f64>);

fn parse_site(text: &str) -> Result<Site, String> {
    match parse_list(text)?.as_slice() {
        [x, y, z] => Ok(Site(Isometry3::translation(*x, *y, *z))),
        [x, y, z, roll, pitch, yaw] => Ok(Site(Isometry3::from_parts(
            Translation3::new(*x, *y, *z),
            UnitQuaternion::from_euler_angles(*roll, *pitch, *yaw),
        ))),
        other => Err(format!("expected x,y,z or x,y,z,roll,pitch,yaw, got {} numbers", other.len())),
    }
}

/// A box in plane coordinates.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rect {
    min_m: [f64; 2],
    max_m: [f64; 2],
}

impl Rect {
    /// Finite corners, the first not beyond the second on either axis.
    fn problem(&self) -> Option<String> {
        if !self.min_m.iter().chain(&self.max_m).all(|x| x.is_finite()) {
            return Some(format!("corners {:?} and {:?} must be finite", self.min_m, self.max_m));
        }
        (self.min_m[0] > self.max_m[0] || self.min_m[1] > self.max_m[1]).then(|| {
            format!(
                "min_m {:?} lies beyond max_m {:?}: the first corner must be the lower on both axes",
                self.min_m, self.max_m
            )
        })
    }
}

fn parse_box(text: &str) -> Result<Rect, String> {
    let rect = match parse_list(text)?.as_slice() {
        [x0, y0, x1, y1] => Rect { min_m: [*x0, *y0], max_m: [*x1, *y1] },
        other => return Err(format!("expected x0,y0,x1,y1, got {} numbers", other.len())),
    };
    rect.problem().map_or(Ok(rect), Err)
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ObstacleFile {
    #[serde(rename = "box", default)]
    boxes: Vec<toml::Spanned<Rect>>,
    #[serde(rename = "box3d", default)]
    boxes_3d: Vec<toml::Spanned<Box3d>>,
    #[serde(rename = "capsule", default)]
    capsules: Vec<toml::Spanned<Capsule>>,
}

/// An oriented box in the world.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Box3d {
    centre_m: [f64; 3],
    half_extents_m: [f64; 3],
    #[serde(default)]
    rpy_rad: [f64; 3],
}

/// A capsule in the world.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Capsule {
    a_m: [f64; 3],
    b_m: [f64; 3],
    radius_m: f64,
}

impl ObstacleFile {
    fn solids(&self) -> Vec<Solid> {
        let boxes = self.boxes_3d.iter().map(|b| b.get_ref()).map(|b| Solid::Box {
            world_from_box: Isometry3::from_parts(
                Translation3::from(Vector3::from(b.centre_m)),
                UnitQuaternion::from_euler_angles(b.rpy_rad[0], b.rpy_rad[1], b.rpy_rad[2]),
            ),
            half_extents_m: Vector3::from(b.half_extents_m),
        });
        let capsules = self.capsules.iter().map(|c| c.get_ref()).map(|c| Solid::Capsule {
            a_m: Vector3::from(c.a_m),
            b_m: Vector3::from(c.b_m),
            radius_m: c.radius_m,
        });
        boxes.chain(capsules).collect()
    }

    /// Every obstacle whose numbers make no solid, as `table[k] (line): reason`: corners not finite
    /// or the wrong way round, half extents or a radius not finite and positive.
    fn problems(&self, text: &str) -> Vec<String> {
        let line = |span: std::ops::Range<usize>| knotlab_hw::toml_file::line_of(text, span.start);
        let mut problems = Vec::new();
        for (k, b) in self.boxes.iter().enumerate() {
            if let Some(p) = b.get_ref().problem() {
                problems.push(format!("{}: box[{k}]: {p}", line(b.span())));
            }
        }
        for (k, b) in self.boxes_3d.iter().enumerate() {
            let v = b.get_ref();
            if !v.half_extents_m.iter().all(|h| h.is_finite() && *h > 0.0) {
                problems.push(format!(
                    "{}: box3d[{k}].half_extents_m: {:?} must all be finite and positive",
                    line(b.span()),
                    v.half_extents_m
                ));
            }
            if !v.centre_m.iter().chain(&v.rpy_rad).all(|x| x.is_finite()) {
                problems.push(format!("{}: box3d[{k}]: centre_m and rpy_rad must be finite", line(b.span())));
            }
        }
        for (k, c) in self.capsules.iter().enumerate() {
            let v = c.get_ref();
            if !(v.radius_m.is_finite() && v.radius_m > 0.0) {
                problems.push(format!(
                    "{}: capsule[{k}].radius_m: {} must be finite and positive",
                    line(c.span()),
                    v.radius_m
                ));
            }
            if !v.a_m.iter().chain(&v.b_m).all(|x| x.is_finite()) {
                problems.push(format!("{}: capsule[{k}]: a_m and b_m must be finite", line(c.span())));
            }
        }
        problems
    }
}

/// A library error in the command line's words: a bad input names the flag that gave it.
fn flag_error(error: FluidError) -> anyhow::Error {
    match &error {
        FluidError::Invalid { field, reason } => {
            let flag = match field.as_str() {
                "region.n" | "n" => "n",
                "re" => "re",
                "margin_m" | "points" => "margin-m",
                "plane.origin_m" => "plane-origin",
                "plane.axis_x" => "plane-x",
                "plane.axis_y" => "plane-y",
                "output_dt_s" => "output-dt-s",
                "radius_m" => "diameter-m",
                _ => return anyhow::anyhow!("{error}"),
            };
            anyhow::anyhow!("--{flag}: {reason}")
        }
        _ => anyhow::anyhow!("{error}"),
    }
}

pub fn run(command: FluidCommand, out: &mut Output) -> anyhow::Result<ExitCode> {
    match command {
        FluidCommand::Cavity(args) => cavity(&args, out),
        FluidCommand::Primitive(args) => primitive(&args, out),
    }
}

#[derive(Serialize)]
struct CavityReport {
    re: f64,
    n: usize,
    solver: &'static str,
    steps: usize,
    coarse_steps: usize,
    time: f64,
    steady: bool,
    final_acceleration: f64,
    max_divergence: f64,
    divergence_tolerance: f64,
    out: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_error: Option<f64>,
}

fn cavity(args: &CavityArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let config = CavityConfig { solver: args.solver.into(), ..CavityConfig::new(args.re, args.n) };
    let reference = match &args.reference {
        Some(path) => Some(read_reference(path, args.re)?),
        None => None,
    };
    let run = run_cavity(&config, |_| {}).map_err(flag_error)?;
    let mut rows = Vec::new();
    let mut max_error: Option<f64> = None;
    let profiles = GHIA_U_Y
        .iter()
        .map(|&y| ("u", y, run.u_centreline(y)))
        .chain(GHIA_V_X.iter().map(|&x| ("v", x, run.v_centreline(x))));
    for (profile, coord, value) in profiles {
        rows.push((profile, coord, value));
        if let Some(table) = &reference {
            let want = table.iter().find(|(p, c, _)| p == profile && (c - coord).abs() < 1e-9).map(|r| r.2);
            if let Some(want) = want {
                max_error = Some(max_error.unwrap_or(0.0).max((value - want).abs()));
            }
        }
    }
    csv_file::write_rows(&args.out, &["profile", "coord", "value"], rows)?;
    let report = CavityReport {
        re: args.re,
        n: args.n,
        solver: config.solver.name(),
        steps: run.steps,
        coarse_steps: run.coarse_steps,
        time: run.sim.time_s(),
        steady: run.steady,
        final_acceleration: run.final_acceleration,
        max_divergence: run.max_divergence,
        divergence_tolerance: config.divergence_tol,
        out: args.out.display().to_string(),
        max_error,
    };
    if args.json {
        out.line(serde_json::to_string_pretty(&report).context("writing JSON")?);
    } else {
        outln!(
            out,
            "cavity Re {} on {} x {} ({} solver): {} steps (+{} on coarser grids) to t = {:.2}, {}",
            report.re,
            report.n,
            report.n,
            report.solver,
            report.steps,
            report.coarse_steps,
            report.time,
            if report.steady { "steady" } else { "NOT steady" }
        );
        outln!(
            out,
            "largest divergence after a step {:.2e} (tolerance {:.0e}); profiles in {}",
            report.max_divergence,
            report.divergence_tolerance,
            report.out
        );
        if let Some(e) = report.max_error {
            outln!(out, "largest error against Ghia et al.: {e:.4}");
        }
    }
    Ok(if run.steady { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

/// The Ghia table's column for `re` (100 or 1000): `(profile, coord, value)`.
fn read_reference(path: &Path, re: f64) -> anyhow::Result<Vec<(String, f64, f64)>> {
    let column = if re == 100.0 {
        2
    } else if re == 1000.0 {
        3
    } else {
        bail!("--reference: the table has Re 100 and 1000 only, not {re}");
    };
    let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader.headers().with_context(|| format!("reading {}", path.display()))?.clone();
    if header.iter().collect::<Vec<_>>() != ["profile", "coord", "re100", "re1000"] {
        bail!("{}: the header must be profile,coord,re100,re1000", path.display());
    }
    let mut rows = Vec::new();
    let mut record = csv::StringRecord::new();
    while reader.read_record(&mut record).with_context(|| format!("reading {}", path.display()))? {
        let line = csv_file::line_of_record(&text, &reader);
        let at = || format!("{}:{line}", path.display());
        let fields: Vec<&str> = record.iter().collect();
        if fields.len() != 4 || !(fields[0] == "u" || fields[0] == "v") {
            bail!(
                "{}: expected profile,coord,re100,re1000 with profile u or v, got '{}'",
                at(),
                fields.join(",")
            );
        }
        let parse = |s: &str, what: &str| {
            s.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .with_context(|| format!("{}: {what} '{s}' is not a number", at()))
        };
        rows.push((fields[0].to_owned(), parse(fields[1], "coord")?, parse(fields[column], "value")?));
    }
    if rows.is_empty() {
        bail!("{}: no rows", path.display());
    }
    Ok(rows)
}

#[derive(Serialize)]
struct PrimitiveReport {
    n: usize,
    cell_m: f64,
    region_origin_m: [f64; 2],
    world_corner_m: [f64; 3],
    points: usize,
    duration_s: f64,
    path_length_m: f64,
    steps: usize,
    solver: &'static str,
    viscosity_m2ps: f64,
    max_divergence_per_s: f64,
    divergence_tol_per_s: f64,
    blocked_cells: usize,
    repaired_cells: usize,
    detours: usize,
    moved_samples: usize,
    particle_splits: usize,
    particle_holds: usize,
    end_gap_m: f64,
    #[serde(serialize_with = "finite_or_null")]
    min_clearance_m: f64,
    start_world_m: [f64; 3],
    end_world_m: [f64; 3],
    #[serde(skip_serializing_if = "Option::is_none")]
    out: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    grid: Option<String>,
}

fn finite_or_null<S: serde::Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    if x.is_finite() { s.serialize_f64(*x) } else { s.serialize_none() }
}

fn primitive(args: &PrimitiveArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let plane = PlaneFrame::new(args.plane_origin, args.plane_x, args.plane_y).map_err(flag_error)?;
    let path = match &args.path_file {
        Some(file) => read_path(file)?,
        None => match args.path {
            BuiltInPath::DoubleLoop => {
                if !(args.speed_mps.is_finite() && args.speed_mps > 0.0) {
                    bail!("--speed-mps: must be positive, got {}", args.speed_mps);
                }
                SpeedPath::double_loop(Vector2::zeros(), args.diameter_m / 2.0, args.speed_mps)
                    .map_err(flag_error)?
            }
        },
    };
    let region = GridRegion::around(&path.points_m, args.n, args.margin_m).map_err(flag_error)?;
    let mut mask = ObstacleMask::free(args.n);
    let mut boxes = args.obstacles.clone();
    let site = args.site.map_or_else(Isometry3::identity, |s| s.0);
    if let Some(file) = &args.obstacles_file {
        let parsed = read_obstacles(file)?;
        boxes.extend(parsed.boxes.iter().map(|b| *b.get_ref()));
        for (k, solid) in parsed.solids().iter().enumerate() {
            block_solid(&mut mask, &plane.moved(&site), &region, solid)
                .map_err(|e| anyhow::anyhow!("{}: solid {}: {e}", file.display(), k + 1))?;
        }
    }
    for b in &boxes {
        region.block_box(&mut mask, Vector2::from(b.min_m), Vector2::from(b.max_m));
    }
    let blocked_cells = mask.count_blocked();
    let settings = InstantiateSettings {
        solver: args.solver.into(),
        output_dt_s: args.output_dt_s,
        ..InstantiateSettings::default()
    };
    let demo = PlanarDemonstration { plane, path };
    let inst = instantiate(&demo, &site, &region, &mask, &settings).map_err(flag_error)?;
    if let Some(file) = &args.out {
        write_path(file, &inst)?;
    }
    if let Some(file) = &args.grid {
        write_grid(file, &inst)?;
    }
    let recording = args.rerun.open("fluid")?;
    #[cfg(feature = "rerun")]
    if let Some(rec) = &recording {
        crate::rerun_log::log_instantiation(rec, &inst, "fluid", 0.0)?;
    }
    crate::rerun_log::finish(recording)?;
    let r = &inst.report;
    let first = inst.points[0].world_m;
    let last = inst.points[inst.points.len() - 1].world_m;
    let report = PrimitiveReport {
        n: args.n,
        cell_m: r.cell_m,
        region_origin_m: [region.origin_m.x, region.origin_m.y],
        world_corner_m: inst.region.world_corner_m(&inst.plane).into(),
        points: inst.points.len(),
        duration_s: r.duration_s,
        path_length_m: inst.points.windows(2).map(|w| (w[1].world_m - w[0].world_m).norm()).sum(),
        steps: r.steps,
        solver: settings.solver.name(),
        viscosity_m2ps: r.viscosity_m2ps,
        max_divergence_per_s: r.max_divergence_per_s,
        divergence_tol_per_s: r.divergence_tol_per_s,
        blocked_cells,
        repaired_cells: r.repaired_cells,
        detours: r.detours,
        moved_samples: r.moved_samples,
        particle_splits: r.particle_splits,
        particle_holds: r.particle_holds,
        end_gap_m: r.end_gap_m,
        min_clearance_m: r.min_clearance_m,
        start_world_m: first.into(),
        end_world_m: last.into(),
        out: args.out.as_ref().map(|p| p.display().to_string()),
        grid: args.grid.as_ref().map(|p| p.display().to_string()),
    };
    if args.json {
        out.line(serde_json::to_string_pretty(&report).context("writing JSON")?);
    } else {
        outln!(
            out,
            "2D primitive on {0} x {0} cells of {1:.3} mm: {2} points over {3:.3} s, {4:.1} mm long, {5} fluid steps ({6} solver)",
            report.n,
            report.cell_m * 1e3,
            report.points,
            report.duration_s,
            report.path_length_m * 1e3,
            report.steps,
            report.solver
        );
        outln!(
            out,
            "obstacles: {} cells blocked (+{} by the repair), {} detours; particle: {} split steps, {} holds, end {:.3} mm from the stirrer, clearance {}",
            report.blocked_cells,
            report.repaired_cells,
            report.detours,
            report.particle_splits,
            report.particle_holds,
            report.end_gap_m * 1e3,
            if report.min_clearance_m.is_finite() {
                format!("{:.3} mm", report.min_clearance_m * 1e3)
            } else {
                "(no obstacle)".to_owned()
            }
        );
        outln!(
            out,
            "largest divergence after a step {:.2e} 1/s (tolerance {:.2e})",
            report.max_divergence_per_s,
            report.divergence_tol_per_s
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// A path file: `x_m,y_m,speed_mps` per line.
fn read_path(file: &Path) -> anyhow::Result<SpeedPath> {
    let text = std::fs::read_to_string(file).with_context(|| format!("{}: cannot read", file.display()))?;
    knotlab_learner::fluid::path_file::parse_speed_path(&text).map_err(|e| {
        if e.line == 0 {
            anyhow::anyhow!("{}: {}", file.display(), e.reason)
        } else {
            anyhow::anyhow!("{}:{}: {}", file.display(), e.line, e.reason)
        }
    })
}

fn read_obstacles(file: &Path) -> anyhow::Result<ObstacleFile> {
    let text = std::fs::read_to_string(file).with_context(|| format!("{}: cannot read", file.display()))?;
    let obstacles: ObstacleFile = knotlab_hw::toml_file::deserialize(&text)
        .map_err(|p| anyhow::anyhow!("{}:{}: {}: {}", file.display(), p.line, p.key, p.reason))?;
    let problems = obstacles.problems(&text);
    if !problems.is_empty() {
        bail!("{}:{}", file.display(), problems.join(&format!("; {}:", file.display())));
    }
    Ok(obstacles)
}

fn write_path(file: &Path, inst: &Instantiation) -> anyhow::Result<()> {
    let rows =
        inst.points.iter().map(|p| (p.t_s, p.plane_m.x, p.plane_m.y, p.world_m.x, p.world_m.y, p.world_m.z));
    csv_file::write_rows(file, &["t_s", "plane_x_m", "plane_y_m", "x_m", "y_m", "z_m"], rows)
}

fn write_grid(file: &Path, inst: &Instantiation) -> anyhow::Result<()> {
    let region = inst.region;
    let rows = (0..region.n).flat_map(|j| (0..region.n).map(move |i| (i, j))).map(|(i, j)| {
        let centre = region.origin_m + Vector2::new(i as f64 + 0.5, j as f64 + 0.5) * region.cell_m;
        let velocity = inst.cell_velocity_mps[j * region.n + i];
        (i, j, centre.x, centre.y, u8::from(inst.mask.get(i, j)), velocity.x, velocity.y)
    });
    csv_file::write_rows(file, &["i", "j", "plane_x_m", "plane_y_m", "blocked", "u_mps", "v_mps"], rows)
}
