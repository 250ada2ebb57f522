//! Benchmark: how much tension the simulated thread's contacts hold before one strand passes through
//! another, the failure that undoes the scripted expert's throws in the chain when it pulls them tight.
//! A strand is wound twice round another (both ends held), as in a surgeon's throw, and its two ends
//! are pulled apart with a tension rising from 0 to 10 N over 5 s (`knotlab_lab::cinch`). Printed per
//! setting (the chain scene's, scenarios/chain.toml, then one change at a time): the tension at the first pass the
//! tunnelling monitor saw, and at which the winding had lost half a turn (or "held"), the passes
//! counted, the deepest overlap of two segments' axes before the first pass as a fraction of the
//! touching distance, the winding at the start and the end (a pass takes a turn off), and
//! milliseconds per step on one core. A second table pulls the same strand to 2 N and prints how tight
//! its turns lie, by segment length: at the shipped 3.1 mm the turns' joints lie 1.77 mm from the
//! other strand's axis (touching: 0.8 mm), at 1.56 mm 1.08 mm, at 0.78 mm 0.83 mm, at 4 and 18 times
//! the cost of a step. With the twist between segments locked (as scenarios/chain.toml has it) the chain
//! scene's wrap loses a turn at 6.0 N (6.4 N laid twisted between segments; 5.9 N with the twist
//! free).
//!
//! `cargo bench -p knotlab-lab --bench thread_cinch`

use std::time::Instant;

use knotlab_lab::cinch::{CinchParams, run_cinch};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::thread::ThreadParams;

fn main() {
    let scene = knotlab_lab::scenes::chain_scene();
    let (solver, thread) = (scene.solver, scene.thread);
    let pull = CinchParams { top_tension_n: 10.0, ramp_s: 5.0, ccd: false };
    let with = |solver: SolverParams| (solver, thread, pull);
    let half_segments = ThreadParams { segments: 2 * thread.segments, ..thread };
    let settings: Vec<(&str, (SolverParams, ThreadParams, CinchParams))> = vec![
        ("chain scene", with(solver)),
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
    // How tight the turns can lie: a segment much longer than a tight turn's circumference (about 5 mm
    // round a 0.8 mm strand) cannot follow it.
    let snug = CinchParams { top_tension_n: 2.0, ramp_s: 1.0, ccd: false };
    let segments_of = |n: usize, iterations: usize| {
        (SolverParams { solver_iterations: iterations, ..solver }, ThreadParams { segments: n, ..thread })
    };
    println!();
    println!(
        "the same wound strand pulled to {} N over {} s: how tight the turns lie at the end",
        snug.top_tension_n, snug.ramp_s
    );
    println!(
        "| segment length | iterations | turns end | median radius of the turns | thread in the turns | ms/step |"
    );
    println!("|---|---|---|---|---|---|");
    for (segments, iterations) in
        [(thread.segments, solver.solver_iterations), (2 * thread.segments, 16), (4 * thread.segments, 32)]
    {
        let (solver, thread) = segments_of(segments, iterations);
        let start = Instant::now();
        match run_cinch(&solver, &thread, &snug) {
            Ok(o) => println!(
                "| {:.2} mm | {iterations} | {:.2} | {} | {:.1} mm | {:.3} |",
                thread.segment_length_m() * 1e3,
                o.turns_end,
                o.wrap_radius_m.map_or("-".to_owned(), |r| format!("{:.2} mm", r * 1e3)),
                o.wrap_length_m * 1e3,
                start.elapsed().as_secs_f64() * 1e3 / o.steps as f64
            ),
            Err(e) => {
                println!("| {:.2} mm | {iterations} | unstable: {e} | | | |", thread.segment_length_m() * 1e3)
            }
        }
    }
}
