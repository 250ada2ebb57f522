//! `knotlab obstacles`: the virtual obstacles of one arm over a grid in a scene: the cells where putting
//! the arm's instrument tip would make the arm collide (or where it cannot be put), on the CPU or the
//! GPU; written as CSV and PNG, counts printed. The glue between sim's scene (trocars, obstacles, the
//! arms' starting joints) and learner, which never depends on sim.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Context;
use clap::{Args, ValueEnum};
use nalgebra::{Rotation3, Vector3};
use serde_json::json;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::{
    ArmState, CellVerdict, CollisionWorld, GridPlane, GridRequest, GridResult, PreparedGrid,
    SubcellOrientation, compute_cpu, cpu::thread_pool,
};
use knotlab_sim::scene::SceneConfig;
use knotlab_sim::world::SimWorld;

use super::csv_file;
use super::numbers::parse_vector3;
use super::output::{Output, outln};
use knotlab_scenarios::shipped;

/// Height of the default plane above the tissue surface, m.
const DEFAULT_HEIGHT_M: f64 = 0.02;
/// Side of the default plane, m.
const DEFAULT_SIZE_M: f64 = 0.06;

/// Which backend computes the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Backend {
    /// rayon on the CPU.
    Cpu,
    /// The wgpu compute shader (falls back to the CPU, saying so, when no GPU adapter exists).
    Gpu,
}

#[derive(Debug, Args)]
pub struct ObstaclesArgs {
    /// The scene file: trocars, obstacles, tissue and stitch; the other arms stand where the scene
    /// starts them [default: the shipped scenarios/default.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    /// The arm whose tip moves over the grid: left, right, assist or camera.
    #[arg(long)]
    arm: ArmName,
    /// The grid's corner (cell 0, 0) x,y,z, m. With --plane-x, --plane-y and --plane-size it replaces
    /// the default plane (centred 2 cm above the stitch, parallel to the tissue, 6 cm square, axes
    /// along and across the wound).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3,
          requires_all = ["plane_x", "plane_y", "plane_size"])]
    plane_origin: Option<Vector3<f64>>,
    /// The grid's first axis x,y,z (cell index i).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, requires = "plane_origin")]
    plane_x: Option<Vector3<f64>>,
    /// The grid's second axis x,y,z (cell index j), perpendicular to the first.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, requires = "plane_origin")]
    plane_y: Option<Vector3<f64>>,
    /// The grid's side, m.
    #[arg(long, requires = "plane_origin")]
    plane_size: Option<f64>,
    /// Cells per side.
    #[arg(long, default_value_t = GridPlane::DEFAULT_CELLS)]
    cells: usize,
    /// Subcells per cell side.
    #[arg(long, default_value_t = GridPlane::DEFAULT_SUBCELLS)]
    subcells: usize,
    /// Hold the jaws this way x,y,z at every subcell (instruments); default: along the shaft.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3)]
    jaw_dir: Option<Vector3<f64>>,
    /// cpu or gpu.
    #[arg(long, value_enum, default_value_t = Backend::Cpu)]
    backend: Backend,
    /// Threads of the CPU backend, 1 to 1024 (default: one per core).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
    /// Directory for obstacles.csv and obstacles.png (created if missing).
    #[arg(long)]
    out: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// How the grid was computed.
struct Run {
    result: GridResult,
    backend: Backend,
    device: String,
    fallback: Option<String>,
    setup_ms: f64,
    elapsed_ms: f64,
    gpu_ms: Option<serde_json::Value>,
}

pub fn run(args: ObstaclesArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    match obstacles(&args, out) {
        Ok(()) => Ok(ExitCode::SUCCESS),
        Err(error) if args.json => {
            let text = format!("{error:#}");
            out.line(serde_json::to_string_pretty(&json!({ "ok": false, "error": text }))?);
            Ok(ExitCode::FAILURE)
        }
        Err(error) => Err(error),
    }
}

