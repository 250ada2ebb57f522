//! A long overhand knot of `knotlab validate` (the (2, 2n+1) torus knot laid loose) seated under
//! the long-knot law's loose load, then pulled by its ends with a load raised steadily to LOAD_N
//! over a minute: each second the pull, the shortening, the most stretched segment, the knot the
//! classifier reads, where it sits along the rope (the middle of its crossings, from the first
//! end) and the pairs of segments the crossing watch counted passing through each other. It shows
//! whether a knot pulled tight keeps its type and its place on the rope:
//!
//! ```text
//! cargo run --release -p knotlab-sim --example long_knot_overload [SCENE [TURNS [LOAD_N]]]
//! ```
//!
//! SCENE defaults to `scenarios/default.toml`, TURNS to 2 (the surgeon's double throw), LOAD_N to
//! 3 (the shipped expert's snug on each end).

mod common;

use knotlab_sim::knot::classify::classify;
use knotlab_sim::rope::{RopeParams, Ropes};
use knotlab_sim::validation::long_knot::{N2H_OVER_E, law_n, open_long_knot};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().cloned().unwrap_or_else(|| "scenarios/default.toml".to_owned());
    let turns = match args.get(1).map(|a| a.parse::<usize>()) {
        None => 2,
        Some(Ok(n)) if (1..=6).contains(&n) => n,
        Some(_) => {
            eprintln!("long_knot_overload: TURNS must be a whole number from 1 to 6, got {:?}", args[1]);
            std::process::exit(2);
        }
    };
    let top_n = match args.get(2).map(|a| a.parse::<f64>()) {
        None => 3.0,
        Some(Ok(f)) if f.is_finite() && f > 0.0 && f <= 100.0 => f,
        Some(_) => {
            eprintln!("long_knot_overload: LOAD_N must be a force in (0, 100] N, got {:?}", args[2]);
            std::process::exit(2);
        }
    };
    let suture = common::suture_of_scene(&path, "long_knot_overload");
    let (h, b, mu) = (suture.params.radius_m, suture.bending_stiffness_n_m2(), suture.params.static_friction);
    let params = RopeParams { damping_per_s: 0.5, kinetic_friction: 0.8 * mu, ..suture.params };
    let mut ropes = Ropes::new(params);
    let strand = ropes.add_strand_along(&open_long_knot(turns, h), suture.spacing_m);
    let (first, last) = (strand.start, strand.end - 1);
    let length_m: f64 = ropes.polyline(0).windows(2).map(|p| (p[1] - p[0]).norm()).sum();
    let along = (ropes.x[last] - ropes.x[first]).normalize();
    let n2 = (turns * turns) as f64;
    let seat_n = law_n(turns, n2 * h / N2H_OVER_E[0], h, b, mu).unwrap_or(0.0);
    let steps_per_s = (1.0 / suture.dt_s).round() as usize;
    let (seat_s, ramp_s): (usize, usize) = (10, 60);
    println!(
        "| s | pull, N | shortening, mm | most stretched segment | knot (determinant) | knot's place, mm | pairs crossed in that second |"
    );
    println!("|---|---|---|---|---|---|---|");
    for second in 1..=seat_s + ramp_s + 10 {
        let ramp = (second.saturating_sub(seat_s) as f64 / ramp_s as f64).min(1.0);
        let pull_n = seat_n + (top_n - seat_n) * ramp;
        ropes.force_n[first] = -along * pull_n;
        ropes.force_n[last] = along * pull_n;
        let mut crossed = Vec::new();
        for _ in 0..steps_per_s {
            ropes.step(suture.dt_s);
            crossed.extend_from_slice(ropes.crossed_last_step());
        }
        let (knot, place) = classify(&ropes.polyline(0)).map_or_else(
            |e| (format!("({e})"), String::new()),
            |c| {
                let place = c
                    .span
                    .as_ref()
                    .map_or_else(String::new, |s| format!("{:.1}", (s.start_m + s.end_m) * 0.5e3));
                (format!("{} ({:?})", c.knot, c.determinant), place)
            },
        );
        println!(
            "| {second} | {pull_n:.3} | {:.1} | {:.3} | {knot} | {place} | {} |",
            (length_m - (ropes.x[last] - ropes.x[first]).norm()) * 1e3,
            ropes.max_stretch_ratio(),
            crossed.len()
        );
    }
}
