//! How a synthesized key orients the tip. A key that knows the demonstrated frame ([`Aim::Frame`])
//! commands it whole where the wrist is bent within its reach ([`recorded_orientation`]): the roll of
//! jaws with thread wound round them winds or unwinds it. Elsewhere only the jaws' direction is
//! commanded, never the roll about it: near the straight-wrist singularity a tenth of a degree of
//! tremor asks for a half turn of the roll joint, and the arm lags centimetres behind. A nearly
//! straight wrist is commanded straight, and one bent further than the wrist can bend (a skill turned
//! with a moved stitch can ask for that) is bent as far as it can.

use nalgebra::{UnitQuaternion, Vector3};

use knotlab_hw::skill::Orientation;

/// What a synthesized key asks of the tip's orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Aim {
    /// The jaws point along this direction, world frame (the roll is the solver's).
    Jaws(Vector3<f64>),
    /// The demonstrated frame, `world_from_tip` (its z along the jaws).
    Frame(UnitQuaternion<f64>),
}

impl Aim {
    /// Where the jaws point (unit, or zero for a zero direction).
    pub fn jaws(&self) -> Vector3<f64> {
        match self {
            Aim::Jaws(d) => d.try_normalize(1e-12).unwrap_or_else(Vector3::zeros),
            Aim::Frame(q) => q * Vector3::z(),
        }
    }

    /// `f` of the way from this aim to `to` (0: this, 1: `to`): two frames turn along the shortest arc
    /// between them, anything else turns the jaws' direction.
    pub fn towards(&self, to: &Aim, f: f64) -> Aim {
        match (self, to) {
            (Aim::Frame(a), Aim::Frame(b)) => {
                Aim::Frame(a.try_slerp(b, f, 1e-9).unwrap_or(if f < 0.5 { *a } else { *b }))
            }
            _ => Aim::Jaws(self.jaws().lerp(&to.jaws(), f)),
        }
    }

    /// The key's orientation with the tip at `tip_m` and the shaft through `trocar_m`.
    pub fn orientation(&self, tip_m: &Vector3<f64>, trocar_m: &Vector3<f64>) -> Orientation {
        match self {
            Aim::Jaws(d) => jaw_orientation(d, tip_m, trocar_m),
            Aim::Frame(q) => recorded_orientation(q, tip_m, trocar_m),
        }
    }
}

/// A wrist bent less than this is commanded straight, rad.
pub const STRAIGHT_WRIST_RAD: f64 = 0.05;

/// The most a key bends the jaws away from the line from the trocar to the tip, rad: the shipped
/// instruments' wrist yaw limit (1.396 rad, which takes the whole bend of a jaw-direction key), less
/// 0.15 rad for the shaft, which runs through the wrist's pitch axis, not through the tip.
pub const MAX_WRIST_BEND_RAD: f64 = 1.25;

/// The orientation of a key whose jaws point along `jaw_direction`, the tip at `tip_m` and the shaft
/// through `trocar_m`.
pub fn jaw_orientation(
    jaw_direction: &Vector3<f64>,
    tip_m: &Vector3<f64>,
    trocar_m: &Vector3<f64>,
) -> Orientation {
    let shaft = tip_m - trocar_m;
    match (jaw_direction.try_normalize(1e-12), shaft.try_normalize(1e-9)) {
        (Some(jaw), Some(shaft)) if jaw.angle(&shaft) >= STRAIGHT_WRIST_RAD => {
            let bend = jaw.angle(&shaft);
            let jaw = if bend > MAX_WRIST_BEND_RAD {
                // Turned back towards the shaft in their common plane.
                let across = (jaw - shaft * jaw.dot(&shaft)).normalize();
                shaft * MAX_WRIST_BEND_RAD.cos() + across * MAX_WRIST_BEND_RAD.sin()
            } else {
                jaw
            };
            Orientation::JawDirection { direction: jaw.into() }
        }
        _ => Orientation::AlongShaft,
    }
}

