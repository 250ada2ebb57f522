//! Human-like motion for the scripted expert: minimum-jerk segments (straight or along an arc), a small
//! tremor, and a builder that turns them into a track's time-stamped keys.

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceEvent, JawKey, Orientation, PoseKey, Track};
use knotlab_sim::world::JAW_CENTRE_OFFSET_M;
use nalgebra::{UnitVector3, Vector3};

/// Minimum-jerk blend from 0 to 1 (Flash and Hogan's profile of a reaching hand).
pub fn min_jerk(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
}

/// Physiological tremor: a sum of three sines between 8 and 12 Hz per axis, of a given amplitude.
#[derive(Clone, Debug, PartialEq)]
pub struct Tremor {
    /// Peak amplitude of each sine, m.
    pub amplitude_m: f64,
    /// Frequency, Hz, and phase, rad, of each sine per axis.
    pub sines: [[(f64, f64); 3]; 3],
}

impl Tremor {
    /// No tremor.
    pub fn none() -> Self {
        Self { amplitude_m: 0.0, sines: [[(10.0, 0.0); 3]; 3] }
    }

    /// The tremor's offset at a time, m.
    pub fn at(&self, time_s: f64) -> Vector3<f64> {
        if self.amplitude_m == 0.0 {
            return Vector3::zeros();
        }
        Vector3::from_fn(|axis, _| {
            self.sines[axis]
                .iter()
                .map(|(f, phase)| (std::f64::consts::TAU * f * time_s + phase).sin())
                .sum::<f64>()
                * self.amplitude_m
                / 3.0
        })
    }
}

/// Where a move goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Path {
    /// A straight line to a point (world frame, m).
    To(Vector3<f64>),
    /// Turns about an axis through a centre (world frame): the point circles it at its present
    /// distance, right-handed about the axis, `turns` times (fractions allowed), rising by `pitch_m`
    /// along the axis per turn.
    Around {
        /// A point on the axis, m.
        centre_m: Vector3<f64>,
        /// The axis.
        axis: UnitVector3<f64>,
        /// How many turns.
        turns: f64,
        /// Advance along the axis per turn, m.
        pitch_m: f64,
    },
}

/// Builds one arm's track: jaw-centre moves turned into tip keys every `key_period_s`.
pub struct TrackBuilder {
    arm: ArmName,
    /// Where the jaw centre is at `time_s` (world frame, m).
    position_m: Vector3<f64>,
    time_s: f64,
    key_period_s: f64,
    /// The trocar the instrument passes through (world frame, m).
    trocar_m: Vector3<f64>,
    /// Where the jaws point (world frame), or `None`: along the shaft.
    jaw_direction: Option<Vector3<f64>>,
    tremor: Tremor,
    poses: Vec<PoseKey>,
    jaw: Vec<JawKey>,
    events: Vec<ForceEvent>,
}

impl TrackBuilder {
    /// A track starting at `position_m` (the jaw centre, world frame) with the jaws at `jaw_rad` at
    /// time 0.
    pub fn new(
        arm: ArmName,
        position_m: Vector3<f64>,
        jaw_rad: f64,
        key_period_s: f64,
        tremor: Tremor,
        trocar_m: Vector3<f64>,
    ) -> Self {
        let mut builder = Self {
            arm,
            position_m,
            time_s: 0.0,
            key_period_s,
            trocar_m,
            jaw_direction: None,
            tremor,
            poses: Vec::new(),
            jaw: vec![JawKey { time_s: 0.0, jaw_rad }],
            events: Vec::new(),
        };
        builder.key(0.0, position_m);
        builder
    }

    /// The arm.
    pub fn arm(&self) -> ArmName {
        self.arm
    }

    /// The jaw centre now, world frame, m.
    pub fn position_m(&self) -> Vector3<f64> {
        self.position_m
    }

