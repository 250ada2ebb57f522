//! Benchmark: does the XPBD rope (`knotlab_sim::rope`) hold by friction what the Rapier capsule
//! chain lets slip? Two ropes, both 0.2 mm in radius, particles 0.3 mm apart, 20 substeps of the
//! 1 ms step, friction solved on positions: `string` (no bending stiffness, lengths by
//! two Gauss-Seidel sweeps) and `stiff` (the default: a suture's bending stiffness, EI 1e-7 N m²,
//! lengths solved directly). The chain's trials, in each:
//! - the capstan: a strand wound twice round another (both its ends pinned), snugged at 1 N, then
//!   0.3 N on one end and 0.3 N / ratio on the other for 2 s; friction should hold while the ratio
//!   stays below `exp(friction 4 pi)` (43 at 0.3, 535 at 0.5, 287,000 at 1.0). The chain slides
//!   11 mm at a ratio of 3 at friction 0.3, and 10 mm at 5, to its end at 10, at 1.0
//!   (`thread_capstan`).
//! - the reef trial: a loose square knot snugged by its four ends at 1 N, then its standing parts
//!   pulled apart with 0.3 N, the free ends let go, for 2 s. The chain's flat knots settle 0.5-14 mm
//!   at 0.5 and 5-25 mm or come apart at 1.0 (`thread_reef`).
//! - the laid-knot trial in the wound (`knotlab_lab::wound`): `laid_knot`'s surgeon's knot over
//!   the stitch of `scenarios/short-suture-friction-0.5.toml`, laid loose (nine layouts, 4 mm up) and
//!   tight (six layouts, 1 mm up), snugged by its free ends at 2 N for 6 s, then the holding test (0.3 N a flap
//!   for 1 s), the rope damped at 10/s. The chain leaves the wound 2.3-19.3 mm open (median 16;
//!   `laid_knot`'s second table); the evaluator allows 1.5 mm.
//!
//! Found, the contacts solved from either end in turn: the stiff rope's tight surgeon's knots hold
//! at friction 0.5 (6 of 6, 0.00 mm), its loose ones jam on their way down (1 of 9 within 1.5 mm;
//! the snug leaves the wound 0.4-4.5 mm open) where at 0.3 they close and 7 of 9 hold; the string's
//! hold none (tight 2.1-11.3 mm, loose 3.7-16.3 mm), nor the stiff rope's tight knots at 0.3
//! (1.5-8.4 mm). The stiff square knot holds within 0.5 mm at 0.5 and 1.0 (the string's slide
//! 16-32 mm at 0.5, 4.6-21 mm at 1.0), and the stiff wrap holds a ratio of 10 at 1.0 where the
//! string's slides from a ratio of 3: with one contact pass a substep the string's solve does not
//! converge (`rope_holds_a_wrap_and_a_square_knot.rs`: four passes hold its wrap at 30).
//!
//! Printed: how far each slid, in all and (in brackets) in the last half of the load, the reef's
//! knot after, the wound's gap, and the wall time of each trial on one core.
//!
//! `cargo bench -p knotlab-lab --bench rope_knot` (16 minutes on one core of a 2-core machine running two other jobs)

use std::time::Instant;

use knotlab_lab::laid_knot::{LaidKnotKind, LaidKnotParams};
use knotlab_lab::trials::{Slide, capstan, reef};
use knotlab_lab::wound::{WoundTrialParams, laid_surgeons_knot_in_wound};
use knotlab_sim::rope::RopeParams;

const FRICTIONS: [f64; 3] = [0.3, 0.5, 1.0];
const RATIOS: [f64; 4] = [3.0, 10.0, 30.0, 100.0];
/// Loose-knot layouts: spread and lift, m.
const LAYOUTS: [(f64, f64); 4] = [(0.003, 0.0015), (0.004, 0.0015), (0.005, 0.002), (0.003, 0.001)];

fn cell(slide: &Slide, seconds: f64) -> String {
    format!("{:.2} mm ({:.2}), {seconds:.1} s", slide.slip_m * 1e3, slide.late_slip_m * 1e3)
}

