//! Benchmark: does the XPBD rope (`knotlab_sim::rope`) hold by friction what the Rapier capsule
//! chain lets slip? The chain's trials, run in the rope (0.2 mm radius, particles 0.3 mm apart,
//! 20 substeps of the 1 ms step, friction solved on positions):
//! - the capstan: a strand wound twice round another (both its ends pinned), snugged at 1 N, then
//!   0.3 N on one end and 0.3 N / ratio on the other for 2 s; friction should hold while the ratio
//!   stays below `exp(friction 4 pi)` (43 at 0.3, 535 at 0.5, 287,000 at 1.0). The chain slides
//!   11 mm at a ratio of 3 at friction 0.3, and 10 mm at 5, to its end at 10, at 1.0
//!   (`thread_capstan`).
//! - the reef trial: a loose square knot snugged by its four ends at 1 N, then its standing parts
//!   pulled apart with 0.3 N, the free ends let go, for 2 s. The chain's flat knots settle 0.5-14 mm
//!   at 0.5 and 5-25 mm or come apart at 1.0, erratically (`thread_reef`), and slide freely once
//!   its solver converges (session 42, `docs/knot-tying-notes.md`).
//!
//! Printed: how far each slid, in all and (in brackets) in the last half of the load, the reef's
//! knot after, and the wall time of each trial on one core.
//!
//! `cargo bench -p knotlab-bench --bench rope_knot` (about 3 minutes)

use std::time::Instant;

use knotlab_sim::rope::RopeParams;
use knotlab_sim::rope::trials::{Slide, capstan, reef};

const FRICTIONS: [f64; 3] = [0.3, 0.5, 1.0];
const RATIOS: [f64; 4] = [3.0, 10.0, 30.0, 100.0];
/// Loose-knot layouts: spread and lift, m.
const LAYOUTS: [(f64, f64); 4] = [(0.003, 0.0015), (0.004, 0.0015), (0.005, 0.002), (0.003, 0.001)];

fn cell(slide: &Slide, seconds: f64) -> String {
    format!("{:.2} mm ({:.2}), {seconds:.1} s", slide.slip_m * 1e3, slide.late_slip_m * 1e3)
}

fn main() {
    let params = |friction: f64| RopeParams {
        static_friction: friction,
        kinetic_friction: 0.8 * friction,
        ..RopeParams::default()
    };
    println!(
        "capstan: a strand wound twice round another, 0.3 N against 0.3 N / ratio for 2 s: slip (last second), wall time"
    );
    let header: Vec<String> = RATIOS.iter().map(|r| format!("ratio {r}")).collect();
    println!("| friction (static; kinetic 0.8 of it) | bound | {} |", header.join(" | "));
    println!("|---|---|{}", "---|".repeat(RATIOS.len()));
    for friction in FRICTIONS {
        let cells: Vec<String> = RATIOS
            .iter()
            .map(|ratio| {
                let start = Instant::now();
                let slide = capstan(params(friction), 0.3, *ratio);
                cell(&slide, start.elapsed().as_secs_f64())
            })
            .collect();
        let bound = (friction * 4.0 * std::f64::consts::PI).exp();
        println!("| {friction} | {bound:.0} | {} |", cells.join(" | "));
    }
    println!();
    println!(
        "reef: a loose square knot snugged at 1 N, then 0.3 N on its standing parts for 2 s, free ends let go: the standing parts drew apart (last second), knot after, wall time"
    );
    let header: Vec<String> =
        LAYOUTS.iter().map(|(s, l)| format!("spread {:.0} mm, lift {:.1} mm", s * 1e3, l * 1e3)).collect();
    println!("| friction | {} |", header.join(" | "));
    println!("|---|{}", "---|".repeat(LAYOUTS.len()));
    for friction in FRICTIONS {
        let cells: Vec<String> = LAYOUTS
            .iter()
            .map(|(spread_m, lift_m)| {
                let start = Instant::now();
                let slide = reef(params(friction), *spread_m, *lift_m, 1.0, 0.3, 2.0);
                let knot = slide.knot_after.map_or("unclassified", |k| k.name());
                format!("{}, {knot}", cell(&slide, start.elapsed().as_secs_f64()))
            })
            .collect();
        println!("| {friction} | {} |", cells.join(" | "));
    }
}
