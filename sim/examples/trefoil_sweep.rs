//! The trefoil of `knotlab validate` tightened at one friction after another, on a scene's suture:
//! the pull over the tightening law's force at each rest, beside how large the law's friction term
//! is against its elastic one there (`2 σ μ / ε`):
//!
//! ```text
//! cargo run --release -p knotlab-sim --example trefoil_sweep [SCENE [MU ...]]
//! ```
//!
//! SCENE defaults to `scenarios/default.toml`, the frictions to 0.05 0.1 0.15 0.2 0.3 0.4 0.5. The
//! law (`F h²/B = ε⁴/2 + μ σ ε³`) is the first order of a loose knot in its friction; where the
//! friction term outgrows the elastic one, how far the knot's pull departs from it says how far the
//! rope's knot goes beyond that order.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;
use knotlab_sim::validation::knot::{EPSILONS, MAX_REST_S, SIGMA, tighten};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().cloned().unwrap_or_else(|| "scenarios/default.toml".to_owned());
    let frictions: Vec<f64> = if args.len() > 1 {
        args[1..]
            .iter()
            .map(|a| match a.parse::<f64>() {
                Ok(mu) if mu.is_finite() && mu >= 0.0 => mu,
                _ => {
                    eprintln!("trefoil_sweep: MU must be a friction coefficient >= 0, got {a:?}");
                    std::process::exit(2);
                }
            })
            .collect()
    } else {
        vec![0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5]
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("trefoil_sweep: cannot read {path}: {e}");
            std::process::exit(2);
        }
    };
    let scene = match parse_scene(&text, &path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("trefoil_sweep: {e}");
            std::process::exit(2);
        }
    };
    let suture = match SutureUnderTest::from_scene(&scene) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("trefoil_sweep: {path}: {e}");
            std::process::exit(2);
        }
    };
    println!(
        "| mu | load for eps | eps at rest | 2 sigma mu / eps | pull over the law's force | s to rest |"
    );
    println!("|---|---|---|---|---|---|");
    for mu in frictions {
        match tighten(&suture, mu) {
            Ok(rests) => {
                for (rest, target) in rests.iter().zip(EPSILONS).skip(1) {
                    let still = if rest.rested_s < MAX_REST_S { "" } else { " (still moving)" };
                    println!(
                        "| {mu} | {target} | {:.3} | {:.2} | {:.3} | {:.0}{still} |",
                        rest.epsilon,
                        2.0 * SIGMA * mu / rest.epsilon,
                        rest.force_n / rest.law_n,
                        rest.rested_s
                    );
                }
            }
            Err(void) => println!("| {mu} | | | | {void} | |"),
        }
    }
}
