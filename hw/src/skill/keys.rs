//! Pose and jaw keys, and interpolation between them.
//!
//! Positions interpolate linearly. Orientations interpolate when two neighbouring keys are of one kind:
//! jaw directions by normalised linear interpolation, full frames by spherical linear interpolation of
//! their quaternions; between keys of different kinds the earlier key's orientation holds until the
//! later key. Jaw openings interpolate linearly. Lookups are binary searches: no allocation.

use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use crate::kinematics::{TipOrientation, TipTarget};

/// How the tip is to be oriented at a key.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Orientation {
    /// Jaws along the line from the trocar to the tip (a straight wrist); the endoscope's only choice.
    #[default]
    AlongShaft,
    /// Jaws pointing this way (world frame, any length but zero); the solver picks the rest.
    JawDirection {
        /// The direction.
        direction: [f64; 3],
    },
    /// The whole tip frame (z the jaw direction, y the wrist yaw axis) as a unit quaternion.
    Frame {
        /// world_from_tip rotation, x, y, z, w.
        quaternion_xyzw: [f64; 4],
    },
}

impl Orientation {
    /// As the kinematics takes it.
    pub fn to_tip_orientation(&self) -> TipOrientation {
        match *self {
            Orientation::AlongShaft => TipOrientation::AlongShaft,
            Orientation::JawDirection { direction } => TipOrientation::JawDirection(Vector3::from(direction)),
            Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => TipOrientation::Frame(
                UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)).to_rotation_matrix(),
            ),
        }
    }
}

/// A tip pose at a time.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PoseKey {
    /// Time from the skill's start, s.
    pub time_s: f64,
    /// Tip position, world frame, m.
    pub world_position_m: [f64; 3],
    /// Tip orientation.
    #[serde(default)]
    pub orientation: Orientation,
}

/// A jaw opening at a time.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct JawKey {
    /// Time from the skill's start, s.
    pub time_s: f64,
    /// Angle between the jaws, rad (0 closed).
    pub jaw_rad: f64,
}

/// The pair of keys around `time_s` and the fraction between them (0 at the first).
fn bracket<K>(keys: &[K], time_s: f64, time_of: impl Fn(&K) -> f64) -> Option<(&K, &K, f64)> {
    let first = keys.first()?;
    let after = keys.partition_point(|k| time_of(k) <= time_s);
    if after == 0 {
        return Some((first, first, 0.0));
    }
    let a = &keys[after - 1];
    let Some(b) = keys.get(after) else { return Some((a, a, 0.0)) };
    let span = time_of(b) - time_of(a);
    let f = if span > 0.0 { ((time_s - time_of(a)) / span).clamp(0.0, 1.0) } else { 1.0 };
    Some((a, b, f))
}

fn interpolate_orientation(a: &Orientation, b: &Orientation, f: f64) -> Orientation {
    match (a, b) {
        (Orientation::JawDirection { direction: da }, Orientation::JawDirection { direction: db }) => {
            let (va, vb) = (Vector3::from(*da), Vector3::from(*db));
            let (na, nb) = (va.norm(), vb.norm());
            let mixed = (va / na).lerp(&(vb / nb), f);
            if mixed.norm() > 1e-9 { Orientation::JawDirection { direction: mixed.into() } } else { *b }
        }
        (Orientation::Frame { quaternion_xyzw: qa }, Orientation::Frame { quaternion_xyzw: qb }) => {
            let unit = |[x, y, z, w]: [f64; 4]| UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z));
            let q = unit(*qa).slerp(&unit(*qb), f);
            Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] }
        }
        _ if f >= 1.0 => *b,
        _ => *a,
    }
}

/// The interpolated tip target at `time_s` (`None` without keys).
pub fn pose_at(keys: &[PoseKey], time_s: f64) -> Option<TipTarget> {
    let (a, b, f) = bracket(keys, time_s, |k| k.time_s)?;
    let pa = Vector3::from(a.world_position_m);
    let pb = Vector3::from(b.world_position_m);
    let orientation = interpolate_orientation(&a.orientation, &b.orientation, f);
    Some(TipTarget { world_position_m: pa.lerp(&pb, f), orientation: orientation.to_tip_orientation() })
}

/// The interpolated jaw opening at `time_s` (`None` without keys).
pub fn jaw_at(keys: &[JawKey], time_s: f64) -> Option<f64> {
    let (a, b, f) = bracket(keys, time_s, |k| k.time_s)?;
    Some(a.jaw_rad + (b.jaw_rad - a.jaw_rad) * f)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(time_s: f64, x: f64, orientation: Orientation) -> PoseKey {
        PoseKey { time_s, world_position_m: [x, 0.0, 1.0], orientation }
    }

    /// Positions interpolate linearly between keys and hold the first and last key outside them; without
    /// keys there is no pose.
    #[test]
    fn positions_interpolate_linearly_and_hold_outside_the_keys() {
        let keys = [key(0.0, 0.0, Orientation::AlongShaft), key(2.0, 0.2, Orientation::AlongShaft)];
        let at = |t: f64| pose_at(&keys, t).unwrap().world_position_m.x;
        assert!((at(0.5) - 0.05).abs() < 1e-12);
        assert!((at(-1.0) - 0.0).abs() < 1e-12);
        assert!((at(5.0) - 0.2).abs() < 1e-12);
        assert!(pose_at(&[], 0.0).is_none());
    }

    /// Two frame keys a quarter turn apart slerp to an eighth of a turn halfway between them.
    #[test]
    fn frames_slerp_halfway() {
        let half = std::f64::consts::FRAC_PI_4;
        let keys = [
            key(0.0, 0.0, Orientation::Frame { quaternion_xyzw: [0.0, 0.0, 0.0, 1.0] }),
            key(1.0, 0.0, Orientation::Frame { quaternion_xyzw: [0.0, 0.0, half.sin(), half.cos()] }),
        ];
        let TipOrientation::Frame(r) = pose_at(&keys, 0.5).unwrap().orientation else { panic!("a frame") };
        assert!((r.angle() - std::f64::consts::FRAC_PI_4).abs() < 1e-12, "{}", r.angle());
    }

    /// Jaw directions of different lengths turn halfway between their unit directions; between keys of
    /// different kinds the earlier orientation holds until the later key's time.
    #[test]
    fn jaw_directions_turn_and_mixed_kinds_step() {
        let a = Orientation::JawDirection { direction: [1.0, 0.0, 0.0] };
        let b = Orientation::JawDirection { direction: [0.0, 2.0, 0.0] };
        let Orientation::JawDirection { direction } = interpolate_orientation(&a, &b, 0.5) else {
            panic!("a direction")
        };
        assert!((direction[0] - direction[1]).abs() < 1e-12 && direction[0] > 0.0);
        assert_eq!(interpolate_orientation(&a, &Orientation::AlongShaft, 0.7), a);
        assert_eq!(interpolate_orientation(&a, &Orientation::AlongShaft, 1.0), Orientation::AlongShaft);
    }

    /// Jaw openings interpolate linearly between keys and hold outside them; without keys there is none.
    #[test]
    fn jaw_openings_interpolate() {
        let keys = [JawKey { time_s: 1.0, jaw_rad: 0.6 }, JawKey { time_s: 2.0, jaw_rad: 0.0 }];
        assert_eq!(jaw_at(&keys, 0.0), Some(0.6));
        assert!((jaw_at(&keys, 1.5).unwrap() - 0.3).abs() < 1e-12);
        assert_eq!(jaw_at(&keys, 3.0), Some(0.0));
        assert_eq!(jaw_at(&[], 1.0), None);
    }
}
