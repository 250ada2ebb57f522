//! L6 and R4: both instruments run the knot down onto the wound.

use super::{Hands, Setting};
use crate::expert::motion::Path;

/// The run-down, through the geometry's waypoints to its ends; returns when it starts, s.
pub(crate) fn run_down(s: &Setting, hands: &mut Hands) -> f64 {
    let geometry = s.geometry;
    let Hands { left, right, .. } = hands;
    let run_down_s = left.time_s() + s.pause(4);
    left.wait_until(run_down_s);
    for via in &geometry.left_run_down_via_m {
        left.go(Path::To(s.at(*via)), s.d(geometry.run_down_s));
    }
    right.wait_until(run_down_s);
    for via in &geometry.right_run_down_via_m {
        right.go(Path::To(s.at(*via)), s.d(geometry.run_down_s));
    }
    for (track, to) in [(left, geometry.left_run_down_to_m), (right, geometry.right_run_down_to_m)] {
        track.wait_until(run_down_s);
        track.go(Path::To(s.at(to)), s.d(geometry.run_down_s));
    }
    run_down_s
}