/// The orientation of a key with a demonstrated frame: the tip frame `world_from_tip` whole where the
/// wrist is bent between straight ([`STRAIGHT_WRIST_RAD`]) and its reach ([`MAX_WRIST_BEND_RAD`]),
/// otherwise as [`jaw_orientation`] has it. Played back by their direction only, the right's jaws,
/// which the long end's turns go round, roll otherwise than recorded and the needle is torn out of
/// them (15.7 N) as the left comes down onto the tail (the canonical demonstration replayed at its own
/// stitch; the fluid and DMP skills the same, 17.4 and 26.5 N).
pub fn recorded_orientation(
    world_from_tip: &UnitQuaternion<f64>,
    tip_m: &Vector3<f64>,
    trocar_m: &Vector3<f64>,
) -> Orientation {
    let jaw = world_from_tip * Vector3::z();
    match (tip_m - trocar_m).try_normalize(1e-9) {
        Some(shaft) if (STRAIGHT_WRIST_RAD..=MAX_WRIST_BEND_RAD).contains(&jaw.angle(&shaft)) => {
            let q = world_from_tip.quaternion();
            Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] }
        }
        _ => jaw_orientation(&jaw, tip_m, trocar_m),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bent wrist keeps its jaw direction, a nearly straight one is left along the shaft, and one asked to
    /// bend past its reach bends only as far as it can, in the same plane.
    #[test]
    fn a_bent_wrist_keeps_its_direction_and_a_straight_one_follows_the_shaft() {
        let trocar = Vector3::new(0.0, 0.0, 1.0);
        let tip = Vector3::new(0.0, 0.0, 0.9);
        let bent = Vector3::new(0.3, 0.0, -1.0);
        assert_eq!(
            jaw_orientation(&bent, &tip, &trocar),
            Orientation::JawDirection { direction: bent.normalize().into() }
        );
        let nearly = Vector3::new(0.01, 0.0, -1.0);
        assert_eq!(jaw_orientation(&nearly, &tip, &trocar), Orientation::AlongShaft);
        // Bent past what the wrist can do (here 100 degrees from the shaft): bent as far as it can, in
        // the same plane.
        let over = Vector3::new(1.0, 0.0, 0.18);
        let Orientation::JawDirection { direction } = jaw_orientation(&over, &tip, &trocar) else {
            panic!("a bent wrist keeps a jaw direction");
        };
        let d = Vector3::from(direction);
        assert!((d.angle(&-Vector3::z()) - MAX_WRIST_BEND_RAD).abs() < 1e-12, "{d:?}");
        assert!(d.y.abs() < 1e-12 && d.x > 0.0, "{d:?}");
    }

    /// A recorded key with the wrist bent within reach keeps its whole frame, roll included; nearly straight
    /// it goes along the shaft, and bent past reach it becomes the jaw direction bent as far as it can.
    #[test]
    fn a_replayed_key_keeps_the_recorded_frame_where_the_wrist_is_bent_within_reach() {
        let trocar = Vector3::new(0.0, 0.0, 1.0);
        let tip = Vector3::new(0.0, 0.0, 0.9);
        // The jaws (the frame's z) turned 0.5 rad from the shaft's -z, and rolled about themselves.
        let frame_turned = |bend_rad: f64| {
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI - bend_rad)
                * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.7)
        };
        let bent = frame_turned(0.5);
        let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = recorded_orientation(&bent, &tip, &trocar)
        else {
            panic!("a bent wrist keeps its frame");
        };
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        assert!(q.angle_to(&bent) < 1e-12, "{q:?} against {bent:?}");
        // Nearly straight: along the shaft, the roll left to the solver.
        assert_eq!(recorded_orientation(&frame_turned(0.01), &tip, &trocar), Orientation::AlongShaft);
        // Bent past its reach: as a jaw direction, bent as far as it can.
        let over = frame_turned(1.5);
        assert_eq!(
            recorded_orientation(&over, &tip, &trocar),
            jaw_orientation(&(over * Vector3::z()), &tip, &trocar)
        );
    }
}
