//! The assist presents the tail ahead of the left's jaws; the left opens, goes there and closes on
//! it.

use nalgebra::Unit;

use super::approach::Winding;
use super::{Hands, Setting, TAKE_APPROACH_M};
use crate::expert::motion::Path;

/// The tail presented and taken, once the coils are wound (`wound_s`).
pub(crate) fn present(s: &Setting, hands: &mut Hands, winding: &Winding, wound_s: f64) {
    let geometry = s.geometry;
    let Hands { left, assist, .. } = hands;
    let (entry, tail_point, hinge, jaws) =
        (winding.entry_m, winding.tail_point_m, winding.hinge, winding.jaws);
    assist.wait_until(wound_s + s.pause(3));
    // The tail swung taut about the entry point (so it neither sags onto the tissue nor catches on
    // the flap) until it runs straight through the point ahead of the left's jaws; the assist holds it
    // there, beyond that point (at least `tail_beyond_m`).
    let radius = ((assist.position_m() - entry).norm() + geometry.tail_tension_m)
        .max((tail_point - entry).norm() + geometry.tail_beyond_m);
    let outward = (assist.position_m() - entry).normalize();
    let towards = (tail_point - entry).normalize();
    if let Some(offered_m) = geometry.tail_end_offered_m {
        // Beside the point ahead of the left's jaws along their hinge, on the side away from the
        // knot; the assist's hinge along the left's, towards the tail's end (it took the tail with
        // its hinge that way), so the rest of the tail runs from its jaws through the left's.
        let side = if (tail_point + hinge.into_inner() * offered_m - entry).norm()
            >= (tail_point - hinge.into_inner() * offered_m - entry).norm()
        {
            hinge.into_inner()
        } else {
            -hinge.into_inner()
        };
        let offer_m = tail_point + side * offered_m;
        let shaft = (offer_m - s.trocar_m(assist.arm())).normalize();
        let assist_jaws = (shaft - side * shaft.dot(&side)).try_normalize(1e-9).unwrap_or(shaft);
        let frame = nalgebra::Rotation3::from_basis_unchecked(&[side.cross(&assist_jaws), side, assist_jaws]);
        assist.go_framing(Path::To(offer_m - assist_jaws * TAKE_APPROACH_M), s.d(1.5), frame);
        assist.go(Path::To(offer_m), s.d(0.8));
    } else if !geometry.tail_via_m.is_empty() {
        // A route given in the stitch frame, then up to the hold.
        for p in &geometry.tail_via_m {
            match geometry.assist_jaw_direction {
                Some(j) => assist.go_pointing(Path::To(s.at(*p)), s.d(0.8), s.dir(j)),
                None => assist.go(Path::To(s.at(*p)), s.d(0.8)),
            }
        }
        assist.go(Path::To(entry + towards * radius), s.d(0.8));
    } else {
        assist.go(Path::To(entry + outward * radius), s.d(0.4));
        // Through a direction leaning off the shortest arc, where the assist's wrist is far from its
        // singular pose.
        let via = (outward + towards).normalize() + s.dir(geometry.tail_swing_lean);
        for (from, to) in [(outward, via.normalize()), (via.normalize(), towards)] {
            if let Some(axis) = Unit::try_new(from.cross(&to), 1e-9) {
                let turns = from.dot(&to).clamp(-1.0, 1.0).acos() / std::f64::consts::TAU;
                assist.go(Path::Around { centre_m: entry, axis, turns, pitch_m: 0.0 }, s.d(0.8));
            }
        }
    }
    left.wait_until(wound_s + s.pause(3));
    left.jaw(geometry.take_tail_jaw_rad, s.d(0.3));
    left.wait_until(assist.time_s());
    left.go(Path::To(tail_point - jaws.into_inner() * geometry.tail_take_short_m), s.d(1.0));
    left.wait_until(left.time_s() + s.pause(4));
    left.jaw(0.0, s.d(0.3));
    left.wait_until(left.time_s() + s.d(0.3) + 0.1);
}
