//! The left carries its coils to the tail where the assist holds it (the right following, so the
//! coils keep their shape), to a point behind the tail along the fetch's jaw direction; then onto
//! the tail, and closes on it.

use nalgebra::{Unit, Vector3};

use super::{Hands, Setting};
use crate::expert::geometry::LeftFetch;
use crate::expert::motion::Path;
use crate::expert::turn_thread::along_within_long_end;
use knotlab_sim::tissue::Flap;

/// The left's coils to behind the tail, jaws open, once the coils are wound (`wound_s`); returns
/// the tail's point the jaws are aimed at (world frame, m).
pub(crate) fn fetch(s: &Setting, hands: &mut Hands, wound_s: f64, fetch: &LeftFetch) -> Vector3<f64> {
    let (world, geometry) = (s.world, s.geometry);
    let Hands { left, right, assist } = hands;
    let (entry, exit) = (s.hole_m(Flap::A), s.hole_m(Flap::B));
    let tail_hold = assist.position_m();
    let jaws_to = s.dir(fetch.jaw_direction).normalize();
    // No further out than the long end reaches with the turns round the jaws.
    let (left_from, right_from) = (left.position_m(), right.position_m());
    let right_at = |jaws_m: &Vector3<f64>| match fetch.right_beside_m {
        Some(offset) => jaws_m + s.dir(offset),
        None => right_from + (jaws_m - jaws_to * fetch.approach_m - left_from) * fetch.right_follows,
    };
    let along = match world.stitch_arc_at_m(Flap::B) {
        Some(long_end_m) => along_within_long_end(
            fetch.along_tail,
            long_end_m,
            geometry.winding_turns,
            &exit,
            &entry,
            &tail_hold,
            right_at,
        ),
        None => fetch.along_tail,
    };
    let on_tail = entry + (tail_hold - entry) * along;
    let behind = on_tail - jaws_to * fetch.approach_m;
    left.wait_until(wound_s.max(assist.time_s()) + s.pause(3));
    left.jaw(geometry.take_tail_jaw_rad, s.d(0.3));
    left.wait_until(left.time_s() + s.d(0.3));
    let shift = behind - left.position_m();
    // Where the right goes meanwhile: beside the left's jaws, or a share of their shift.
    let right_fetching = |from: Vector3<f64>| match fetch.right_beside_m {
        Some(offset) => behind + s.dir(offset),
        None => from + shift * fetch.right_follows,
    };
    let relocate_from = left.time_s();
    if fetch.holds_frame() {
        // The whole tip frame turns (the hinge along the tail, so that it runs between the open
        // jaws; no roll left to the solver, which may flip it half way and jerk the coils), and
        // the right turns with it about the left's jaws: the coils keep their shape.
        // (A tail along the new jaw direction leaves the hinge free: any side across them.)
        let across_to = |d: Vector3<f64>| Unit::try_new(d - jaws_to * d.dot(&jaws_to), 1e-9);
        let hinge = across_to(tail_hold - entry)
            .or_else(|| across_to(Vector3::x()))
            .unwrap_or_else(|| Unit::new_normalize(Vector3::y()));
        let (left_from, frame_from, jaws_from) = (left.position_m(), left.held_frame(), left.jaw_direction());
        let y_now = frame_from.map_or_else(Vector3::y, |q| q * Vector3::y());
        // Of the two hinge senses the one nearer the present, unless the wrist cannot turn so.
        let hinge = if hinge.dot(&y_now) >= 0.0 { hinge } else { -hinge };
        let frame_with = |hinge: Unit<Vector3<f64>>| {
            nalgebra::Rotation3::from_basis_unchecked(&[hinge.cross(&jaws_to), hinge.into_inner(), jaws_to])
        };
        let frame = [frame_with(hinge), frame_with(-hinge)]
            .into_iter()
            .find(|f| left.reaches_framing(behind, *f))
            .unwrap_or_else(|| frame_with(hinge));
        left.go_framing(Path::To(behind), s.d(1.5), frame);
        right.wait_until(relocate_from);
        if fetch.as_one_body {
            // The right turns with the jaws' direction only: turned about the jaws as well, it
            // would go round them and wind or unwind the coils.
            let rotation = nalgebra::UnitQuaternion::rotation_between(&jaws_from, &jaws_to)
                .unwrap_or_else(nalgebra::UnitQuaternion::identity);
            let carried = Path::Carried { pivot_from_m: left_from, pivot_to_m: behind, rotation };
            right.go(carried, left.time_s() - relocate_from);
        } else {
            right.go(Path::To(right_fetching(right.position_m())), left.time_s() - relocate_from);
        }
    } else {
        left.go_pointing(Path::To(behind), s.d(1.5), jaws_to);
        right.wait_until(relocate_from);
        right.go(Path::To(right_fetching(right.position_m())), left.time_s() - relocate_from);
    }
    left.wait_until(left.time_s() + s.pause(4));
    on_tail
}

/// The left onto the tail at `on_tail` (its jaws' centre short of it, so the tail lies towards
/// their tips, ahead of the coils: every coil then passes over it when the jaws draw back), the
/// right beside it if the fetch says so; the jaws close.
pub(crate) fn close_on_tail(s: &Setting, hands: &mut Hands, on_tail: Vector3<f64>, fetch: &LeftFetch) {
    let Hands { left, right, .. } = hands;
    let jaws_to = s.dir(fetch.jaw_direction).normalize();
    let (onto, onto_s) = (on_tail - jaws_to * fetch.stop_short_m, left.time_s());
    left.go(Path::To(onto), s.d(0.8));
    if let Some(offset) = fetch.right_beside_m {
        right.wait_until(onto_s);
        right.go(Path::To(onto + s.dir(offset)), left.time_s() - onto_s);
    }
    left.wait_until(left.time_s() + s.pause(4));
    left.jaw(0.0, s.d(0.3));
    left.wait_until(left.time_s() + s.d(0.3) + 0.1);
}
