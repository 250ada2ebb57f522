//! R5: the ends pulled apart until each reaches its set force; then either held so (a second
//! throw follows) or let go.

use knotlab_hw::skill::{ForceAction, ForceEvent};
use nalgebra::Vector3;

use super::{Hands, Setting};
use crate::expert::motion::{Path, TrackBuilder};

/// The name of the pulls' force events (each pull's `fires_with` names the other's).
const SET_FORCE: &str = "set force";

/// The pulls hold the knot cinched until the second throw: both stop at the set force (or where
/// they were going) and hold there together to the end of this plan; or, if the second throw says
/// the left lets go first, the left then lets go of the tail where it stopped, its hold lasting until
/// its jaws are open, and the right holds on to the needle and the long end.
pub(crate) fn pull_and_hold(s: &Setting, hands: &mut Hands, run_down_s: f64) {
    let geometry = s.geometry;
    let pulls = Pulls::after(s, hands, run_down_s);
    let left_lets_go = geometry.second_throw.as_ref().is_some_and(|t| t.left_lets_go_first);
    let Hands { left, right, .. } = hands;
    pulls.pull(s, left, geometry.left_pull_to_m);
    pulls.pull(s, right, geometry.right_pull_to_m);
    let held_s = left.time_s().max(right.time_s()) + 1.0;
    let end_s = if left_lets_go { held_s + s.d(0.2) + 0.3 } else { held_s };
    for (track, threshold_n) in [(&mut *left, pulls.tail_force_n), (&mut *right, geometry.pull_force_n)] {
        track.event(pulls.set_force(s, end_s, threshold_n, ForceAction::Hold));
        track.wait_until(held_s);
        pulls.hold_from_run_down(s, track);
    }
    if left_lets_go {
        left.jaw(s.open().max(geometry.take_tail_jaw_rad), s.d(0.2));
    }
    hands.wait_until(end_s);
}

/// The pulls, then both let go together, a second after the later pull's end, whether or not the
/// set force was reached: a pull sent on within reach may run longer than the other (ended at its
/// own time, the left let go of the tail while the right was still drawing the long end's slack).
pub(crate) fn pull_and_let_go(s: &Setting, hands: &mut Hands, run_down_s: f64) {
    let geometry = s.geometry;
    let pulls = Pulls::after(s, hands, run_down_s);
    let Hands { left, right, assist } = hands;
    // The left lets go of the tail past the angle its jaws took it at (which may be as wide as they
    // were opened to take it: jaws opened less still squeeze it, and the grip held through the
    // holding test).
    let left_let_go = s.open().max(geometry.take_tail_jaw_rad);
    let ends = [
        (geometry.left_pull_to_m, pulls.tail_force_n, left_let_go),
        (geometry.right_pull_to_m, geometry.pull_force_n, s.open()),
    ];
    pulls.pull(s, left, ends[0].0);
    pulls.pull(s, right, ends[1].0);
    let release_s = left.time_s().max(right.time_s()) + 1.0;
    for (track, (_, threshold_n, let_go)) in [&mut *left, &mut *right].into_iter().zip(ends) {
        // The hold ends as the jaws start to open, or, with `hold_through_release`, once they are
        // open: ended before, the arm goes on towards where the pull was headed as it lets go.
        let hold_until_s = if geometry.hold_through_release { release_s + s.d(0.2) + 0.3 } else { release_s };
        let action =
            if geometry.hold_at_force { ForceAction::Hold } else { ForceAction::OpenJaw { jaw_rad: let_go } };
        track.event(pulls.set_force(s, hold_until_s, threshold_n, action));
        track.wait_until(release_s);
        track.jaw(let_go, s.d(0.2));
        track.wait_until(track.time_s() + s.d(0.2) + 0.3);
        pulls.hold_from_run_down(s, track);
    }
    assist.wait_until(left.time_s());
}

/// What both endings' pulls share.
struct Pulls {
    /// When the run-down started, s.
    run_down_s: f64,
    /// When the pulls start, s.
    pull_s: f64,
    /// The left's set force on the tail, N.
    tail_force_n: f64,
}

impl Pulls {
    fn after(s: &Setting, hands: &Hands, run_down_s: f64) -> Self {
        let geometry = s.geometry;
        Self {
            run_down_s,
            pull_s: hands.left.time_s().max(hands.right.time_s()) + 0.3,
            tail_force_n: geometry.tail_pull_force_n.unwrap_or(geometry.pull_force_n),
        }
    }

    /// `track`'s pull to `to` (stitch frame), or on past it within reach (`pull_on_m`), at the same
    /// speed.
    fn pull(&self, s: &Setting, track: &mut TrackBuilder, to: [f64; 3]) {
        let geometry = s.geometry;
        track.wait_until(self.pull_s);
        let (from, to) = (track.position_m(), s.at(to));
        // On level with the tissue: the pulls come down to it, and going on down they pressed the
        // instrument into it (7 N, read as the set force).
        let normal = s.world_from_stitch.rotation * Vector3::z();
        let way = (to - from) - normal * normal.dot(&(to - from));
        let beyond = to + way.try_normalize(1e-12).unwrap_or_default() * geometry.pull_on_m;
        let end = track.reach_towards(beyond);
        let to_target_m = (to - from).norm();
        let stretch = if to_target_m > 1e-9 { (end - from).norm() / to_target_m } else { 1.0 };
        // The jaws keep pointing as they do: turning them along the shaft on the way passes the
        // straight wrist, where the arm crawls and the pull never reaches its force.
        track.go(Path::To(end), s.d(geometry.pull_s) * stretch.max(0.1));
    }

    /// The set-force event of a pull, watched from shortly after it starts to `until_s`.
    fn set_force(&self, s: &Setting, until_s: f64, threshold_n: f64, action: ForceAction) -> ForceEvent {
        let geometry = s.geometry;
        ForceEvent {
            name: SET_FORCE.into(),
            from_s: self.pull_s + s.d(0.5),
            until_s,
            threshold_n,
            sustain_s: geometry.pull_force_sustain_s,
            fires_with: geometry.pulls_stop_together.then(|| SET_FORCE.to_owned()),
            action,
        }
    }

    /// A run-down stopped at its force holds there to the end: going on to the pulls from the
    /// run-down's end would drag what stopped it.
    fn hold_from_run_down(&self, s: &Setting, track: &mut TrackBuilder) {
        if let Some(threshold_n) = s.geometry.run_down_force_n {
            track.event(ForceEvent {
                name: "run-down force".into(),
                from_s: self.run_down_s,
                until_s: track.time_s(),
                threshold_n,
                sustain_s: 0.0,
                fires_with: None,
                action: ForceAction::Hold,
            });
        }
    }
}