/// The scene's stitch point on the tissue surface and the wound's direction.
fn stitch(scene: &SceneConfig) -> (Vector3<f64>, Rotation3<f64>) {
    let world_from_tissue = knotlab_sim::tissue::Tissue::frame(&scene.tissue);
    let stitch = world_from_tissue * nalgebra::Point3::new(scene.stitch.along_m, 0.0, 0.0);
    (stitch.coords, world_from_tissue.rotation.to_rotation_matrix())
}

fn plane(args: &ObstaclesArgs, scene: &SceneConfig) -> anyhow::Result<(GridPlane, bool)> {
    match (args.plane_origin, args.plane_x, args.plane_y, args.plane_size) {
        (Some(origin), Some(u), Some(v), Some(size)) => {
            let plane = GridPlane::new(origin, u, v, size, args.cells, args.subcells)
                .context("--plane-origin/--plane-x/--plane-y/--plane-size/--cells/--subcells")?;
            Ok((plane, false))
        }
        _ => {
            let (point, rotation) = stitch(scene);
            let centre = point + rotation * Vector3::z() * DEFAULT_HEIGHT_M;
            let plane = GridPlane::centred(
                centre,
                rotation * Vector3::x(),
                rotation * Vector3::y(),
                DEFAULT_SIZE_M,
                args.cells,
                args.subcells,
            )
            .context("--cells/--subcells")?;
            Ok((plane, true))
        }
    }
}

fn trocar(scene: &SceneConfig, arm: ArmName) -> Vector3<f64> {
    let t = &scene.trocars;
    Vector3::from(match arm {
        ArmName::Left => t.left,
        ArmName::Right => t.right,
        ArmName::Assist => t.assist,
        ArmName::Camera => t.camera,
    })
}

/// The collision world: the rig at the scene's starting joints, the scene's obstacles.
fn collision_world(scene_name: &str, scene: &SceneConfig) -> anyhow::Result<CollisionWorld> {
    let rig = Rig::shipped().context("the shipped rig")?;
    let sim = SimWorld::new(scene.clone(), rig).with_context(|| scene_name.to_owned())?;
    let states: Vec<ArmState> = ArmName::ALL
        .iter()
        .map(|&name| ArmState { name, trocar_m: trocar(scene, name), joints: sim.arm(name).command })
        .collect();
    let mut world = CollisionWorld::from_rig(sim.rig(), &states)?;
    for (k, o) in scene.obstacles.iter().enumerate() {
        world
            .add_obstacle(
                &format!("obstacles[{k}]"),
                Vector3::from(o.centre_m),
                Vector3::from(o.half_extents_m),
            )
            .with_context(|| scene_name.to_owned())?;
    }
    Ok(world)
}

fn run_cpu(grid: &PreparedGrid, threads: Option<usize>, fallback: Option<String>) -> anyhow::Result<Run> {
    let start = Instant::now();
    let (result, device) = match threads {
        Some(n) => (thread_pool(n)?.install(|| compute_cpu(grid, false)), format!("cpu, {n} threads")),
        None => (compute_cpu(grid, false), format!("cpu, {} threads", rayon_threads())),
    };
    let elapsed_ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(Run { result, backend: Backend::Cpu, device, fallback, setup_ms: 0.0, elapsed_ms, gpu_ms: None })
}

/// Threads of the default pool (one per core).
fn rayon_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

#[cfg(feature = "gpu")]
fn run_gpu(grid: &PreparedGrid, threads: Option<usize>, out: &mut Output) -> anyhow::Result<Run> {
    use knotlab_learner::obstacles::gpu::{GpuContext, GpuError, GpuKernel, compute_gpu};
    let start = Instant::now();
    let ctx = match GpuContext::new() {
        Ok(ctx) => ctx,
        Err(error @ GpuError::NoAdapter { .. }) => {
            let reason = error.to_string();
            out.error(format!("warning: {reason}: computing on the CPU instead"));
            return run_cpu(grid, threads, Some(reason));
        }
        Err(error) => return Err(error.into()),
    };
    let kernel = GpuKernel::new(&ctx)?;
    let setup_ms = start.elapsed().as_secs_f64() * 1e3;
    let (result, t) = compute_gpu(&ctx, &kernel, grid, false)?;
    let gpu_ms = json!({
        "upload": t.upload_ms,
        "kernel": t.kernel_ms,
        "kernel_gpu_timestamps": t.kernel_gpu_ms,
        "readback": t.readback_ms,
    });
    Ok(Run {
        result,
        backend: Backend::Gpu,
        device: ctx.describe(),
        fallback: None,
        setup_ms,
        elapsed_ms: t.total_ms(),
        gpu_ms: Some(gpu_ms),
    })
}