    /// The track's time now, s.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    fn key(&mut self, time_s: f64, centre_m: Vector3<f64>) {
        self.key_pointing(time_s, centre_m, self.jaw_direction);
    }

    /// A key with the jaw centre at `centre_m` and the jaws along `direction` (`None`: the shaft).
    fn key_pointing(&mut self, time_s: f64, centre_m: Vector3<f64>, direction: Option<Vector3<f64>>) {
        let centre = centre_m + self.tremor.at(time_s);
        let (along, orientation) = match direction {
            Some(d) => (d.normalize(), Orientation::JawDirection { direction: d.normalize().into() }),
            None => ((centre - self.trocar_m).normalize(), Orientation::AlongShaft),
        };
        let tip = centre + along * JAW_CENTRE_OFFSET_M;
        self.poses.push(PoseKey { time_s, world_position_m: tip.into(), orientation });
    }

    /// The jaws' direction now: the one set, or along the shaft.
    pub fn jaw_direction(&self) -> Vector3<f64> {
        self.jaw_direction.unwrap_or_else(|| (self.position_m - self.trocar_m).normalize())
    }

    /// Moves along `path` in `duration_s` (minimum jerk) while the jaws turn to point along
    /// `direction` (world frame), with the wrist.
    pub fn go_pointing(&mut self, path: Path, duration_s: f64, direction: Vector3<f64>) {
        let from = self.jaw_direction();
        let to = direction.normalize();
        let t0 = self.time_s;
        let start = self.position_m;
        self.go_with(path, duration_s, |s| Some(from.lerp(&to, min_jerk(s))));
        debug_assert!(self.time_s > t0 || duration_s <= 0.0 || start == self.position_m);
        self.jaw_direction = Some(to);
    }

    /// Holds still until `time_s` (a pause, or waiting for another instrument).
    pub fn wait_until(&mut self, time_s: f64) {
        while self.time_s + self.key_period_s < time_s {
            self.time_s += self.key_period_s;
            self.key(self.time_s, self.position_m);
        }
        if time_s > self.time_s {
            self.time_s = time_s;
            self.key(time_s, self.position_m);
        }
    }

    /// Moves along `path` in `duration_s` with a minimum-jerk profile, the jaws as they point.
    pub fn go(&mut self, path: Path, duration_s: f64) {
        let direction = self.jaw_direction;
        self.go_with(path, duration_s, |_| direction);
    }

    fn go_with(&mut self, path: Path, duration_s: f64, direction: impl Fn(f64) -> Option<Vector3<f64>>) {
        let start = self.position_m;
        let at = |s: f64| -> Vector3<f64> {
            match path {
                Path::To(end) => start + (end - start) * min_jerk(s),
                Path::Around { centre_m, axis, turns, pitch_m } => {
                    let angle = std::f64::consts::TAU * turns * min_jerk(s);
                    let rotation = nalgebra::Rotation3::from_axis_angle(&axis, angle);
                    let along = axis.into_inner() * pitch_m * turns * min_jerk(s);
                    centre_m + rotation * (start - centre_m) + along
                }
            }
        };
        let steps = (duration_s / self.key_period_s).ceil().max(1.0) as usize;
        let t0 = self.time_s;
        for i in 1..=steps {
            let s = i as f64 / steps as f64;
            self.key_pointing(t0 + s * duration_s, at(s), direction(s));
        }
        self.time_s = t0 + duration_s;
        self.position_m = at(1.0);
    }

    /// Sets the jaw opening, reached over `duration_s` from now (the track's time does not advance).
    pub fn jaw(&mut self, jaw_rad: f64, duration_s: f64) {
        let from = self.jaw.last().map_or(jaw_rad, |k| k.jaw_rad);
        self.jaw.push(JawKey { time_s: self.time_s, jaw_rad: from });
        self.jaw.push(JawKey { time_s: self.time_s + duration_s, jaw_rad });
    }

    /// Adds a force-triggered event.
    pub fn event(&mut self, event: ForceEvent) {
        self.events.push(event);
    }

    /// The track.
    pub fn build(self) -> Track {
        Track { arm: self.arm, poses: self.poses, jaw: self.jaw, events: self.events }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_jerk_starts_and_ends_at_rest() {
        assert_eq!(min_jerk(0.0), 0.0);
        assert_eq!(min_jerk(1.0), 1.0);
        assert!((min_jerk(0.5) - 0.5).abs() < 1e-12);
        let h = 1e-6;
        assert!((min_jerk(h) - min_jerk(0.0)) / h < 1e-6, "no speed at the start");
    }

    #[test]
    fn a_circle_comes_back_after_whole_turns() {
        let mut b = TrackBuilder::new(
            ArmName::Right,
            Vector3::new(0.02, 0.0, 0.0),
            0.0,
            0.01,
            Tremor::none(),
            Vector3::new(0.0, 0.0, 1.0),
        );
        b.go(
            Path::Around { centre_m: Vector3::zeros(), axis: Vector3::z_axis(), turns: 2.0, pitch_m: 0.0 },
            2.0,
        );
        assert!((b.position_m() - Vector3::new(0.02, 0.0, 0.0)).norm() < 1e-12);
        let track = b.build();
        // Tips are 5 mm past the jaw centre, away from the trocar: the jaw centres stay on the circle.
        let radii: Vec<f64> = track
            .poses
            .iter()
            .map(|k| {
                let tip = Vector3::from(k.world_position_m);
                let centre = tip - (tip - Vector3::new(0.0, 0.0, 1.0)).normalize() * JAW_CENTRE_OFFSET_M;
                centre.norm()
            })
            .collect();
        assert!(radii.iter().all(|r| (r - 0.02).abs() < 1e-3), "{radii:?}");
        assert_eq!(track.poses.len(), 201);
    }
}
