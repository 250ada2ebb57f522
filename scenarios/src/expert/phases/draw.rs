//! L5 and R3: the left draws the tail back out of its coils, along its jaws, while the right follows
//! a little so that the coils stay loose and slide off the jaws onto the tail.

use super::{Hands, Setting};
use crate::expert::geometry::LeftFetch;
use crate::expert::motion::Path;

/// The draw, after the assist has retreated and no sooner than a moment after the left's grasp
/// (`grasped_s`).
pub(crate) fn draw(s: &Setting, hands: &mut Hands, grasped_s: f64) {
    let geometry = s.geometry;
    let Hands { left, right, assist } = hands;
    let mut draw_s = assist.time_s().max(grasped_s + s.d(0.4));
    if !geometry.right_before_draw_m.is_empty() {
        right.wait_until(draw_s);
        for p in &geometry.right_before_draw_m {
            right.go(Path::To(s.at(*p)), s.d(0.8));
        }
        draw_s = right.time_s() + s.pause(4);
    }
    left.wait_until(draw_s);
    right.wait_until(draw_s);
    let first_s = left.time_s();
    let draw = -left.jaw_direction() * geometry.draw_back_m;
    // The wrist straightens a little on the way (a bent wrist drawn back runs into its limit).
    let drawn_to = left.position_m() + draw;
    let shaft = (drawn_to - s.trocar_m(left.arm())).normalize();
    let relaxed = left.jaw_direction().lerp(&shaft, geometry.draw_relax);
    if geometry.fetch().is_some_and(LeftFetch::holds_frame) {
        // The left holds a whole frame since the fetch: it turns that frame, the roll going with it
        // (handed to the solver, the roll flipped: the jaws jumped at 400-530 mm/s and tore the
        // needle out of the right's jaws).
        left.go_turning(Path::To(drawn_to), s.d(geometry.draw_s), relaxed);
    } else {
        left.go_pointing(Path::To(drawn_to), s.d(geometry.draw_s), relaxed);
    }
    let right_to = match geometry.right_draws_to_m {
        Some(p) => s.at(p),
        None => right.position_m() + draw * geometry.right_follows_draw,
    };
    right.go(Path::To(right_to), left.time_s() - first_s);
}