/// The rope models compared: the string (no bending stiffness, lengths by two
/// Gauss-Seidel sweeps) and the default (a suture's bending stiffness, lengths solved directly).
fn models() -> [(&'static str, RopeParams); 2] {
    let string = RopeParams {
        bending_stiffness_n_m2: 0.0,
        direct_stretch: false,
        stretch_iterations: 2,
        ..RopeParams::default()
    };
    [("string", string), ("stiff", RopeParams::default())]
}

fn with_friction(rope: RopeParams, friction: f64) -> RopeParams {
    RopeParams { static_friction: friction, kinetic_friction: 0.8 * friction, ..rope }
}

fn main() {
    println!(
        "capstan: a strand wound twice round another, 0.3 N against 0.3 N / ratio for 2 s: slip (last second), wall time"
    );
    let header: Vec<String> = RATIOS.iter().map(|r| format!("ratio {r}")).collect();
    println!("| rope | friction (static; kinetic 0.8 of it) | bound | {} |", header.join(" | "));
    println!("|---|---|---|{}", "---|".repeat(RATIOS.len()));
    for (name, rope) in models() {
        for friction in FRICTIONS {
            let cells: Vec<String> = RATIOS
                .iter()
                .map(|ratio| {
                    let start = Instant::now();
                    let slide = capstan(with_friction(rope, friction), 0.3, *ratio);
                    cell(&slide, start.elapsed().as_secs_f64())
                })
                .collect();
            let bound = (friction * 4.0 * std::f64::consts::PI).exp();
            println!("| {name} | {friction} | {bound:.0} | {} |", cells.join(" | "));
        }
    }
    println!();
    println!(
        "reef: a loose square knot snugged at 1 N, then 0.3 N on its standing parts for 2 s, free ends let go: the standing parts drew apart (last second), knot after, wall time"
    );
    let header: Vec<String> =
        LAYOUTS.iter().map(|(s, l)| format!("spread {:.0} mm, lift {:.1} mm", s * 1e3, l * 1e3)).collect();
    println!("| rope | friction | {} |", header.join(" | "));
    println!("|---|---|{}", "---|".repeat(LAYOUTS.len()));
    for (name, rope) in models() {
        for friction in FRICTIONS {
            let cells: Vec<String> = LAYOUTS
                .iter()
                .map(|(spread_m, lift_m)| {
                    let start = Instant::now();
                    let slide = reef(with_friction(rope, friction), *spread_m, *lift_m, 1.0, 0.3, 2.0);
                    let knot = slide.knot_after.map_or("unclassified", |k| k.name());
                    format!("{}, {knot}", cell(&slide, start.elapsed().as_secs_f64()))
                })
                .collect();
            println!("| {name} | {friction} | {} |", cells.join(" | "));
        }
    }
    println!();
    let loose: Vec<(f64, f64)> =
        [0.006, 0.008, 0.010].into_iter().flat_map(|s| [0.001, 0.0012, 0.0015].map(|l| (s, l))).collect();
    wound("laid loose, 4 mm over the tissue", &loose, 0.004);
    println!();
    let tight: Vec<(f64, f64)> =
        [0.001, 0.0016, 0.002].into_iter().flat_map(|s| [0.00022, 0.0003].map(|l| (s, l))).collect();
    wound("laid tight, 1 mm over the tissue", &tight, 0.001);
}

/// The laid surgeon's knot over the stitch in each rope, in `layouts` (spread, helix radius) at
/// `height_m`, the rope damped at 10/s.
fn wound(title: &str, layouts: &[(f64, f64)], height_m: f64) {
    let scene = knotlab_lab::scenes::short_suture_scene();
    println!(
        "the surgeon's knot {title}, snugged at 2 N for 6 s, 0.3 N a flap for 1 s, rope damped at 10/s: the wound's gap as snugged / after (knot after), wall time"
    );
    let header: Vec<String> =
        layouts.iter().map(|(s, l)| format!("{:.1} mm, {:.2} mm", s * 1e3, l * 1e3)).collect();
    println!("| rope | friction | {} | within 1.5 mm |", header.join(" | "));
    println!("|---|---|{}---|", "---|".repeat(layouts.len()));
    for (name, rope) in models() {
        for friction in [0.3, 0.5] {
            let rope = RopeParams { damping_per_s: 10.0, ..with_friction(rope, friction) };
            let mut within = 0;
            let cells: Vec<String> = layouts
                .iter()
                .map(|(spread_m, lift_m)| {
                    let knot = LaidKnotParams {
                        kind: LaidKnotKind::SurgeonsKnot,
                        spread_m: *spread_m,
                        lift_m: *lift_m,
                        height_m,
                        snug_n: 2.0,
                        snug_s: 6.0,
                        ..LaidKnotParams::default()
                    };
                    let start = Instant::now();
                    let o = laid_surgeons_knot_in_wound(
                        rope,
                        &scene.tissue,
                        &scene.stitch,
                        &knot,
                        &WoundTrialParams::default(),
                    );
                    let accepted = o.knot_after.is_some_and(|k| k.name().starts_with("surgeons"));
                    if accepted && o.gap_after_m <= 0.0015 {
                        within += 1;
                    }
                    format!(
                        "{:.2} / {:.2} mm ({}), {:.1} s",
                        o.gap_snug_m * 1e3,
                        o.gap_after_m * 1e3,
                        o.knot_after.map_or("unclassified", |k| k.name()),
                        start.elapsed().as_secs_f64()
                    )
                })
                .collect();
            println!("| {name} | {friction} | {} | {within} of {} |", cells.join(" | "), layouts.len());
        }
    }
}
