//! The loop's two legs as the thread lies: from the stitch's exit point back along the long end to
//! where it first touches the tail, and from the entry point along the tail to where it first touches
//! the long end. A leg holding much more thread than the distance it spans lies slack: loaded, the
//! wound opens by what it has to spare before the knot is pulled at all. Measured by contact, not by
//! the crossings of a picture, so a slack leg lying over itself still counts whole.

use nalgebra::Vector3;
use serde::Serialize;

use knotlab_hw::geometry::{arc_lengths, segment_closest_parameters};

/// One leg of the loop outside the tissue.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Leg {
    /// Thread between the stitch point and the first contact with the other end, m.
    pub thread_m: f64,
    /// Straight distance between the two, m.
    pub span_m: f64,
}

impl Leg {
    /// Thread the leg has to spare, m.
    pub fn slack_m(&self) -> f64 {
        self.thread_m - self.span_m
    }
}

/// The point at arc length `arc_m` along the polyline.
fn point_at(points: &[Vector3<f64>], arcs: &[f64], arc_m: f64) -> Vector3<f64> {
    let k = arcs.partition_point(|&a| a <= arc_m).clamp(1, points.len() - 1);
    let (a0, a1) = (arcs[k - 1], arcs[k]);
    let t = if a1 > a0 { ((arc_m - a0) / (a1 - a0)).clamp(0.0, 1.0) } else { 0.0 };
    points[k - 1] + (points[k] - points[k - 1]) * t
}

/// The closest points of segments `i` and `j`: their parameters along each (0 to 1) and distance, m.
pub(crate) fn closest(points: &[Vector3<f64>], i: usize, j: usize) -> (f64, f64, f64) {
    let (p0, q0) = (points[i], points[j]);
    let (d1, d2) = (points[i + 1] - p0, points[j + 1] - q0);
    let (s, t) = segment_closest_parameters(&p0, &d1, &q0, &d2);
    (s, t, ((p0 + d1 * s) - (q0 + d2 * t)).norm())
}

/// The arc length of the first contact met walking `walk`'s segments in order against `others`:
/// on the first segment within `touch_m` of any of them, the contact nearest the walk's start (the
/// smallest parameter along the segment if `forward`, else the largest).
fn first_contact_arc(
    points: &[Vector3<f64>],
    arcs: &[f64],
    walk: impl Iterator<Item = usize>,
    others: &[usize],
    touch_m: f64,
    forward: bool,
) -> Option<f64> {
    let mut walk = walk;
    walk.find_map(|i| {
        let mut touching =
            others.iter().map(|&j| closest(points, i, j)).filter(|c| c.2 < touch_m).map(|c| c.0);
        let first = touching.next()?;
        let u = touching.fold(first, |b, u| if forward { b.min(u) } else { b.max(u) });
        Some(arcs[i] + u * (arcs[i + 1] - arcs[i]))
    })
}

/// The segments of a polyline with arc lengths `arcs` wholly before the stitch's exit at `exit_m`
/// (the long end) and wholly after its entry at `entry_m` (the tail), in order along the thread.
pub(crate) fn ends(arcs: &[f64], exit_m: f64, entry_m: f64) -> (Vec<usize>, Vec<usize>) {
    let n = arcs.len().saturating_sub(1);
    let long_end = (0..n).filter(|&i| arcs[i + 1] <= exit_m).collect();
    let tail = (0..n).filter(|&j| arcs[j] >= entry_m).collect();
    (long_end, tail)
}

/// The two legs of a centreline (needle end first) whose stitch leaves the tissue at arc length
/// `exit_m` and enters it again at `entry_m` (`exit_m < entry_m`): `(exit leg, entry leg)`, each `None`
/// when its end touches nothing of the other within `touch_m` (segment to segment). Each leg ends at
/// the contact nearest its stitch point on the first segment that touches.
pub fn legs(points: &[Vector3<f64>], exit_m: f64, entry_m: f64, touch_m: f64) -> (Option<Leg>, Option<Leg>) {
    // NaN arcs fail the comparison too.
    if points.len() < 2 || exit_m.partial_cmp(&entry_m) != Some(std::cmp::Ordering::Less) {
        return (None, None);
    }
    let arcs = arc_lengths(points);
    let (long_end, tail) = ends(&arcs, exit_m, entry_m);
    let exit_point = point_at(points, &arcs, exit_m);
    let entry_point = point_at(points, &arcs, entry_m);
    // Walking back from the exit: the first long-end segment touching the tail, at its contact
    // nearest the exit; walking on from the entry: the first tail segment touching the long end, at
    // its contact nearest the entry.
    let exit_leg = first_contact_arc(points, &arcs, long_end.iter().rev().copied(), &tail, touch_m, false)
        .map(|contact| Leg {
            thread_m: exit_m - contact,
            span_m: (exit_point - point_at(points, &arcs, contact)).norm(),
        });
    let entry_leg =
        first_contact_arc(points, &arcs, tail.iter().copied(), &long_end, touch_m, true).map(|contact| Leg {
            thread_m: contact - entry_m,
            span_m: (point_at(points, &arcs, contact) - entry_point).norm(),
        });
    (exit_leg, entry_leg)
}

