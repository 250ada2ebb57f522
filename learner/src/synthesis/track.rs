//! Building one instrument's track of a synthesized skill: pose keys in increasing time (each aimed by a
//! demonstrated frame or the jaws' direction, see [`super::orientation`]), holds, straight
//! minimum-jerk moves.

use nalgebra::Vector3;

use knotlab_hw::kinematics::TipTarget;
use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::profile::min_jerk;
use knotlab_hw::skill::{ForceEvent, JawKey, PoseKey, Track};

use super::orientation::Aim;

/// Keys closer in time than this are one key, s.
const SAME_TIME_S: f64 = 1e-6;

/// One instrument's track, being built.
#[derive(Clone, Debug)]
pub struct TrackKeys {
    /// The instrument.
    pub arm: ArmName,
    trocar_m: Vector3<f64>,
    poses: Vec<PoseKey>,
    /// Where the tip is at the last key, m.
    pub position_m: Vector3<f64>,
    /// How the last key aims the tip.
    pub aim: Aim,
    /// Time of the last key, s.
    pub time_s: f64,
    /// Jaw keys (sorted when the track is built).
    pub jaw: Vec<JawKey>,
    /// Force events.
    pub events: Vec<ForceEvent>,
}

impl TrackKeys {
    /// A track whose first key, at 0 s, is the tip where it is.
    pub fn new(arm: ArmName, trocar_m: Vector3<f64>, position_m: Vector3<f64>, aim: Aim) -> Self {
        let mut track = Self {
            arm,
            trocar_m,
            poses: Vec::new(),
            position_m,
            aim,
            time_s: 0.0,
            jaw: Vec::new(),
            events: Vec::new(),
        };
        track.key(0.0, position_m, aim);
        track
    }

    /// A key at `time_s` (a key at the same time as the last replaces it; an earlier one is dropped).
    pub fn key(&mut self, time_s: f64, position_m: Vector3<f64>, aim: Aim) {
        let orientation = aim.orientation(&position_m, &self.trocar_m);
        let key = PoseKey { time_s, world_position_m: position_m.into(), orientation };
        match self.poses.last() {
            Some(last) if time_s < last.time_s - SAME_TIME_S => return,
            Some(last) if time_s <= last.time_s + SAME_TIME_S => {
                let n = self.poses.len();
                self.poses[n - 1] = PoseKey { time_s: last.time_s, ..key };
            }
            _ => self.poses.push(key),
        }
        self.position_m = position_m;
        if aim.jaws().norm() > 1e-12 {
            self.aim = aim;
        }
        self.time_s = self.time_s.max(time_s);
    }

    /// The tip target a key at `position_m` aimed by `aim` asks of the arm.
    pub fn target(&self, position_m: Vector3<f64>, aim: Aim) -> TipTarget {
        TipTarget {
            world_position_m: position_m,
            orientation: aim.orientation(&position_m, &self.trocar_m).to_tip_orientation(),
        }
    }

    /// Stays where it is until `time_s`.
    pub fn hold_until(&mut self, time_s: f64) {
        if time_s > self.time_s + SAME_TIME_S {
            self.key(time_s, self.position_m, self.aim);
        }
    }

    /// A straight minimum-jerk move from where it is, ending at `end_s` (starting at the last key).
    pub fn move_to(&mut self, end_s: f64, to_m: Vector3<f64>, to_aim: Aim, keys: usize) {
        let (t0, from, from_aim) = (self.time_s, self.position_m, self.aim);
        if end_s <= t0 + SAME_TIME_S {
            self.key(t0, to_m, to_aim);
            return;
        }
        let n = keys.max(2);
        for k in 1..=n {
            let f = k as f64 / n as f64;
            let s = min_jerk(f);
            self.key(t0 + (end_s - t0) * f, from.lerp(&to_m, s), from_aim.towards(&to_aim, s));
        }
    }

    /// The finished track: jaw keys sorted, those at one time merged (the later wins).
    pub fn build(mut self) -> Track {
        self.jaw.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        let mut jaw: Vec<JawKey> = Vec::with_capacity(self.jaw.len());
        for key in self.jaw {
            match jaw.last_mut() {
                Some(last) if key.time_s <= last.time_s + SAME_TIME_S => last.jaw_rad = key.jaw_rad,
                _ => jaw.push(key),
            }
        }
        Track { arm: self.arm, poses: self.poses, jaw, events: self.events }
    }
}
