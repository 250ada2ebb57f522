//! The pull that draws the nominal suture through two flat parts closer together than its thickness,
//! at 6, 12 and 24 substeps:
//!
//! ```text
//! cargo run --release -p knotlab-sim --example pinch_probe
//! ```
//!
//! Two kinematic plates 10 mm square lie either side of a straight 40 mm strand of the default
//! scene's rope ([`knotlab_sim::validation::pinch`]), their faces apart by a fraction of the thread's
//! diameter at metal (1.1, 0.95, 0.9, 0.85, 0.8, 0.7) and of its diameter in its knots (0.85, 0.7), with
//! the scene's friction on metal. One end is held back with 0.02 N; after 1 s the other is pulled
//! harder and harder (0.02 to 10 N over 5 s) until the held end has moved 1 mm. A squeezed thread
//! should slide at a pull set by the squeeze and the friction, whatever the substep.

use knotlab_sim::rope::RopeParams;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;
use knotlab_sim::validation::pinch::slides_at_n;

/// The largest pull tried, N.
const MAX_N: f64 = 10.0;

fn main() {
    let extra: Vec<String> = std::env::args().skip(1).collect();
    if !extra.is_empty() {
        eprintln!(
            "pinch_probe: takes no arguments, got {extra:?} (usage: cargo run --release -p knotlab-sim --example pinch_probe)"
        );
        std::process::exit(2);
    }
    let scene = match parse_scene(include_str!("../../scenarios/default.toml"), "default.toml") {
        Ok(scene) => scene,
        Err(e) => {
            eprintln!("pinch_probe: the shipped scene: {e}");
            std::process::exit(1);
        }
    };
    let suture = match SutureUnderTest::from_scene(&scene) {
        Ok(suture) => suture,
        Err(e) => {
            eprintln!("pinch_probe: {e}");
            std::process::exit(1);
        }
    };
    println!(
        "the nominal suture ({:.3} mm across at metal, {:.2} mm in its knots, friction on metal {}), \
         drawn through two plates:",
        suture.diameter_at_metal_m() * 1e3,
        suture.diameter_m() * 1e3,
        suture.friction_on_metal
    );
    println!("| gap | 6 substeps | 12 substeps | 24 substeps |");
    println!("|---|---|---|---|");
    let at_metal = [1.1, 0.95, 0.9, 0.85, 0.8, 0.7].map(|f| (f, suture.diameter_at_metal_m(), "at metal"));
    let in_knots = [0.85, 0.7].map(|f| (f, suture.diameter_m(), "in its knots"));
    for (fraction, diameter_m, which) in at_metal.into_iter().chain(in_knots) {
        let gap_m = fraction * diameter_m;
        let cells: Vec<String> = [6, 12, 24]
            .iter()
            .map(|&substeps| {
                match slides_at_n(&suture, RopeParams { substeps, ..suture.params }, gap_m, MAX_N) {
                    Some(pull_n) => format!("{pull_n:.3} N"),
                    None => format!("held to {MAX_N} N"),
                }
            })
            .collect();
        println!("| {fraction} of its diameter {which} ({:.3} mm) | {} |", gap_m * 1e3, cells.join(" | "));
    }
}
