//! The left, its jaws over the tail (a fetch that looks), closes on the tail where it lies now.

use nalgebra::{Unit, Vector3};

use super::{Hands, Setting};
use crate::expert::geometry::LeftFetch;
use crate::expert::motion::Path;
use crate::expert::tail::tail_ahead_of_jaws;

/// How far off the jaws' line the tail they look at may lie for them to go straight onto it, m.
const OFF_LINE_M: f64 = 0.002;

/// Onto the tail's point nearest the line of the left's jaws, ahead of them, as it lies now, and
/// closed on it.
pub(crate) fn take_as_it_lies(s: &Setting, hands: &mut Hands) {
    let geometry = s.geometry;
    let Hands { left, right, .. } = hands;
    let jaws_to = left.jaw_direction();
    let from = left.position_m();
    let stop_short_m = geometry.fetch().map_or(0.0, |f| f.stop_short_m);
    if let Some((tail_m, tail_dir)) = tail_ahead_of_jaws(s.world, &from, &jaws_to) {
        let framed = geometry.fetch().is_some_and(LeftFetch::holds_frame);
        let square = geometry.fetch().is_some_and(|f| f.hinge_along_tail);
        // Taking the tail square to it, a tail found well off the jaws' line (the part under
        // them lying low) is gone over first and come onto along the jaws, not sideways through
        // it; without `hinge_along_tail`, the straight descent.
        let off_line_m = (tail_m - from - jaws_to * (tail_m - from).dot(&jaws_to)).norm();
        let approach_m = geometry.fetch().map_or(0.0, |f| f.approach_m);
        let mut ways = vec![];
        if square && off_line_m > OFF_LINE_M {
            ways.push(tail_m - jaws_to * (stop_short_m + approach_m));
        }
        ways.push(tail_m - jaws_to * stop_short_m);
        let beside = geometry.fetch().and_then(|f| f.right_beside_m).map(|d| s.dir(d));
        let follows = geometry.fetch().map_or(0.0, |f| f.right_follows);
        for to_m in ways {
            let (to, from_s, left_from) = (Path::To(to_m), left.time_s(), left.position_m());
            match left.held_frame().filter(|_| framed) {
                // The jaws roll on the way, their hinge along the tail where it lies, so that it
                // runs between them: aimed at the line from the entry to the assist, the hinge lay
                // across a slack tail and the jaws closed beside it.
                Some(held) => {
                    let hinge_now = held * Vector3::y();
                    let hinge = Unit::try_new(tail_dir - jaws_to * tail_dir.dot(&jaws_to), 1e-9)
                        .map(|h| if h.dot(&hinge_now) >= 0.0 { h } else { -h })
                        .unwrap_or_else(|| Unit::new_normalize(hinge_now));
                    let frame = nalgebra::Rotation3::from_basis_unchecked(&[
                        hinge.cross(&jaws_to),
                        hinge.into_inner(),
                        jaws_to,
                    ]);
                    left.go_framing(to, s.d(0.8), frame);
                }
                None => left.go(to, s.d(0.8)),
            }
            // The right keeps beside the left's jaws (the turn's thread), if told; or follows
            // their descent by the fetch's share, as it followed them to the tail. The turns lie
            // round both instruments' jaws: left standing (or stopped 8 mm over the tissue), the
            // right drew them taut as the left went down (seeds 0 and 19: both gauges 100-530 N,
            // equal and opposite; on seed 19 the assist's grip on the tail tore).
            if let Some(offset_m) = beside {
                right.wait_until(from_s);
                right.go(Path::To(to_m + offset_m), left.time_s() - from_s);
            } else if follows > 0.0 {
                right.wait_until(from_s);
                right.go(Path::To(right.position_m() + (to_m - left_from) * follows), left.time_s() - from_s);
            }
        }
    }
    left.wait_until(left.time_s() + s.pause(4));
    left.jaw(0.0, s.d(0.3));
    left.wait_until(left.time_s() + s.d(0.3) + 0.1);
}
