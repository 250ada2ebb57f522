//! The rope's knot trials, as `crate::cinch` and `crate::reef` run them for the capsule chain: a
//! strand wound twice round another and pulled harder at one end (the capstan), and a loose square
//! knot snugged by its four ends, then loaded by its standing parts with its free ends let go.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Vector3;

use crate::reef::{as_stitch, loose_knot};
use knotlab_sim::knot::{KnotType, classify};
use knotlab_sim::rope::{RopeParams, Ropes};

/// Particle spacing of the trials' ropes, m (one and a half radii of the default rope).
pub const SPACING_M: f64 = 0.0003;

/// Strand A (30 mm, both ends pinned) and B wound twice round it in a helix touching it, B's ends
/// leading off along -z and +z; both at [`SPACING_M`], one and a half radii of the default rope (a
/// thicker rope's particles would overlap their second neighbours').
pub fn wound_pair(params: RopeParams) -> (Ropes, std::ops::Range<usize>) {
    let mut ropes = Ropes::new(params);
    let a =
        ropes.add_strand_along(&[Vector3::new(-0.015, 0.0, 0.0), Vector3::new(0.015, 0.0, 0.0)], SPACING_M);
    ropes.w[a.start] = 0.0;
    ropes.w[a.end - 1] = 0.0;
    let r = 2.04 * params.radius_m;
    let mut path = vec![Vector3::new(-0.003, 0.0, -0.03), Vector3::new(-0.003, 0.0, -r)];
    let n = 200;
    path.extend((0..=n).map(|k| {
        let f = k as f64 / n as f64;
        let angle = -FRAC_PI_2 + f * 4.0 * PI;
        Vector3::new(-0.003 + 0.006 * f, r * angle.cos(), r * angle.sin())
    }));
    path.push(Vector3::new(0.003, 0.0, 0.03));
    let b = ropes.add_strand_along(&path, SPACING_M);
    (ropes, b)
}
/// Step of the trials, s.
pub const DT_S: f64 = 0.001;

/// What a trial measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slide {
    /// How far the measured end moved while loaded, m.
    pub slip_m: f64,
    /// ... in the last half of that time, m (near zero when friction holds).
    pub late_slip_m: f64,
    /// The knot the strands make at the end (the reef trial's red and blue joined as
    /// [`crate::reef::as_stitch`] joins them; none for the capstan, or if the classifier failed).
    pub knot_after: Option<KnotType>,
}

/// The capstan: B's ends pulled apart with 1 N for 0.5 s, then its first end with `high_n` and its
/// last with `high_n / ratio` for 2 s. Friction should hold B while `ratio` stays below
/// `exp(friction 4 pi)`. The slip is the first end's travel along its pull.
pub fn capstan(params: RopeParams, high_n: f64, ratio: f64) -> Slide {
    let (mut ropes, b) = wound_pair(params);
    let (first, last) = (b.start, b.end - 1);
    let (snug, hold) = (500, 2000);
    let (mut z_start, mut z_half) = (0.0, 0.0);
    for step in 0..snug + hold {
        let (f_first, f_last) = if step < snug { (1.0, 1.0) } else { (high_n, high_n / ratio) };
        ropes.force_n[first] = Vector3::new(0.0, 0.0, -f_first);
        ropes.force_n[last] = Vector3::new(0.0, 0.0, f_last);
        if step == snug {
            z_start = ropes.x[first].z;
        }
        if step == snug + hold / 2 {
            z_half = ropes.x[first].z;
        }
        ropes.step(DT_S);
    }
    let z_end = ropes.x[first].z;
    Slide { slip_m: z_start - z_end, late_slip_m: z_half - z_end, knot_after: None }
}

/// The reef trial: [`loose_knot`] (`spread_m`, `lift_m`, 20 mm tails) laid as two strands, snugged
/// by its four ends with `snug_n` each (ramped over the first half of 1 s), then for `hold_s` the
/// standing parts pulled apart with `load_n` and the free ends let go. The slip is how far the
/// standing parts' ends drew apart meanwhile (a knot that turns as it settles can bring them
/// closer: the slip is then negative).
pub fn reef(params: RopeParams, spread_m: f64, lift_m: f64, snug_n: f64, load_n: f64, hold_s: f64) -> Slide {
    let knot = loose_knot(spread_m, lift_m, 0.02);
    let mut ropes = Ropes::new(params);
    let mut ends = Vec::new();
    for path in [&knot.red, &knot.blue] {
        let r = ropes.add_strand_along(path, SPACING_M);
        let (first, last) = (r.start, r.end - 1);
        let out_first = (ropes.x[first] - ropes.x[first + 1]).normalize();
        let out_last = (ropes.x[last] - ropes.x[last - 1]).normalize();
        ends.push((first, out_first, last, out_last));
    }
    let snug = (1.0 / DT_S).round() as usize;
    let hold = (hold_s / DT_S).round() as usize;
    let apart = |ropes: &Ropes| (ropes.x[ends[0].0] - ropes.x[ends[1].0]).norm();
    let (mut start, mut half) = (0.0, 0.0);
    for step in 0..snug + hold {
        for &(first, out_first, last, out_last) in &ends {
            if step < snug {
                let f = snug_n * (2.0 * step as f64 / snug as f64).min(1.0);
                ropes.force_n[first] = out_first * f;
                ropes.force_n[last] = out_last * f;
            } else {
                ropes.force_n[first] = out_first * load_n;
                ropes.force_n[last] = Vector3::zeros();
            }
        }
        if step == snug {
            start = apart(&ropes);
        }
        if step == snug + hold / 2 {
            half = apart(&ropes);
        }
        ropes.step(DT_S);
    }
    let end = apart(&ropes);
    let knot_after = classify(&as_stitch(&ropes.polyline(0), &ropes.polyline(1))).ok().map(|c| c.knot);
    Slide { slip_m: end - start, late_slip_m: end - half, knot_after }
}
