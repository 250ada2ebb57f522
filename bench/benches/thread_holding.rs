//! Benchmark: does a snug throw hold once its free ends are let go? A strand (B) wound twice round
//! another (A), as in a surgeon's throw, no gravity, is snugged with both of B's ends pulled at 1 N
//! while A's ends are held; then the loop pulls B's other end with a set tension for 2 s while A's
//! loop end stays held, and the free ends (A's other end, B's other end) are let go or kept
//! (`knotlab_sim::cinch::run_holding`). With both let go this is the knot as the instruments leave
//! it when the holding test loads it (0.3 N a flap). Printed per thread model, friction and loop
//! tension, for each choice of free ends let go: how far the loaded end moved in the 2 s (in the last
//! second), or "off" where the turns came undone.
//!
//! `cargo bench -p knotlab-bench --bench thread_holding`

use knotlab_sim::cinch::{HoldingParams, run_holding};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::thread::ThreadParams;

/// (A's free end let go, B's free end let go), as the columns go.
const RELEASES: [(bool, bool, &str); 4] =
    [(false, false, "none"), (true, false, "A's"), (false, true, "B's"), (true, true, "both")];

fn main() {
    let scene = knotlab_bench::shipped_scene();
    let (solver, thread) = (scene.solver, scene.thread);
    println!(
        "strand B wound twice round A, snugged at 1 N for 0.5 s; then the loop pulls B's other end for 2 s with A's loop end held, the free ends let go or kept: how far the loaded end moved (in the last second); one core"
    );
    let header: Vec<String> = RELEASES.iter().map(|(_, _, name)| format!("let go: {name}")).collect();
    println!("| thread | friction | loop | {} |", header.join(" | "));
    println!("|---|---|---|{}", "---|".repeat(RELEASES.len()));
    let fine = ThreadParams {
        segments: 2 * thread.segments,
        bend_stiffness_n_m_per_rad: 2.0 * thread.bend_stiffness_n_m_per_rad,
        bend_damping_n_m_s_per_rad: 2.0 * thread.bend_damping_n_m_s_per_rad,
        ..thread
    };
    let fine_solver = SolverParams { solver_iterations: 2 * solver.solver_iterations, ..solver };
    let rows = [("shipped (3.1 mm segments)", solver, thread), ("1.56 mm segments", fine_solver, fine)];
    for (name, solver, strand) in rows {
        for friction in [thread.friction, 0.3, 1.0] {
            for loop_n in [0.05, 0.3] {
                let strand = ThreadParams { friction, ..strand };
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
