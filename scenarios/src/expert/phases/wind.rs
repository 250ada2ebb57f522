//! R2: the right winds the long end round the left's jaws, gives a little back and draws the coils
//! towards the jaws' hinge; the assist gives the winding thread meanwhile.

use knotlab_hw::rig::ArmName;

use super::approach::Winding;
use super::{Hands, Setting};
use crate::expert::motion::Path;

/// The winding, after the left is at the winding point; returns when the coils are wound, s.
pub(crate) fn wind(s: &Setting, hands: &mut Hands, winding: &Winding) -> f64 {
    let geometry = s.geometry;
    let Hands { left, right, assist } = hands;
    let (centre, axis, advance_m) = (winding.centre_m, winding.axis, winding.advance_m);
    right.wait_until(left.time_s() + s.pause(2));
    right.go(
        Path::Around { centre_m: centre, axis, turns: geometry.winding_turns, pitch_m: advance_m },
        s.d(geometry.winding_s),
    );
    // Then it gives a little thread back, so the coils loosen enough to slide along the jaws.
    right.wait_until(right.time_s() + s.pause(2));
    let slack_dir = (centre - right.position_m()).normalize();
    // ... and draws the coils back along the left's jaws, towards their hinge.
    let back = -winding.jaws.into_inner() * geometry.coils_back_m;
    right.go(Path::To(right.position_m() + slack_dir * geometry.loosen_m + back), s.d(0.5));
    let wound_s = right.time_s();
    // Meanwhile the assist gives the winding thread, moving the tail towards the entry point.
    let (entry, tail_now) = (winding.entry_m, assist.position_m());
    assist.wait_until(left.time_s() + s.pause(2));
    assist
        .go(Path::To(tail_now + (entry - tail_now) * geometry.tail_give_fraction), wound_s - assist.time_s());
    if let Some(to_m) = geometry.tail_brought_to_m {
        // Its wrist straightening on the way (held as they took the tail far out, the jaws needed
        // the wrist at its limits on the way back: the move slowed and jerked, and the tail was lost).
        let to = s.at(to_m);
        assist.go_pointing(Path::To(to), s.d(1.5), to - s.trocar_m(ArmName::Assist));
    }
    wound_s
}
