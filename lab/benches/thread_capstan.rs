//! Benchmark: does friction between simulated strands obey the capstan equation? A strand (B) wound
//! twice round another (A, both ends held), no gravity, is snugged with 1 N on both ends for 0.5 s;
//! then one end is pulled with 0.3 N (the holding test's load on a flap) and the other with less, for
//! 2 s (`knotlab_lab::cinch::run_capstan`). Friction should hold B while the ratio of the two tensions
//! stays below `exp(friction * 4 pi)` (6.6 at the scene's friction of 0.15, 43 at 0.3) and let it slide
//! beyond. Printed per thread model, friction and tension ratio: how far B slid in the 2 s, "to its
//! end" where it slid until its held end jammed against A, "off" where it slid off A altogether.
//!
//! Found with it: with the twist between segments free (`twist_free`, the default) B slides off
//! at a ratio of 2 whatever the friction, even at 1.0 (bound 290,000): a capsule 0.4 mm round spins at
//! the slightest torque, so strands roll over each other instead of sliding. Locking the twist holds
//! once every end is held as jaws hold it (no strand can spin as a whole): ratio 1.5 at friction
//! 0.15, 2 at 0.3, 3 at 1.0 (a few mm of settling), as the equation says, if short of its bound.
//! (Laid twisted between segments, the strands hold 2 at 0.15.)
//!
//! A second table lays the strand over a fixed 5 mm ball instead (half a turn, bound exp(friction *
//! pi)): at friction 0.15 and 0.3 it holds 0.8 of the bound and lets go at 0.95, at 1.0 it lets go
//! at half the bound. Against a rigid body the solver's friction is close to Coulomb's at the
//! scene's friction, so what the strand-on-strand wrap falls short by is the wrap's geometry: 3.1 mm
//! segments cannot lie round a strand 0.8 mm thick.
//!
//! `cargo bench -p knotlab-lab --bench thread_capstan`

use knotlab_lab::cinch::{
    BallCapstanParams, CapstanParams, capstan_ratio, run_capstan, run_capstan_over_ball,
};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::thread::ThreadParams;

/// B's loaded end, N; the other end gets this divided by each ratio.
const HIGH_N: f64 = 0.3;
const RATIOS: [f64; 5] = [1.2, 1.5, 2.0, 3.0, 5.0];

fn main() {
    let scene = knotlab_lab::scenes::chain_scene();
    let (solver, thread) = (scene.solver, scene.thread);
    println!(
        "strand wound twice round another, snugged at 1 N, then {HIGH_N} N on one end and {HIGH_N} N / ratio on the other for 2 s: how far it slid; one core"
    );
    let header: Vec<String> = RATIOS.iter().map(|r| format!("ratio {r}")).collect();
    println!("| twist | ends | friction (capstan bound) | {} |", header.join(" | "));
    println!("|---|---|---|{}", "---|".repeat(RATIOS.len()));
    let fine = ThreadParams {
        segments: 2 * thread.segments,
        bend_stiffness_n_m_per_rad: 2.0 * thread.bend_stiffness_n_m_per_rad,
        bend_damping_n_m_s_per_rad: 2.0 * thread.bend_damping_n_m_s_per_rad,
        ..thread
    };
    let fine_solver = SolverParams { solver_iterations: 2 * solver.solver_iterations, ..solver };
    let mut rows: Vec<(String, SolverParams, ThreadParams, bool)> = Vec::new();
    for twist_free in [true, false] {
        for held_as_jaws in [false, true] {
            rows.push((String::new(), solver, ThreadParams { twist_free, ..thread }, held_as_jaws));
        }
    }
    rows.push((
        " (1.56 mm segments)".to_owned(),
        fine_solver,
        ThreadParams { twist_free: false, ..fine },
        true,
    ));
    for (note, solver, strand, held_as_jaws) in rows {
        for friction in [thread.friction, 0.3, 1.0] {
            let strand = ThreadParams { friction, friction_on_itself: None, ..strand };
            let cells: Vec<String> = RATIOS
                .iter()
                .map(|ratio| {
                    let params = CapstanParams {
                        snug_n: 1.0,
                        snug_s: 0.5,
                        high_n: HIGH_N,
                        low_n: HIGH_N / ratio,
                        hold_s: 2.0,
                        held_as_jaws,
                    };
                    match run_capstan(&solver, &strand, &params) {
                        Ok(o) if o.turns_end < 1.0 => "off".to_owned(),
                        Ok(o) if o.slid_to_end => "to its end".to_owned(),
                        Ok(o) => format!("{:.1} mm", 1e3 * o.slip_m),
                        // A strand that slid off and flew away trips the speed check.
                        Err(_) => "off".to_owned(),
                    }
                })
                .collect();
            println!(
                "| {}{note} | {} | {friction} ({:.0}) | {} |",
                if strand.twist_free { "free" } else { "locked" },
                if held_as_jaws { "held as jaws" } else { "A pinned, B free" },
                capstan_ratio(friction),
                cells.join(" | ")
            );
        }
    }
    // The same law against a rigid body: the strand over a fixed ball, half a turn. Where this holds
    // close to the bound and the strand-on-strand wrap above does not, the solver's friction is not
    // what lets the wrap go.
    println!();
    println!(
        "the shipped strand over a fixed 5 mm ball (half a turn), snugged at {HIGH_N} N for 1 s, then {HIGH_N} N and {HIGH_N} N / ratio for 3 s: how far it slid (in the last 1.5 s); the capstan bound is exp(friction * pi)"
    );
    let fractions = [0.5, 0.8, 0.95, 1.2];
    let header: Vec<String> = fractions.iter().map(|f| format!("ratio {f} x bound")).collect();
    println!("| friction (bound) | {} |", header.join(" | "));
    println!("|---|{}", "---|".repeat(fractions.len()));
    for friction in [thread.friction, 0.3, 1.0] {
        let strand = ThreadParams { friction, friction_on_itself: None, ..thread };
        let bound = (friction * std::f64::consts::PI).exp();
        let cells: Vec<String> = fractions
            .iter()
            .map(|f| {
                let ratio = (f * bound).max(1.0);
                let params = BallCapstanParams {
                    ball_radius_m: 0.005,
                    high_n: HIGH_N,
                    snug_s: 1.0,
                    ratio,
                    hold_s: 3.0,
                };
                match run_capstan_over_ball(&solver, &strand, &params) {
                    Ok((_, _, true)) => format!("{ratio:.2}: to its end"),
                    Ok((slip, late, false)) => {
                        format!("{ratio:.2}: {:.1} mm ({:.2})", 1e3 * slip, 1e3 * late)
                    }
                    Err(_) => format!("{ratio:.2}: off"),
                }
            })
            .collect();
        println!("| {friction} ({bound:.2}) | {} |", cells.join(" | "));
    }
}