#[cfg(not(feature = "gpu"))]
fn run_gpu(grid: &PreparedGrid, threads: Option<usize>, out: &mut Output) -> anyhow::Result<Run> {
    let reason = "this knotlab was built without the `gpu` feature".to_owned();
    out.error(format!("warning: {reason}: computing on the CPU instead"));
    run_cpu(grid, threads, Some(reason))
}

fn obstacles(args: &ObstaclesArgs, out: &mut Output) -> anyhow::Result<()> {
    let threads = args.threads.map(usize::from);
    let scene = shipped::scene(args.scene.as_deref(), &shipped::SCENE)?;
    let (plane, default_plane) = plane(args, &scene)?;
    let orientation = match args.jaw_dir {
        Some(d) => SubcellOrientation::JawDirection(d),
        None => SubcellOrientation::AlongShaft,
    };
    let world = collision_world(&scene_name(args), &scene)?;
    let request = GridRequest { arm: args.arm, plane, orientation };
    let prepare_start = Instant::now();
    let grid = PreparedGrid::new(&world, &request).context("--arm/--jaw-dir")?;
    let prepare_ms = prepare_start.elapsed().as_secs_f64() * 1e3;
    let mut run = match args.backend {
        Backend::Cpu => run_cpu(&grid, threads, None)?,
        Backend::Gpu => run_gpu(&grid, threads, out)?,
    };
    run.elapsed_ms += prepare_ms;
    std::fs::create_dir_all(&args.out).with_context(|| format!("creating --out {}", args.out.display()))?;
    let csv_path = args.out.join("obstacles.csv");
    let png_path = args.out.join("obstacles.png");
    write_cells(&csv_path, &run.result)?;
    std::fs::write(&png_path, picture(&run.result)?)
        .with_context(|| format!("writing {}", png_path.display()))?;
    report(args, &run, default_plane, &csv_path, &png_path, out)
}

/// The scene's name in messages and the report.
fn scene_name(args: &ObstaclesArgs) -> String {
    shipped::name(args.scene.as_deref(), &shipped::SCENE)
}

fn backend_name(backend: Backend) -> &'static str {
    match backend {
        Backend::Cpu => "cpu",
        Backend::Gpu => "gpu",
    }
}

