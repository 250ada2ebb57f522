//! Benchmark: does a snug throw hold once its free ends are let go? A strand (B) wound twice round
//! another (A), as in a surgeon's throw, no gravity, is snugged with both of B's ends pulled at 1 N
//! while A's ends are held; then the loop pulls B's other end with a set tension for 2 s while A's
//! loop end stays held, and the free ends (A's other end, B's other end) are let go or kept
//! (`knotlab_lab::cinch::run_holding`). With both let go this is the knot as the instruments leave
//! it when the holding test loads it (0.3 N a flap). Printed per thread model, friction and loop
//! tension, for each choice of free ends let go: how far the loaded end moved in the 2 s (in the last
//! second), or "off" where the turns came undone. Found: with its free ends held the throw
//! holds (a few mm of settling); with both let go it slides off under 0.05 N at every friction (0.15
//! to 1.0) and segment length (3.1, 1.56, 0.78 mm). A wrap whose one end is slack cannot hold the
//! other (the capstan equation), so a first throw let go holds nothing: the second throw must. Laid
//! untwisted it also holds with only A's free end let go (B's held, 0.2-0.8 mm, 4.6 mm
//! at 0.78 mm segments and friction 1.0); with B's let go it comes off, as with both.
//!
//! `cargo bench -p knotlab-lab --bench thread_holding`

use knotlab_lab::cinch::{HoldingParams, run_holding};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::thread::ThreadParams;

/// (A's free end let go, B's free end let go), as the columns go.
const RELEASES: [(bool, bool, &str); 4] =
    [(false, false, "none"), (true, false, "A's"), (false, true, "B's"), (true, true, "both")];

/// One thread model of the table and what it is tried with.
struct Row<'a> {
    name: &'a str,
    solver: SolverParams,
    strand: ThreadParams,
    frictions: &'a [f64],
    loops: &'a [f64],
}

fn main() {
    let scene = knotlab_lab::scenes::chain_scene();
    let (solver, thread) = (scene.solver, scene.thread);
    println!(
        "strand B wound twice round A, snugged at 1 N for 0.5 s; then the loop pulls B's other end for 2 s with A's loop end held, the free ends let go or kept: how far the loaded end moved (in the last second); one core"
    );
    let header: Vec<String> = RELEASES.iter().map(|(_, _, name)| format!("let go: {name}")).collect();
    println!("| thread | friction | loop | {} |", header.join(" | "));
    println!("|---|---|---|{}", "---|".repeat(RELEASES.len()));
    // Shorter segments, more solver iterations.
    let finer =
        |k: usize, iterations: usize| knotlab_lab::scenes::finer_thread(&solver, &thread, k, iterations);
    let (solver_2, thread_2) = finer(2, 2);
    let (solver_4, thread_4) = finer(4, 4);
    let all = [thread.friction, 0.3, 1.0];
    let rows = [
        Row {
            name: "shipped (3.1 mm segments)",
            solver,
            strand: thread,
            frictions: &all,
            loops: &[0.05, 0.3],
        },
        Row {
            name: "1.56 mm segments",
            solver: solver_2,
            strand: thread_2,
            frictions: &all,
            loops: &[0.05, 0.3],
        },
        // Slow (about 9 s a cell): the lightest load only.
        Row {
            name: "0.78 mm segments",
            solver: solver_4,
            strand: thread_4,
            frictions: &[thread.friction, 1.0],
            loops: &[0.05],
        },
    ];
    for Row { name, solver, strand, frictions, loops } in rows {
        for &friction in frictions {
            for &loop_n in loops {
                let strand = ThreadParams { friction, friction_on_itself: None, ..strand };
                let cells: Vec<String> = RELEASES
                    .iter()
                    .map(|&(release_a, release_b, _)| {
                        let params = HoldingParams {
                            snug_n: 1.0,
                            snug_s: 0.5,
                            loop_n,
                            hold_s: 2.0,
                            release_a,
                            release_b,
                        };
                        match run_holding(&solver, &strand, &params) {
                            Ok(o) if o.turns_end < 1.0 => format!("off ({:.1} turns)", o.turns_end),
                            Ok(o) => format!("{:.1} mm ({:.1})", 1e3 * o.slip_m, 1e3 * o.late_slip_m),
                            // A strand that slid off and flew away trips the speed check.
                            Err(_) => "off (flew)".to_owned(),
                        }
                    })
                    .collect();
                println!("| {name} | {friction} | {loop_n} N | {} |", cells.join(" | "));
            }
        }
    }
}
