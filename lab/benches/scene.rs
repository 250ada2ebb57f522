//! Benchmark: the full scene (four arms through their servos, the thread through the stitch, tissue
//! flaps on their springs, needle, grasps) running the `knotlab sim` stress sequence, on one core
//! (Rapier runs single-threaded here). For each discretisation of the thread and the solver, printed:
//! the real-time factor (simulated seconds per wall second), ms per step, the worst joint gap as a
//! fraction of a segment, tunnelling events and health failures. Target: 5x real time.
//!
//! `cargo bench -p knotlab-lab --bench scene` (the shipped scene's speed alone: `cargo bench -p
//! knotlab-bench --bench scene_step`)

use knotlab_hw::rig::Rig;
use knotlab_scenarios::stress::run_stress;
use knotlab_sim::world::SimWorld;

const SECONDS: f64 = 6.0;

fn main() {
    let rig = match Rig::shipped() {
        Ok(rig) => rig,
        Err(e) => {
            eprintln!("the shipped rig: {e}");
            std::process::exit(1);
        }
    };
    println!("full scene, stress sequence of {SECONDS} s simulated, one core");
    println!(
        "| segments | dt ms | iterations x sweeps | real time x | ms/step | max stretch % | tunnelling | failures |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    // (segments, dt, solver iterations, Gauss-Seidel sweeps): the shipped default first.
    let points = [
        (40, 1.0, 8, 4),
        (40, 1.0, 4, 4),
        (40, 1.0, 4, 2),
        (40, 2.0, 8, 4),
        (40, 1.0, 16, 4),
        (30, 1.0, 8, 4),
        (60, 1.0, 8, 4),
        (60, 1.0, 16, 4),
    ];
    for (segments, dt_ms, iterations, sweeps) in points {
        let mut scene = knotlab_bench::shipped_scene();
        scene.thread.segments = segments;
        scene.solver.dt_s = dt_ms * 1e-3;
        scene.solver.solver_iterations = iterations;
        scene.solver.pgs_iterations_per_substep = sweeps;
        let mut world = match SimWorld::new(scene, rig.clone()) {
            Ok(w) => w,
            Err(e) => {
                println!("| {segments} | {dt_ms} | {iterations} x {sweeps} | scene refused: {e} |");
                continue;
            }
        };
        let report = run_stress(&mut world, SECONDS, &[], &mut |_, _| {});
        println!(
            "| {segments} | {dt_ms} | {iterations} x {sweeps} | {:.2} | {:.3} | {:.2} | {} | {} |",
            report.realtime_factor,
            1e3 * report.wall_s / report.steps.max(1) as f64,
            100.0 * report.max_stretch_ratio,
            report.tunnelling_events,
            report.failure.as_deref().unwrap_or("none"),
        );
    }
}
