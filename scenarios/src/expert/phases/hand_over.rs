//! Before a second throw wound on the assist's jaws: the assist takes the tail by its end from the
//! left, which lets go and rises clear.

use super::take_tail::take_tail;
use super::{Hands, Setting};
use crate::expert::motion::Path;
use crate::expert::tail::tail_from_its_end;

/// How far the left rises from where it let go of the tail before it goes to take it back, m.
const RETAKE_CLEARANCE_M: f64 = 0.025;

/// The assist takes the tail `from_end_m` from its free end, the left lets go and rises clear, and
/// the assist draws the tail by its end to `to_m` (stitch frame), if given.
pub(crate) fn hand_over(s: &Setting, hands: &mut Hands, from_end_m: f64, to_m: Option<[f64; 3]>) {
    let Hands { left, assist, .. } = hands;
    if let Some((tail_m, tail_dir)) = tail_from_its_end(s.world, from_end_m) {
        take_tail(assist, s, tail_m, tail_dir);
    }
    left.wait_until(assist.time_s() + s.pause(5));
    left.jaw(s.open(), s.d(0.2));
    left.wait_until(left.time_s() + s.d(0.2) + s.pause(0));
    left.go(Path::To(left.position_m() + s.up() * RETAKE_CLEARANCE_M), s.d(0.8));
    if let Some(to_m) = to_m {
        assist.wait_until(left.time_s());
        assist.go(Path::To(s.at(to_m)), s.d(1.5));
    }
    let end_s = left.time_s().max(assist.time_s()) + s.pause(5);
    hands.wait_until(end_s);
}
