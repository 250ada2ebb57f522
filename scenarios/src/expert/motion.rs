//! Human-like motion for the scripted expert: minimum-jerk segments (`hw`'s profile), straight or
//! along an arc, a small tremor, and a builder that turns them into a track's time-stamped keys.

use knotlab_hw::kinematics::tool::Tool;
use knotlab_hw::kinematics::{ArmJoints, ArmModel};
use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceEvent, JawKey, Orientation, PoseKey, Track};
use knotlab_sim::world::JAW_CENTRE_OFFSET_M;
use nalgebra::{Point3, Rotation3, UnitQuaternion, UnitVector3, Vector3};

pub use knotlab_hw::skill::profile::min_jerk;

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
    /// Carried with another body: its point `pivot_from_m` moves straight to `pivot_to_m` while it
    /// turns by `rotation` about that point.
    Carried {
        /// The pivot at the start, m.
        pivot_from_m: Vector3<f64>,
        /// ... and at the end, m.
        pivot_to_m: Vector3<f64>,
        /// The body's turn.
        rotation: UnitQuaternion<f64>,
    },
}

/// How the jaws are held during a move.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Hold {
    /// Along the shaft (a straight wrist).
    AlongShaft,
    /// Pointing this way (world frame); the solver picks the roll.
    Pointing(Vector3<f64>),
    /// The whole tip frame, `world_from_tip`.
    Frame(UnitQuaternion<f64>),
}

/// What a builder needs to keep a move within the arm's speed: its model, the joints at the last key,
/// and the fraction of each joint's rated speed a move may ask for.
pub struct Follow {
    /// The arm.
    pub model: ArmModel,
    /// The trocar, world frame, m.
    pub trocar_m: Vector3<f64>,
    /// The joints at the last key.
    pub joints: ArmJoints,
    /// Fraction of the rated joint speeds a move may use.
    pub speed_fraction: f64,
}

impl Follow {
    /// The joints along `keys` (seeded from the last) and how much faster than allowed the fastest joint
    /// goes between keys (1 or less: the arm can follow); `None` if a key is out of reach.
    fn check(&self, keys: &[PoseKey], period_s: f64) -> Option<(ArmJoints, f64)> {
        let mut joints = self.joints;
        let mut worst: f64 = 0.0;
        let mut last_time = None;
        for key in keys {
            let target = knotlab_hw::skill::keys::pose_at(std::slice::from_ref(key), key.time_s)?;
            let next = self.model.solve_tip(&target, &self.trocar_m, &joints).ok()?;
            let dt = last_time.map_or(period_s, |t: f64| (key.time_s - t).max(1e-6));
            for j in 0..6 {
                let allowed = self.model.limits[j].max_velocity_rad_s * self.speed_fraction * dt;
                worst = worst.max((next.arm_rad[j] - joints.arm_rad[j]).abs() / allowed);
            }
            joints = next;
            last_time = Some(key.time_s);
        }
        Some((joints, worst))
    }
}

/// The step along a way at which [`TrackBuilder::reach_towards`] tries the arm's reach, m.
const REACH_STEP_M: f64 = 0.002;

/// How far short of the edge of its reach [`TrackBuilder::reach_towards`] stops an arm, m.
const REACH_MARGIN_M: f64 = 0.01;

