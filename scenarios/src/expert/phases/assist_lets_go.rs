//! A1: once the left holds the tail, the assist lets go of it and retreats.

use super::{Hands, Setting};
use crate::expert::motion::Path;

/// The assist lets go as the left's grasp ends and retreats; returns when the left's grasp ended, s.
pub(crate) fn assist_lets_go(s: &Setting, hands: &mut Hands) -> f64 {
    let Hands { left, assist, .. } = hands;
    let grasped_s = left.time_s();
    assist.wait_until(grasped_s);
    assist.jaw(s.open(), s.d(0.2));
    assist.wait_until(grasped_s + s.d(0.2) + s.pause(5));
    assist.go(Path::To(s.at(s.geometry.assist_retreat_m)), s.d(1.2));
    grasped_s
}
