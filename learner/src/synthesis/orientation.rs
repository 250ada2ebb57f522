//! How a synthesized key orients the tip. A key that knows the demonstrated frame ([`Aim::Frame`])
//! commands it whole ([`recorded_orientation`]): the roll of jaws with thread wound round them winds
//! or unwinds it. Bent further than the wrist can bend (a skill turned with a moved stitch can ask for
//! that), the frame is turned back to the wrist's reach, so that a path crossing the reach goes on
//! without a jump. A key that knows only the jaws' direction commands that, never the roll about it,
//! bent as far as the wrist can. Near the straight-wrist singularity a tenth of a degree of tremor
//! asks for a half turn of the roll joint, and the arm lags centimetres behind: a nearly straight
//! wrist is commanded straight.

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
/// wrist is bent between straight ([`STRAIGHT_WRIST_RAD`]) and its reach ([`MAX_WRIST_BEND_RAD`]);
/// bent further, the frame turned back towards the shaft to the reach (its roll about the jaws kept);
/// nearly straight, along the shaft. Played back by their direction only, the right's jaws,
/// which the long end's turns go round, roll otherwise than recorded and the needle is torn out of
/// them (15.7 N) as the left comes down onto the tail (the canonical demonstration replayed at its own
/// stitch; the fluid and DMP skills the same, 17.4 and 26.5 N).
pub fn recorded_orientation(
    world_from_tip: &UnitQuaternion<f64>,
    tip_m: &Vector3<f64>,
    trocar_m: &Vector3<f64>,
) -> Orientation {
    let jaw = world_from_tip * Vector3::z();
    let frame = |q: &UnitQuaternion<f64>| {
        let q = q.quaternion();
        Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] }
    };
    match (tip_m - trocar_m).try_normalize(1e-9) {
        Some(shaft) if (STRAIGHT_WRIST_RAD..=MAX_WRIST_BEND_RAD).contains(&jaw.angle(&shaft)) => {
            frame(world_from_tip)
        }
        Some(shaft) if jaw.angle(&shaft) > MAX_WRIST_BEND_RAD => {
            // Turned back towards the shaft, roll and all, about the axis across both: at the reach
            // the frame is the one asked for, so a path that crosses it is commanded without a jump
            // (as a jaw direction, the whole bend in the yaw, the pitch would jump to zero).
            match jaw.cross(&shaft).try_normalize(1e-9) {
                Some(across) => {
                    let back = UnitQuaternion::from_axis_angle(
                        &nalgebra::Unit::new_unchecked(across),
                        jaw.angle(&shaft) - MAX_WRIST_BEND_RAD,
                    );
                    frame(&(back * world_from_tip))
                }
                None => jaw_orientation(&jaw, tip_m, trocar_m),
            }
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
        // Bent past its reach: the frame turned back to the reach, its roll about the jaws kept, in
        // the plane of the shaft and the jaws.
        let over = frame_turned(1.5);
        let Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = recorded_orientation(&over, &tip, &trocar)
        else {
            panic!("a wrist bent past its reach keeps a frame");
        };
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        assert!(q.angle_to(&frame_turned(MAX_WRIST_BEND_RAD)) < 1e-12, "{q:?}");
    }

    /// A recorded path whose wrist bend crosses the reach is commanded without a jump: just past the
    /// reach the commanded frame is as far from the asked one as the asked one is past the reach (as
    /// a jaw direction, the whole bend put in the yaw, the pitch jumped 37 degrees at a turned stitch
    /// and the left's tip swung 14 mm off its path, throwing the long end's turns off its jaws).
    #[test]
    fn a_frame_crossing_the_wrists_reach_is_commanded_without_a_jump() {
        let trocar = Vector3::new(0.0, 0.0, 1.0);
        let tip = Vector3::new(0.0, 0.0, 0.9);
        // Jaws bent about an oblique axis and rolled: the frame's yaw axis is not across the bend.
        let frame = |bend_rad: f64| {
            UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI)
                * UnitQuaternion::from_axis_angle(
                    &nalgebra::Unit::new_normalize(Vector3::new(1.0, 1.0, 0.0)),
                    bend_rad,
                )
                * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.9)
        };
        let commanded = |bend_rad: f64| match recorded_orientation(&frame(bend_rad), &tip, &trocar) {
            Orientation::Frame { quaternion_xyzw: [x, y, z, w] } => {
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
            }
            other => panic!("a bent wrist keeps a frame: {other:?}"),
        };
        for past in [1e-6, 1e-3, 0.05, 0.3] {
            let asked = frame(MAX_WRIST_BEND_RAD + past);
            let got = commanded(MAX_WRIST_BEND_RAD + past);
            assert!((got.angle_to(&asked) - past).abs() < 1e-9, "{past}: {}", got.angle_to(&asked));
            let shaft = (tip - trocar).normalize();
            assert!(((got * Vector3::z()).angle(&shaft) - MAX_WRIST_BEND_RAD).abs() < 1e-9);
        }
        let at = commanded(MAX_WRIST_BEND_RAD - 1e-9);
        assert!(at.angle_to(&commanded(MAX_WRIST_BEND_RAD + 1e-9)) < 1e-8);
    }
}
