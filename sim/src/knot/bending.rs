//! How much each end bends inside the knot: the long end over the stretch of it that touches the
//! tail, the tail over the stretch of it that touches the long end. In a knot laid flat each end bends
//! round the other. In one whose tail runs straight through the long end's turns (a knot capsized
//! into a slip knot, as a pull in line with the tail's own leg leaves it) only the long end bends, and
//! under load the tail slides through the turns. The knot's type cannot tell the two apart: capsizing
//! does not change it.

use nalgebra::Vector3;
use serde::Serialize;

use knotlab_hw::geometry::arc_lengths;

use crate::knot::legs::{closest, ends};

/// How much each end turns between its first and its last contact with the other end.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Bending {
    /// The long end's turning, rad (the sum of the angles between its consecutive segments).
    pub long_end_rad: f64,
    /// The tail's turning, rad.
    pub tail_rad: f64,
}

/// The turning of the polyline over segments `first..=last`, rad.
fn turning(points: &[Vector3<f64>], first: usize, last: usize) -> f64 {
    (first..last)
        .map(|i| {
            let (a, b) = (points[i + 1] - points[i], points[i + 2] - points[i + 1]);
            let (na, nb) = (a.norm(), b.norm());
            if na > 0.0 && nb > 0.0 { (a.dot(&b) / (na * nb)).clamp(-1.0, 1.0).acos() } else { 0.0 }
        })
        .fold(0.0, |sum, angle| sum + angle)
}

/// The bending of both ends of a centreline (needle end first) whose stitch leaves the tissue at arc
/// length `exit_m` and enters it again at `entry_m` (`exit_m < entry_m`); `None` when the ends touch
/// nowhere within `touch_m` (segment to segment).
pub fn bending(points: &[Vector3<f64>], exit_m: f64, entry_m: f64, touch_m: f64) -> Option<Bending> {
    // NaN arcs fail the comparison too.
    if points.len() < 2 || exit_m.partial_cmp(&entry_m) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let (long_end, tail) = ends(&arc_lengths(points), exit_m, entry_m);
    let touching = |walk: &[usize], others: &[usize]| -> Option<(usize, usize)> {
        let hits: Vec<usize> = walk
            .iter()
            .copied()
            .filter(|&i| others.iter().any(|&j| closest(points, i, j).2 < touch_m))
            .collect();
        Some((*hits.first()?, *hits.last()?))
    };
    let (l0, l1) = touching(&long_end, &tail)?;
    let (t0, t1) = touching(&tail, &long_end)?;
    Some(Bending { long_end_rad: turning(points, l0, l1), tail_rad: turning(points, t0, t1) })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The long end wound once round a straight tail ([`crate::knot::legs::tests::line`]).
    fn wound_round_a_straight_tail() -> (Vec<Vector3<f64>>, f64, f64) {
        crate::knot::legs::tests::line()
    }

    /// A long end wound once round a straight tail bends about a turn while the tail shows no bending.
    #[test]
    fn a_long_end_wound_round_a_straight_tail_bends_and_the_tail_does_not() {
        let (p, exit_m, entry_m) = wound_round_a_straight_tail();
        let b = bending(&p, exit_m, entry_m, 0.0012).expect("the turn touches the tail");
        // A whole turn, and a quarter turn more or less where it comes in and where it leaves.
        let tau = std::f64::consts::TAU;
        assert!(b.long_end_rad > 0.9 * tau && b.long_end_rad < 1.7 * tau, "{b:?}");
        assert!(b.tail_rad < 1e-9, "the tail runs straight: {b:?}");
    }

    /// Reading the thread from its tail's end swaps the long end's and the tail's bending exactly.
    #[test]
    fn read_from_the_other_end_the_roles_swap() {
        // The same thread from its tail's end: the straight strand is now the long end.
        let (mut p, exit_m, entry_m) = wound_round_a_straight_tail();
        let total_m = arc_lengths(&p)[p.len() - 1];
        p.reverse();
        let forward = bending(&p, total_m - entry_m, total_m - exit_m, 0.0012).expect("they touch");
        let (q, exit_m, entry_m) = wound_round_a_straight_tail();
        let backward = bending(&q, exit_m, entry_m, 0.0012).expect("they touch");
        assert!((forward.long_end_rad - backward.tail_rad).abs() < 1e-9, "{forward:?} {backward:?}");
        assert!((forward.tail_rad - backward.long_end_rad).abs() < 1e-9, "{forward:?} {backward:?}");
    }

    /// Ends that never touch, an exit after the entry, or a one-point thread give no bending at all.
    #[test]
    fn ends_that_touch_nothing_have_no_bending() {
        let (p, exit_m, entry_m) = wound_round_a_straight_tail();
        assert_eq!(bending(&p, exit_m, entry_m, 1e-6), None);
        assert_eq!(bending(&p, entry_m, exit_m, 0.0012), None, "exit after the entry");
        assert_eq!(bending(&p[..1], 0.0, 1.0, 0.0012), None);
    }
}
