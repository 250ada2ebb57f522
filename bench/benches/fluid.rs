//! Benchmark: the fluid solver's time per step at 50 x 50, 128 x 128 and 256 x 256 cells with the SOR
//! reference and the factor-once sparse Cholesky solve, and the time to instantiate the knot's 2D
//! primitive (a double wrap 2.4 cm across at 2 cm/s) on a 50 x 50 grid (target: at most 50 ms, one core).
//!
//! `cargo bench -p knotlab-bench --bench fluid` prints the tables. Steps are timed on a developed
//! lid-driven cavity flow at Re 1000 (started from rest and run to t = 1 first), each solver warm-started
//! by a few untimed steps; both solve to the same divergence tolerance. Medians over repetitions (robust
//! to the odd preempted run on a shared machine). Everything runs on one thread. Beside the wall-clock
//! time, the instantiation table gives the thread's CPU time (Linux `/proc/thread-self/schedstat`), which
//! leaves out the time the thread waited for a core that other processes held.

use std::hint::black_box;
use std::time::Instant;

use knotlab_learner::fluid::{
    DonorCell, FluidParams, FluidSim, GridRegion, InstantiateSettings, ObstacleMask, PlanarDemonstration,
    PlaneFrame, PressureSolverKind, SpeedPath, Walls, instantiate,
};
use nalgebra::{Isometry3, Vector2};

/// The divergence tolerance of every pressure solve here, 1/s (the cavity's validation uses 1e-8).
const TOLERANCE: f64 = 1e-8;

/// CPU time of this thread so far, s (None where the kernel does not tell).
fn thread_cpu_s() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

fn params(re: f64, solver: PressureSolverKind) -> FluidParams {
    FluidParams {
        viscosity_m2ps: 1.0 / re,
        donor_cell: DonorCell::Local { factor: 1.0 },
        tau: 0.8,
        divergence_tol_per_s: TOLERANCE,
        solver,
        max_sor_iterations: 1_000_000,
    }
}

fn cavity(n: usize, solver: PressureSolverKind) -> Result<FluidSim, Box<dyn std::error::Error>> {
    let walls = Walls { top_u_mps: 1.0, ..Walls::default() };
    Ok(FluidSim::new(&ObstacleMask::free(n), 1.0 / n as f64, walls, params(1000.0, solver))?)
}

/// Per-step time (ms) and SOR iterations per step, on a copy of `developed`'s velocities.
fn time_steps(
    n: usize,
    solver: PressureSolverKind,
    u: &[f64],
    v: &[f64],
    steps: usize,
) -> Result<(f64, f64, f64), Box<dyn std::error::Error>> {
    let start = Instant::now();
    let mut sim = cavity(n, solver)?;
    let setup_ms = start.elapsed().as_secs_f64() * 1e3;
    sim.set_velocities(u.to_vec(), v.to_vec())?;
    for _ in 0..3 {
        sim.step(sim.stable_dt())?;
    }
    let mut times = Vec::new();
    let mut iterations = 0;
    for _ in 0..steps {
        let dt = sim.stable_dt();
        let start = Instant::now();
        let report = black_box(sim.step(dt)?);
        times.push(start.elapsed().as_secs_f64() * 1e3);
        iterations += report.pressure_iterations;
        assert!(report.max_divergence_per_s <= TOLERANCE);
    }
    Ok((median(times), iterations as f64 / steps as f64, setup_ms))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "fluid step, lid-driven cavity Re 1000 developed to t = 1, divergence tolerance {TOLERANCE:.0e}, one thread"
    );
    println!("{:>9} {:>8} {:>12} {:>14} {:>12}", "grid", "solver", "ms/step", "iter/step", "setup ms");
    for n in [50, 128, 256] {
        let mut developed = cavity(n, PressureSolverKind::Direct)?;
        while developed.time_s() < 1.0 {
            developed.step(developed.stable_dt())?;
        }
        let (u, v) = (developed.u().to_vec(), developed.v().to_vec());
        for solver in [PressureSolverKind::Direct, PressureSolverKind::Sor] {
            let steps = match (solver, n) {
                (PressureSolverKind::Direct, _) => 51,
                (PressureSolverKind::Sor, 256) => 5,
                (PressureSolverKind::Sor, _) => 11,
            };
            let (ms, iterations, setup) = time_steps(n, solver, &u, &v, steps)?;
            println!(
                "{:>9} {:>8} {ms:>12.3} {iterations:>14.1} {setup:>12.2}",
                format!("{n}x{n}"),
                solver.name()
            );
        }
    }

    println!();
    println!(
        "2D primitive: the knot's double wrap (2.4 cm across, 2 cm/s, 8.2 s) on 50 x 50 cells, one thread"
    );
    let path = SpeedPath::double_loop(Vector2::zeros(), 0.012, 0.02)?;
    let region = GridRegion::around(&path.points_m, 50, 0.006)?;
    let demo = PlanarDemonstration { plane: PlaneFrame::horizontal(0.85), path };
    let site = Isometry3::translation(0.05, -0.02, 0.0);
    let mut blocked = ObstacleMask::free(50);
    region.block_box(&mut blocked, Vector2::new(-0.003, -0.03), Vector2::new(0.003, -0.008));
    println!(
        "{:>22} {:>8} {:>12} {:>10} {:>12} {:>8}",
        "case", "solver", "median ms", "p90 ms", "median cpu ms", "steps"
    );
    for (case, mask) in [("free space", ObstacleMask::free(50)), ("obstacle across path", blocked)] {
        for solver in [PressureSolverKind::Direct, PressureSolverKind::Sor] {
            let settings = InstantiateSettings { solver, ..InstantiateSettings::default() };
            let runs = if solver == PressureSolverKind::Direct { 41 } else { 5 };
            let mut times = Vec::new();
            let mut cpu = Vec::new();
            let mut steps = 0;
            for _ in 0..runs {
                let cpu_start = thread_cpu_s();
                let start = Instant::now();
                let inst = black_box(instantiate(&demo, &site, &region, &mask, &settings)?);
                times.push(start.elapsed().as_secs_f64() * 1e3);
                if let (Some(a), Some(b)) = (cpu_start, thread_cpu_s()) {
                    cpu.push((b - a) * 1e3);
                }
                steps = inst.report.steps;
            }
            times.sort_by(f64::total_cmp);
            let p90 = times[(times.len() - 1) * 9 / 10];
            let cpu = if cpu.is_empty() { "n/a".to_owned() } else { format!("{:.1}", median(cpu)) };
            println!(
                "{case:>22} {:>8} {:>12.1} {p90:>10.1} {cpu:>13} {steps:>8}",
                solver.name(),
                median(times.clone())
            );
        }
    }
    println!("target: at most 50 ms per instantiation (direct solver)");
    Ok(())
}