/// Builds one arm's track: jaw-centre moves turned into tip keys every `key_period_s`.
pub struct TrackBuilder {
    arm: ArmName,
    /// Where the jaw centre is at `time_s` (world frame, m).
    position_m: Vector3<f64>,
    time_s: f64,
    key_period_s: f64,
    /// The trocar the instrument passes through (world frame, m).
    trocar_m: Vector3<f64>,
    /// How the jaws are held: along the shaft, pointing a way, or a whole frame.
    hold: Hold,
    tremor: Tremor,
    /// The arm's model and its joints at the last key: moves are slowed until the arm can follow.
    follow: Option<Follow>,
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
            hold: Hold::AlongShaft,
            tremor,
            follow: None,
            poses: Vec::new(),
            jaw: vec![JawKey { time_s: 0.0, jaw_rad }],
            events: Vec::new(),
        };
        builder.key(0.0, position_m);
        builder
    }

    /// Slows every later move until the arm can follow it (see [`Follow`]).
    pub fn follow(&mut self, follow: Follow) {
        self.follow = Some(follow);
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
        let key = self.make_key(time_s, centre_m, self.hold);
        self.poses.push(key);
    }

    fn make_key(&self, time_s: f64, centre_m: Vector3<f64>, hold: Hold) -> PoseKey {
        let centre = centre_m + self.tremor.at(time_s);
        let (along, orientation) = match hold {
            Hold::Pointing(d) => {
                (d.normalize(), Orientation::JawDirection { direction: d.normalize().into() })
            }
            Hold::Frame(q) => {
                (q * Vector3::z(), Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] })
            }
            Hold::AlongShaft => ((centre - self.trocar_m).normalize(), Orientation::AlongShaft),
        };
        let tip = centre + along * JAW_CENTRE_OFFSET_M;
        PoseKey { time_s, world_position_m: tip.into(), orientation }
    }

    /// The jaws' direction now.
    pub fn jaw_direction(&self) -> Vector3<f64> {
        match self.hold {
            Hold::Pointing(d) => d.normalize(),
            Hold::Frame(q) => q * Vector3::z(),
            Hold::AlongShaft => (self.position_m - self.trocar_m).normalize(),
        }
    }

    /// The tip frame at the last key, `world_from_tip`, from the arm's model (`None` without one).
    pub fn tip_frame(&self) -> Option<UnitQuaternion<f64>> {
        let follow = self.follow.as_ref()?;
        let r = follow.model.world_from_tip(&follow.joints).rotation;
        Some(UnitQuaternion::from_rotation_matrix(&r))
    }

    /// The instrument's wrist at the last key, from the arm's model: its pitch axis (where the shaft
    /// ends) and its yaw axis (where the jaws hinge), world frame, m (`None` without a model or an
    /// instrument).
    pub fn wrist_m(&self) -> Option<(Vector3<f64>, Vector3<f64>)> {
        let follow = self.follow.as_ref()?;
        let Tool::Instrument { geometry, .. } = follow.model.tool else { return None };
        let shaft = follow.model.shaft_axis(&follow.joints);
        let pitch = shaft.origin_m + shaft.direction * geometry.shaft_m;
        let tip = follow.model.world_from_tip(&follow.joints);
        let yaw = (tip * Point3::new(0.0, 0.0, -geometry.jaw_m)).coords;
        Some((pitch, yaw))
    }

    /// The tip frame the jaws are held in now, `world_from_tip`: the one asked for, or the arm's
    /// model's at the last key (`None` without one).
    pub fn held_frame(&self) -> Option<UnitQuaternion<f64>> {
        match self.hold {
            Hold::Frame(q) => Some(q),
            _ => self.tip_frame(),
        }
    }

    /// Holds the jaws as the arm's model has them at the last key (instead of along the shaft): for a
    /// track that goes on from where another left the instrument. Needs [`TrackBuilder::follow`].
    pub fn hold_as_it_stands(&mut self) {
        let Some(q) = self.tip_frame() else { return };
        self.hold = Hold::Frame(q);
        let key = self.make_key(self.time_s, self.position_m, self.hold);
        if let Some(last) = self.poses.last_mut() {
            *last = key;
        }
    }

    /// Moves along `path` in `duration_s` (minimum jerk) while the jaws turn to point along
    /// `direction` (world frame), with the wrist.
    pub fn go_pointing(&mut self, path: Path, duration_s: f64, direction: Vector3<f64>) {
        let from = self.jaw_direction();
        let to = direction.normalize();
        // Half way between opposite directions their blend is zero: those turn about a side at
        // right angles instead (any will do), through the same half turn.
        let opposite = from.dot(&to) < -1.0 + 1e-9;
        let side = {
            let helper = if from.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
            UnitVector3::new_normalize(from.cross(&helper))
        };
        self.go_with(path, duration_s, |s| {
            Hold::Pointing(if opposite {
                Rotation3::from_axis_angle(&side, std::f64::consts::PI * min_jerk(s)) * from
            } else {
                from.lerp(&to, min_jerk(s))
            })
        });
        self.hold = Hold::Pointing(to);
    }

    /// Moves along `path` in `duration_s` while the jaws turn to point along `direction` (world
    /// frame), the whole tip frame turning by the smallest rotation that does it, so the roll goes
    /// with the jaws instead of being chosen afresh by the solver (which may flip it). Needs the
    /// arm's model ([`TrackBuilder::follow`]) for the frame it starts from, unless one is held.
    pub fn go_turning(&mut self, path: Path, duration_s: f64, direction: Vector3<f64>) {
        let from_jaws = self.jaw_direction();
        let turn = UnitQuaternion::rotation_between(&from_jaws, &direction.normalize())
            .unwrap_or_else(UnitQuaternion::identity);
        match self.held_frame() {
            Some(from) => {
                let to = turn * from;
                self.go_with(path, duration_s, |s| Hold::Frame(from.slerp(&to, min_jerk(s))));
                self.hold = Hold::Frame(to);
            }
            None => self.go_pointing(path, duration_s, direction),
        }
    }

    /// Moves along `path` while the tip frame turns to `world_from_tip` (the jaws along its z, their
    /// hinge along its y). Needs the arm's model ([`TrackBuilder::follow`]) for the frame it starts from.
    pub fn go_framing(&mut self, path: Path, duration_s: f64, world_from_tip: Rotation3<f64>) {
        let to = UnitQuaternion::from_rotation_matrix(&world_from_tip);
        let from = match self.hold {
            Hold::Frame(q) => q,
            _ => self.tip_frame().unwrap_or(to),
        };
        self.go_with(path, duration_s, |s| Hold::Frame(from.slerp(&to, min_jerk(s))));
        self.hold = Hold::Frame(to);
    }

    /// Whether the arm reaches every pose of a straight move to `end_m` turning to `world_from_tip`
    /// (as [`TrackBuilder::go_framing`] would ask; true without the arm's model: nothing to check).
    pub fn reaches_framing(&self, end_m: Vector3<f64>, world_from_tip: Rotation3<f64>) -> bool {
        let Some(follow) = &self.follow else { return true };
        let to = UnitQuaternion::from_rotation_matrix(&world_from_tip);
        let from = self.held_frame().unwrap_or(to);
        let start = self.position_m;
        const STEPS: usize = 50;
        let keys: Vec<PoseKey> = (1..=STEPS)
            .map(|i| {
                let s = min_jerk(i as f64 / STEPS as f64);
                self.make_key(
                    self.time_s + i as f64,
                    start + (end_m - start) * s,
                    Hold::Frame(from.slerp(&to, s)),
                )
            })
            .collect();
        follow.check(&keys, 1.0).is_some()
    }

    /// The furthest point of the straight way from the jaw centre to `end_m` that the arm reaches
    /// holding its jaws as they are: `end_m` when it reaches it; else `REACH_MARGIN_M` short of the
    /// first point it cannot reach (the instrument's insertion or the arm's own reach: held at the
    /// edge of its reach, its elbow nearly straight, the left's jaws jumped 5 mm about the hold and
    /// tore the tail out of them).
    pub fn reach_towards(&self, end_m: Vector3<f64>) -> Vector3<f64> {
        let Some(follow) = &self.follow else { return end_m };
        let start = self.position_m;
        let length_m = (end_m - start).norm();
        let steps = (length_m / REACH_STEP_M).ceil().max(1.0) as usize;
        let point = |i: usize| start + (end_m - start) * (i as f64 / steps as f64);
        let mut joints = follow.joints;
        for i in 1..=steps {
            let key = self.make_key(self.time_s, point(i), self.hold);
            let solved = knotlab_hw::skill::keys::pose_at(std::slice::from_ref(&key), key.time_s)
                .and_then(|target| follow.model.solve_tip(&target, &follow.trocar_m, &joints).ok());
            match solved {
                Some(next) => joints = next,
                None => {
                    let reached = point(i - 1);
                    let back = (reached - start).norm().min(REACH_MARGIN_M);
                    return reached - (end_m - start).normalize() * back;
                }
            }
        }
        end_m
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
        let hold = self.hold;
        self.go_with(path, duration_s, |_| hold);
    }

    fn go_with(&mut self, path: Path, duration_s: f64, hold: impl Fn(f64) -> Hold) {
        let start = self.position_m;
        let at = |s: f64| -> Vector3<f64> {
            match path {
                Path::To(end) => start + (end - start) * min_jerk(s),
                Path::Around { centre_m, axis, turns, pitch_m } => {
                    let angle = std::f64::consts::TAU * turns * min_jerk(s);
                    let rotation = Rotation3::from_axis_angle(&axis, angle);
                    let along = axis.into_inner() * pitch_m * turns * min_jerk(s);
                    centre_m + rotation * (start - centre_m) + along
                }
                Path::Carried { pivot_from_m, pivot_to_m, rotation } => {
                    let turned = UnitQuaternion::identity().slerp(&rotation, min_jerk(s));
                    pivot_from_m + (pivot_to_m - pivot_from_m) * min_jerk(s) + turned * (start - pivot_from_m)
                }
            }
        };
        let t0 = self.time_s;
        let asked_s = duration_s.max(self.key_period_s);
        let mut duration_s = asked_s;
        // Slower until the arm can follow (at most 30 times the asked duration). A jump that slowing
        // does not shrink is a discontinuity of the solution, not a speed: slowing stops there.
        let mut last_worst = f64::INFINITY;
        let keys = loop {
            let steps = (duration_s / self.key_period_s).ceil().max(1.0) as usize;
            let keys: Vec<PoseKey> = (1..=steps)
                .map(|i| {
                    let s = i as f64 / steps as f64;
                    self.make_key(t0 + s * duration_s, at(s), hold(s))
                })
                .collect();
            let Some(follow) = &self.follow else { break keys };
            // Out of reach: keep the keys, the controller will say so.
            let Some((joints, worst)) = follow.check(&keys, self.key_period_s) else { break keys };
            if worst <= 1.0 || duration_s >= 30.0 * asked_s || worst > 0.7 * last_worst {
                if let Some(f) = &mut self.follow {
                    f.joints = joints;
                }
                break keys;
            }
            last_worst = worst;
            duration_s *= worst.min(8.0) * 1.05;
        };
        self.poses.extend(keys);
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

    /// A circular path of whole turns ends where it began, a key per 10 ms, its jaw centres on the circle.
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

    fn quaternion_of(key: &PoseKey) -> UnitQuaternion<f64> {
        match key.orientation {
            Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
            }
            ref other => panic!("a whole frame, not {other:?}"),
        }
    }

    /// Turning the jaws to a new direction carries their roll along: every key holds a whole frame with the
    /// hinge along -z.
    #[test]
    fn turning_the_jaws_carries_their_roll_along() {
        let mut b = TrackBuilder::new(
            ArmName::Left,
            Vector3::zeros(),
            0.0,
            0.01,
            Tremor::none(),
            Vector3::new(0.0, 0.0, 1.0),
        );
        // A frame with the jaws along x and the hinge along z, then the jaws turned to y.
        let frame = Rotation3::from_basis_unchecked(&[-Vector3::y(), -Vector3::z(), Vector3::x()]);
        b.go_framing(Path::To(Vector3::zeros()), 0.5, frame);
        b.go_turning(Path::To(Vector3::new(0.0, 0.0, -0.01)), 1.0, Vector3::y());
        let track = b.build();
        let last = quaternion_of(track.poses.last().expect("keys"));
        assert!((last * Vector3::z() - Vector3::y()).norm() < 1e-9, "the jaws along y");
        // Turned about z (x to y), the hinge stays along -z: the roll went with the jaws.
        assert!((last * Vector3::y() + Vector3::z()).norm() < 1e-9, "the hinge {:?}", last * Vector3::y());
        // On the way every key holds a whole frame, the hinge along -z throughout.
        for key in &track.poses[51..] {
            assert!((quaternion_of(key) * Vector3::y() + Vector3::z()).norm() < 1e-9);
        }
    }
}
