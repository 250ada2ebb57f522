//! Benchmark: the fluid solver's time per step at 50 x 50, 128 x 128 and 256 x 256 cells with the SOR
//! reference and the factor-once sparse Cholesky solve, and the time to instantiate the knot's 2D
//! primitive (a double wrap 2.4 cm across at 2 cm/s) on a 50 x 50 grid (target: at most 50 ms, one core).
//!
//! `cargo bench -p knotlab-bench --bench fluid` times them with divan. Steps are timed on a developed
//! lid-driven cavity flow at Re 1000 (started from rest and run to t = 1 first), each solver warm-started
//! by a few untimed steps; both solve to the same divergence tolerance. Everything runs on one thread.

use std::hint::black_box;

use knotlab_learner::fluid::{
    DonorCell, FluidParams, FluidSim, GridRegion, InstantiateSettings, ObstacleMask, PlanarDemonstration,
    PlaneFrame, PressureSolverKind, SpeedPath, Walls, instantiate,
};
use nalgebra::{Isometry3, Vector2};

/// The divergence tolerance of every pressure solve here, 1/s (the cavity's validation uses 1e-8).
const TOLERANCE: f64 = 1e-8;

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

fn main() {
    divan::main();
}

/// The grids and pressure solvers of the step's table: `cells solver`.
const STEPS: [&str; 6] = ["50 direct", "50 sor", "128 direct", "128 sor", "256 direct", "256 sor"];

/// One step of the lid-driven cavity at Re 1000, developed to t = 1 and warm-started by three
/// untimed steps, to the divergence tolerance.
#[divan::bench(args = STEPS, sample_count = 10, sample_size = 1)]
fn cavity_step(bencher: divan::Bencher, case: &str) {
    let (cells, solver) = case.split_once(' ').expect("cells and solver");
    let n: usize = cells.parse().expect("a cell count");
    let solver = if solver == "sor" { PressureSolverKind::Sor } else { PressureSolverKind::Direct };
    let mut developed = cavity(n, PressureSolverKind::Direct).expect("the cavity");
    while developed.time_s() < 1.0 {
        developed.step(developed.stable_dt()).expect("a step");
    }
    let mut sim = cavity(n, solver).expect("the cavity");
    sim.set_velocities(developed.u().to_vec(), developed.v().to_vec()).expect("its velocities");
    for _ in 0..3 {
        sim.step(sim.stable_dt()).expect("a step");
    }
    bencher.bench_local(|| {
        let report = black_box(sim.step(sim.stable_dt()).expect("a step"));
        assert!(report.max_divergence_per_s <= TOLERANCE);
    });
}

/// The obstacles of the instantiation's table.
const MASKS: [&str; 2] = ["free space", "obstacle across path"];

/// Instantiating the knot's 2D primitive (a double wrap 2.4 cm across at 2 cm/s, 8.2 s) at a moved
/// site on 50 x 50 cells, with the direct pressure solve.
#[divan::bench(args = MASKS, sample_count = 20, sample_size = 1)]
fn instantiate_double_wrap(bencher: divan::Bencher, mask: &str) {
    let path = SpeedPath::double_loop(Vector2::zeros(), 0.012, 0.02).expect("the path");
    let region = GridRegion::around(&path.points_m, 50, 0.006).expect("the region");
    let demo = PlanarDemonstration { plane: PlaneFrame::horizontal(0.85), path };
    let site = Isometry3::translation(0.05, -0.02, 0.0);
    let mut obstacles = ObstacleMask::free(50);
    if mask != "free space" {
        region.block_box(&mut obstacles, Vector2::new(-0.003, -0.03), Vector2::new(0.003, -0.008));
    }
    let settings =
        InstantiateSettings { solver: PressureSolverKind::Direct, ..InstantiateSettings::default() };
    bencher.bench_local(|| {
        black_box(instantiate(&demo, &site, &region, &obstacles, &settings).expect("an instantiation"))
    });
}
