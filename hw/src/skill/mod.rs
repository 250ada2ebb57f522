//! The Skill: what the controller executes, and what the learner produces. Per instrument, a track of
//! time-indexed tip poses, jaw openings and force-triggered events; all tracks share one clock, so
//! keys at equal times happen together (the instruments are synchronised by their timing).
//!
//! - [`keys`]: pose and jaw keys and how the controller interpolates between them.
//! - [`event`]: force-triggered events ("open the jaw when the force exceeds F").
//! - [`profile`]: motion profiles for skill generators (minimum jerk).
//! - [`check`]: the checks a skill must pass before it runs, naming each bad field.
//! - [`preview`]: the kinematic preview: every target reachable, within the joints' limits.
//!
//! Room to grow: events carry names, and what triggers an event is its own type, so a later trigger
//! ("after the other instrument's event N", a wait) can be added without changing the tracks. A skill
//! serialises with serde (field names as here; times in s, positions in m, angles in rad).

pub mod check;
pub mod event;
pub mod keys;
pub mod preview;
pub mod profile;
mod serde_arm;

pub use check::{SkillError, SkillProblem};
pub use event::{ForceAction, ForceEvent};
pub use keys::{JawKey, Orientation, PoseKey};

use serde::{Deserialize, Serialize};

use crate::kinematics::TipTarget;
use crate::rig::ArmName;

/// A skill: one track per instrument (or the endoscope), on one clock starting at 0 s.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Skill {
    /// What the skill does ("square knot, first throw").
    pub name: String,
    /// The tracks, at most one per arm.
    pub tracks: Vec<Track>,
}

/// What one arm does during a skill.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Track {
    /// The arm.
    #[serde(with = "serde_arm")]
    pub arm: ArmName,
    /// Tip poses, world frame, in increasing time (at least one).
    pub poses: Vec<PoseKey>,
    /// Jaw openings in increasing time (none: the jaw stays as it is).
    #[serde(default)]
    pub jaw: Vec<JawKey>,
    /// Force-triggered events.
    #[serde(default)]
    pub events: Vec<ForceEvent>,
}

impl Track {
    /// The tip target at `time_s`: the poses interpolated (see [`keys`]); before the first key the first,
    /// after the last the last.
    pub fn target_at(&self, time_s: f64) -> Option<TipTarget> {
        keys::pose_at(&self.poses, time_s)
    }

    /// The jaw opening at `time_s` (linear between keys), or `None` when the track has no jaw keys.
    pub fn jaw_at(&self, time_s: f64) -> Option<f64> {
        keys::jaw_at(&self.jaw, time_s)
    }

    /// When the track's last key or event window ends, s.
    pub fn end_s(&self) -> f64 {
        let poses = self.poses.last().map_or(0.0, |k| k.time_s);
        let jaw = self.jaw.last().map_or(0.0, |k| k.time_s);
        let events = self.events.iter().map(|e| e.until_s).fold(0.0, f64::max);
        poses.max(jaw).max(events)
    }
}

impl Skill {
    /// When the last track ends, s.
    pub fn duration_s(&self) -> f64 {
        self.tracks.iter().map(Track::end_s).fold(0.0, f64::max)
    }

    /// The track of one arm.
    pub fn track(&self, arm: ArmName) -> Option<&Track> {
        self.tracks.iter().find(|t| t.arm == arm)
    }
}