/// The two free ends of a centreline (needle end first) whose stitch leaves the tissue at `exit_m`
/// and enters it again at `entry_m`: `(long end, tail)`, the thread from the needle end to the long
/// end's first contact with the tail and from the tail's last contact with the long end to its end,
/// m; `None` when the two ends do not touch within `touch_m`.
pub fn free_ends(points: &[Vector3<f64>], exit_m: f64, entry_m: f64, touch_m: f64) -> Option<(f64, f64)> {
    if points.len() < 2 || exit_m.partial_cmp(&entry_m) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let arcs = arc_lengths(points);
    let n = points.len() - 1;
    let (long_end, tail) = ends(&arcs, exit_m, entry_m);
    let long_end_m = first_contact_arc(points, &arcs, long_end.iter().copied(), &tail, touch_m, true)?;
    let tail_from_m =
        first_contact_arc(points, &arcs, tail.iter().rev().copied(), &long_end, touch_m, false)?;
    Some((long_end_m, arcs[n] - tail_from_m))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A long end coming in along -x at height 5 mm, wound round the tail (a vertical line at the
    /// origin) once, then a slack leg: out to x = 30 mm and back to the exit at (10, 0, 0); under the
    /// tissue to the entry at (0, 0, 0); the tail straight up through the wrap. Returns the points,
    /// the exit's and the entry's arc lengths.
    pub(crate) fn line() -> (Vec<Vector3<f64>>, f64, f64) {
        let mut p = vec![Vector3::new(-0.05, 0.0, 0.005)];
        // The wrap: a circle of 1 mm radius round the z axis at z = 5 mm, starting at (-1 mm, 0).
        for k in 0..=16 {
            let a = std::f64::consts::PI + std::f64::consts::TAU * k as f64 / 16.0;
            p.push(Vector3::new(0.001 * a.cos(), 0.001 * a.sin(), 0.005));
        }
        // The slack leg: to (30, 5, 1) mm, back to the exit at (10, 0, 0).
        p.push(Vector3::new(0.03, 0.005, 0.001));
        p.push(Vector3::new(0.01, 0.0, 0.0));
        let exit_m = arc_lengths(&p)[p.len() - 1];
        // Under the tissue to the entry at the origin, then the tail up.
        p.push(Vector3::new(0.005, 0.0, -0.003));
        p.push(Vector3::new(0.0, 0.0, 0.0));
        let entry_m = arc_lengths(&p)[p.len() - 1];
        for k in 1..=10 {
            p.push(Vector3::new(0.0, 0.0, 0.002 * k as f64));
        }
        (p, exit_m, entry_m)
    }

    /// A slack leg looping out and back counts all its thread against its shorter span, and a tail running
    /// straight through the wrap has a short leg with no slack.
    #[test]
    fn the_slack_leg_counts_whole_and_the_tail_leg_is_short() {
        let (p, exit_m, entry_m) = line();
        let (exit_leg, entry_leg) = legs(&p, exit_m, entry_m, 0.0012);
        let exit_leg = exit_leg.expect("the long end touches the tail at its wrap");
        // From the wrap's last point (-1, 0, 5) mm: to (30, 5, 1), then to (10, 0, 0).
        let a: Vector3<f64> = Vector3::new(-0.001, 0.0, 0.005);
        let b: Vector3<f64> = Vector3::new(0.03, 0.005, 0.001);
        let c: Vector3<f64> = Vector3::new(0.01, 0.0, 0.0);
        let want: f64 = (b - a).norm() + (c - b).norm();
        // (It ends where the leg's first segment passes nearest the tail, about 1 mm past the wrap.)
        assert!((exit_leg.thread_m - want).abs() < 0.0015, "{exit_leg:?} vs {want}");
        assert!((exit_leg.span_m - (c - a).norm()).abs() < 0.0015, "{exit_leg:?}");
        assert!(exit_leg.slack_m() > 0.03, "{exit_leg:?}");
        // The tail meets the long end at the wrap's height, 5 mm (within a touching distance), and
        // runs straight: no slack.
        let entry_leg = entry_leg.expect("the tail touches the wrap");
        assert!((entry_leg.thread_m - 0.005).abs() < 0.0012, "{entry_leg:?}");
        assert!(entry_leg.slack_m().abs() < 1e-9, "{entry_leg:?}");
    }

    /// The long end is free from its end to its first contact with the tail, the tail from its last contact
    /// to its end; ends that never touch or an exit after the entry give none.
    #[test]
    fn the_free_ends_run_to_the_wrap() {
        let (p, exit_m, entry_m) = line();
        let (long_end_m, tail_m) = free_ends(&p, exit_m, entry_m, 0.0012).expect("the ends touch");
        // The long end runs 49 mm along -x to the wrap at (-1, 0, 5) mm, where it passes 1 mm from
        // the tail (the z axis): its first contact.
        assert!((long_end_m - 0.049).abs() < 0.0005, "{long_end_m}");
        // The tail runs from the origin up to 20 mm, through the wrap at 5 mm; the leg leaving the
        // wrap passes 1.15 mm from the tail's point at 6 mm, which is where it last touches: 14 mm free.
        assert!((tail_m - 0.014).abs() < 0.0005, "{tail_m}");
        // Touching nothing, no free ends.
        assert_eq!(free_ends(&p, exit_m, entry_m, 1e-6), None);
        assert_eq!(free_ends(&p, entry_m, exit_m, 0.0012), None);
    }

    /// Ends that never touch, an exit after the entry, or a one-point thread give no leg at all.
    #[test]
    fn ends_that_touch_nothing_have_no_leg() {
        let (p, exit_m, entry_m) = line();
        assert_eq!(legs(&p, exit_m, entry_m, 1e-6), (None, None));
        assert_eq!(legs(&p, entry_m, exit_m, 0.0012), (None, None), "exit after the entry");
        assert_eq!(legs(&p[..1], 0.0, 1.0, 0.0012), (None, None));
    }
}