fn report(
    args: &ObstaclesArgs,
    run: &Run,
    default_plane: bool,
    csv: &Path,
    png: &Path,
    out: &mut Output,
) -> anyhow::Result<()> {
    let r = &run.result;
    let p = &r.plane;
    let added = r.cells_blocked() - r.raw.count_blocked();
    if args.json {
        let orientation = match args.jaw_dir {
            Some(d) => json!({ "jaw_direction": [d.x, d.y, d.z] }),
            None => json!("along_shaft"),
        };
        let value = json!({
            "ok": true,
            "scene": scene_name(args),
            "arm": args.arm.as_str(),
            "backend": backend_name(run.backend),
            "device": run.device,
            "fallback": run.fallback,
            "plane": {
                "default": default_plane,
                "origin_m": [p.origin_m.x, p.origin_m.y, p.origin_m.z],
                "axis_x": [p.axis_u.x, p.axis_u.y, p.axis_u.z],
                "axis_y": [p.axis_v.x, p.axis_v.y, p.axis_v.z],
                "size_m": p.size_m,
                "cells": p.cells,
                "subcells": p.subcells,
            },
            "orientation": orientation,
            "cells": p.cells * p.cells,
            "cells_blocked": r.cells_blocked(),
            "cells_blocked_raw": r.raw.count_blocked(),
            "cells_added_by_fluid_rules": added,
            "cells_colliding": r.count(CellVerdict::Collides),
            "cells_unreachable": r.count(CellVerdict::Unreachable),
            "subcells_checked": r.subcells_checked,
            "subcells_collision_tested": r.subcells_collision_tested,
            "elapsed_ms": run.elapsed_ms,
            "setup_ms": run.setup_ms,
            "gpu_ms": run.gpu_ms,
            "files": { "csv": csv.display().to_string(), "png": png.display().to_string() },
        });
        out.line(serde_json::to_string_pretty(&value)?);
        return Ok(());
    }
    outln!(
        out,
        "arm {} on {} ({}); {} x {} cells of {} x {} subcells, {:.4} m square{}",
        args.arm,
        backend_name(run.backend),
        run.device,
        p.cells,
        p.cells,
        p.subcells,
        p.subcells,
        p.size_m,
        if default_plane { " (default plane: 2 cm above the stitch)" } else { "" }
    );
    outln!(out, "cells_blocked {}", r.cells_blocked());
    outln!(out, "subcells_checked {}", r.subcells_checked);
    outln!(out, "elapsed_ms {:.3}", run.elapsed_ms);
    outln!(
        out,
        "cells: {} colliding, {} unreachable, {} added by the fluid rules, {} free",
        r.count(CellVerdict::Collides),
        r.count(CellVerdict::Unreachable),
        added,
        p.cells * p.cells - r.cells_blocked()
    );
    if let Some(reason) = &run.fallback {
        outln!(out, "fell back to the CPU: {reason}");
    }
    outln!(out, "wrote {} and {}", csv.display(), png.display());
    Ok(())
}

/// Writes `i,j,x_m,y_m,z_m,verdict,virtual_obstacle,blocked` per cell: its centre in the world, what
/// its subcells found, whether it is a virtual obstacle, and whether it is blocked after the fluid
/// rules.
fn write_cells(path: &Path, r: &GridResult) -> anyhow::Result<()> {
    let n = r.plane.cells;
    let rows = r.cells.iter().enumerate().map(|(c, verdict)| {
        let (i, j) = (c % n, c / n);
        let centre = r.plane.cell_centre_m(i, j);
        let at = |x: f64| format!("{x:.6}");
        (
            i,
            j,
            at(centre.x),
            at(centre.y),
            at(centre.z),
            verdict.as_str(),
            u8::from(r.raw.blocked[c]),
            u8::from(r.mask.blocked[c]),
        )
    });
    let header = ["i", "j", "x_m", "y_m", "z_m", "verdict", "virtual_obstacle", "blocked"];
    csv_file::write_rows(path, &header, rows)
}

/// The grid as an RGB picture, +x to the right and +y up: free white, colliding red, unreachable grey,
/// cells added by the fluid rules orange; each cell a square of pixels (about 500 pixels a side).
fn picture(r: &GridResult) -> anyhow::Result<Vec<u8>> {
    let n = r.plane.cells;
    let scale = (500 / n).max(1);
    let side = n * scale;
    let mut pixels = Vec::with_capacity(side * side * 3);
    for row in 0..side {
        let j = n - 1 - row / scale;
        for col in 0..side {
            let c = j * n + col / scale;
            let rgb = match (r.cells[c], r.mask.blocked[c]) {
                (CellVerdict::Collides, _) => [220, 40, 40],
                (CellVerdict::Unreachable, _) => [110, 110, 110],
                (CellVerdict::Free, true) => [255, 165, 40],
                (CellVerdict::Free, false) => [255, 255, 255],
            };
            pixels.extend_from_slice(&rgb);
        }
    }
    let mut bytes = Vec::new();
    let size = u32::try_from(side).context("picture too large")?;
    let mut encoder = png::Encoder::new(&mut bytes, size, size);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().context("encoding the PNG")?;
    writer.write_image_data(&pixels).context("encoding the PNG")?;
    writer.finish().context("encoding the PNG")?;
    Ok(bytes)
}
