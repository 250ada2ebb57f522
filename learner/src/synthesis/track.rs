//! Building one instrument's track of a synthesized skill: pose keys in increasing time (each aimed by a
//! demonstrated frame or the jaws' direction, see [`super::orientation`]), holds, straight
//! minimum-jerk moves.

use nalgebra::Vector3;

use knotlab_hw::kinematics::TipTarget;
use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::profile::min_jerk;
use knotlab_hw::skill::{ForceEvent, JawKey, PoseKey, Track};

use super::orientation::Aim;
use super::site::Reach;

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

    /// How many pose keys the track has.
    pub fn poses_len(&self) -> usize {
        self.poses.len()
    }

    /// Keys from the `from`-th on that `reach` says the instrument cannot take moved back towards the key
    /// before them, as far as it reaches with `margin_m` to spare further along the way (by
    /// bisection), or onto that key where it reaches no further: the instrument goes to the edge of
    /// its reach and waits there until the keys come back within it. Without `reach`, nothing moves.
    pub fn keep_within_reach(&mut self, from: usize, reach: Option<Reach<'_>>, margin_m: f64) {
        let Some(Reach(reaches)) = reach else { return };
        for k in from.max(1)..self.poses.len() {
            let key = self.poses[k];
            let to = Vector3::from(key.world_position_m);
            let takes = |at: Vector3<f64>| {
                reaches(
                    self.arm,
                    &TipTarget { world_position_m: at, orientation: key.orientation.to_tip_orientation() },
                )
            };
            if takes(to) {
                continue;
            }
            let from_m = Vector3::from(self.poses[k - 1].world_position_m);
            let way = to - from_m;
            let length_m = way.norm();
            let beyond = |f: f64| {
                let ahead = if length_m > 1e-12 { way * (margin_m / length_m) } else { Vector3::zeros() };
                takes(from_m + way * f + ahead)
            };
            let mut lo = 0.0;
            if beyond(lo) {
                let mut hi = 1.0;
                for _ in 0..20 {
                    let mid = 0.5 * (lo + hi);
                    if beyond(mid) { lo = mid } else { hi = mid }
                }
            }
            self.poses[k].world_position_m = (from_m + way * lo).into();
        }
        if let Some(last) = self.poses.last() {
            self.position_m = Vector3::from(last.world_position_m);
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

#[cfg(test)]
mod tests {
    use nalgebra::UnitQuaternion;

    use super::*;

    /// Keys beyond the reach stop at its edge, with the margin to spare, and wait there until the keys
    /// come back within it; keys before `from` and keys within the reach stay where they are.
    #[test]
    fn keys_beyond_the_reach_wait_at_its_edge() {
        let aim = Aim::Frame(UnitQuaternion::identity());
        let mut track = TrackKeys::new(ArmName::Left, Vector3::new(0.0, 0.0, 1.0), Vector3::zeros(), aim);
        for (t, x) in [(1.0, 0.05), (2.0, 0.2), (3.0, 0.3), (4.0, 0.06)] {
            track.key(t, Vector3::new(x, 0.0, 0.0), aim);
        }
        let within = |_: ArmName, target: &TipTarget| target.world_position_m.norm() <= 0.1;
        let mut untouched = track.clone();
        untouched.keep_within_reach(1, None, 0.002);
        track.keep_within_reach(1, Some(Reach(&within)), 0.002);
        let x: Vec<f64> = track.clone().build().poses.iter().map(|k| k.world_position_m[0]).collect();
        assert_eq!(x.len(), 5);
        assert_eq!((x[0], x[1], x[4]), (0.0, 0.05, 0.06), "{x:?}");
        for far in &x[2..4] {
            assert!((far - 0.098).abs() < 1e-6, "at the edge with the margin to spare: {x:?}");
        }
        assert_eq!(track.position_m.x, 0.06);
        let before: Vec<f64> = untouched.build().poses.iter().map(|k| k.world_position_m[0]).collect();
        assert_eq!(before, [0.0, 0.05, 0.2, 0.3, 0.06], "without a reach nothing moves");
    }
}
