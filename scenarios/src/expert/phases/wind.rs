//! R2: the right winds the long end round the left's jaws, gives a little back and draws the coils
//! towards the jaws' hinge; the assist gives the winding thread meanwhile.

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceAction, ForceEvent};

use super::approach::Winding;
use super::{Hands, Setting};
use crate::expert::motion::Path;

/// The winding as planned: when the right starts to circle and when the coils are wound, s.
pub(crate) struct Wound {
    pub from_s: f64,
    pub wound_s: f64,
    /// Wound in an earlier plan: no tension to keep in this one.
    done: bool,
}

impl Wound {
    /// A winding done before the plan starts (its tension kept no further).
    pub fn done() -> Self {
        Self { from_s: 0.0, wound_s: 0.0, done: true }
    }

    /// The right keeping the long end's tension from the winding's start to `until_s`, if the plan
    /// asks for it ([`crate::expert::geometry::TieGeometry::winding_give_force_n`]). Where the stage
    /// is planned on from the world as it then stands, the tension is kept to the stage's end: the
    /// next stage starts from where the right's tip gave to; cut short, the tip would go back to
    /// its track at once and jerk the taut thread.
    pub fn keep_tension(&self, s: &Setting, hands: &mut Hands, until_s: f64) {
        let geometry = s.geometry;
        if let Some(set_force_n) = geometry.winding_give_force_n.filter(|_| !self.done) {
            hands.right.event(ForceEvent {
                name: "winding tension".into(),
                from_s: self.from_s,
                until_s,
                threshold_n: set_force_n,
                sustain_s: 0.0,
                fires_with: None,
                action: ForceAction::Give {
                    set_force_n,
                    rate_m_per_n_s: geometry.winding_give_rate_m_per_n_s,
                },
            });
        }
    }
}

/// The winding, after the left is at the winding point.
pub(crate) fn wind(s: &Setting, hands: &mut Hands, winding: &Winding) -> Wound {
    let geometry = s.geometry;
    let Hands { left, right, assist } = hands;
    let (centre, axis, advance_m) = (winding.centre_m, winding.axis, winding.advance_m);
    right.wait_until(left.time_s() + s.pause(2));
    let winding_from_s = right.time_s();
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
    Wound { from_s: winding_from_s, wound_s, done: false }
}
