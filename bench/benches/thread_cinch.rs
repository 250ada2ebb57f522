//! Benchmark: how much tension the simulated thread's contacts hold before one strand passes through
//! another, the failure that undid the scripted expert's throws when it pulled them tight (issue 6).
//! A strand is wound twice round another (both ends held), as in a surgeon's throw, and its two ends
//! are pulled apart with a tension rising from 0 to 10 N over 5 s (`knotlab_sim::cinch`). Printed per
//! setting (the shipped scene's, then one change at a time): the tension at the first pass the
//! tunnelling monitor saw, and at which the winding had lost half a turn (or "held"), the passes counted, the deepest overlap of two segments' axes before the first pass as a
//! fraction of the touching distance, the winding at the start and the end (a pass takes a turn off),
//! and milliseconds per step on one core.
//!
//! `cargo bench -p knotlab-bench --bench thread_cinch`

use std::time::Instant;

use knotlab_sim::cinch::{CinchParams, run_cinch};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadParams;

const SCENE: &str = include_str!("../../scenarios/default.toml");

fn main() {
    let scene = match parse_scene(SCENE, "scenarios/default.toml") {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let (solver, thread) = (scene.solver, scene.thread);
    let pull = CinchParams { top_tension_n: 10.0, ramp_s: 5.0, ccd: false };
    let with = |solver: SolverParams| (solver, thread, pull);
    let half_segments = ThreadParams { segments: 2 * thread.segments, ..thread };
    let settings: Vec<(&str, (SolverParams, ThreadParams, CinchParams))> = vec![
        ("shipped scene", with(solver)),
        ("correction 0.1 m/s", with(SolverParams { max_corrective_speed_m_s: 0.1, ..solver })),
        ("correction 0.3 m/s", with(SolverParams { max_corrective_speed_m_s: 0.3, ..solver })),
        ("correction 3 m/s", with(SolverParams { max_corrective_speed_m_s: 3.0, ..solver })),
        ("16 iterations", with(SolverParams { solver_iterations: 16, ..solver })),
        ("dt 0.5 ms", with(SolverParams { dt_s: 0.5e-3, ..solver })),
        ("contacts 1 kHz", with(SolverParams { contact_frequency_hz: 1_000.0, ..solver })),
        ("contacts 10 kHz", with(SolverParams { contact_frequency_hz: 10_000.0, ..solver })),
        ("prediction 2 mm", with(SolverParams { prediction_distance_m: 0.002, ..solver })),
        ("CCD", (solver, thread, CinchParams { ccd: true, ..pull })),
        ("radius 0.5 mm", (solver, ThreadParams { radius_m: 0.0005, ..thread }, pull)),
        ("mass x10", (solver, ThreadParams { mass_kg: 10.0 * thread.mass_kg, ..thread }, pull)),
        ("half-length segments", (solver, half_segments, pull)),
    ];
    println!(
        "strand wound twice round another, ends pulled apart 0 -> {} N over {} s; one core",
        pull.top_tension_n, pull.ramp_s
    );
    println!(
        "| setting | first pass at | turn lost at | passes | deepest overlap before | turns start -> end | ms/step |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, (solver, thread, pull)) in &settings {
        let start = Instant::now();
        match run_cinch(solver, thread, pull) {
            Ok(o) => println!(
                "| {name} | {} | {} | {} | {:.0} % | {:.2} -> {:.2} | {:.3} |",
                o.first_pass_tension_n.map_or("held".to_owned(), |t| format!("{t:.2} N")),
                o.turn_lost_tension_n.map_or("held".to_owned(), |t| format!("{t:.2} N")),
                o.passes,
                100.0 * o.deepest_overlap,
                o.turns_start,
                o.turns_end,
                start.elapsed().as_secs_f64() * 1e3 / o.steps as f64
            ),
            Err(e) => println!("| {name} | unstable: {e} | | | | | |"),
        }
    }
}
