//! L1: the left to the winding point, its jaws framed for the winding and the tail; the right takes
//! up the long end meanwhile, to where the winding starts.

use knotlab_hw::rig::ArmName;
use knotlab_sim::tissue::Flap;
use nalgebra::{Unit, Vector3};

use super::{Hands, Setting};
use crate::expert::clearance::{Circle, Wrist, clear_of_wrist};
use crate::expert::motion::Path;

/// Where the winding goes, as the approach placed it (world frame).
pub(crate) struct Winding {
    /// The circle's centre, m.
    pub centre_m: Vector3<f64>,
    /// The turns' axis (right-handed), the left's jaws or their reverse.
    pub axis: Unit<Vector3<f64>>,
    /// The left's jaws.
    pub jaws: Unit<Vector3<f64>>,
    /// The advance along the jaws per turn, m.
    pub advance_m: f64,
    /// The left's hinge, across the line from the entry point to the tail's point.
    pub hinge: Unit<Vector3<f64>>,
    /// Where the thread enters the tissue (the tail's flap), m.
    pub entry_m: Vector3<f64>,
    /// The point ahead of the left's jaws where the tail is taken, m.
    pub tail_point_m: Vector3<f64>,
}

/// The left to the winding point and the right to the winding's start; there the left's jaws
/// close to `left_jaw_rad` (`None`: they hold the tail already and stay so).
pub(crate) fn approach(s: &Setting, hands: &mut Hands, left_jaw_rad: Option<f64>) -> Winding {
    let (world, geometry) = (s.world, s.geometry);
    let Hands { left, right, .. } = hands;
    // The winding point; the right takes up the long end meanwhile, to where the winding starts:
    // the long end then runs from the stitch past the left's jaws.
    let winding_point = s.at(geometry.winding_point_m) + s.variation.winding_offset_m;
    // The left's jaws point at the right's trocar: the right's shaft then circles them at a distance.
    let jaws = match geometry.left_jaw_direction {
        Some(d) => Unit::new_normalize(s.dir(d)),
        None => Unit::new_normalize(s.trocar_m(ArmName::Right) - winding_point),
    };
    let axis = jaws;
    let across = |d: Vector3<f64>| Unit::try_new(d - axis.into_inner() * d.dot(&axis), 1e-9);
    // The winding starts opposite the exit point, so that the long end already lies across the
    // left's jaws, a little before the point where it would run straight over them.
    let exit = s.hole_m(Flap::B);
    // (With the exit on the jaw axis, any side will do: the one at right angles to `towards`.)
    let towards = across(s.dir(geometry.winding_towards))
        .or_else(|| across(Vector3::x()))
        .unwrap_or_else(|| Unit::new_normalize(Vector3::y()));
    let over = across(winding_point - exit).unwrap_or_else(|| Unit::new_normalize(axis.cross(&towards)));
    // The turns' sense: right-handed about the axis that moves `over` towards `towards`.
    let axis = if axis.cross(&over).dot(&towards) >= 0.0 { axis } else { -axis };
    let start_dir =
        nalgebra::Rotation3::from_axis_angle(&axis, -geometry.winding_lead_rad) * over.into_inner();
    let start_dir = Unit::new_normalize(start_dir);
    let centre = winding_point - jaws.into_inner() * geometry.winding_behind_m;
    // The jaws' hinge lies across the line from the entry point to where the tail will be held, so
    // that the tail then runs between the open jaws.
    let entry = s.hole_m(Flap::A);
    let tail_point = winding_point + jaws.into_inner() * geometry.tail_ahead_m;
    let hinge = across(tail_point - entry).unwrap_or(towards);
    let left_frame = nalgebra::Rotation3::from_basis_unchecked(&[
        hinge.cross(&jaws),
        hinge.into_inner(),
        jaws.into_inner(),
    ]);
    let l1_s = left.time_s();
    left.go_framing(Path::To(winding_point), s.d(2.0), left_frame);
    right.wait_until(l1_s);
    let winding_start = centre + start_dir.into_inner() * geometry.winding_radius_m;
    // The circle moved towards the jaws' tips until the thread in the right's jaws, going round it,
    // keeps clear of the left's wrist (at most to the jaw centre).
    // `axis` is the jaws' or their reverse (the turns' sense): the advance is along the jaws.
    let advance_m = geometry.winding_pitch_m * axis.dot(&jaws).signum();
    let turns = geometry.winding_turns;
    let planned = Circle { centre_m: centre, axis, start_m: winding_start, turns, pitch_m: advance_m };
    let circle = match (left.wrist_m(), world.rig().link_radius_m(ArmName::Left, "wrist")) {
        (Some((pitch_m, yaw_m)), Some(radius_m)) => {
            let trocar_m = s.trocar_m(ArmName::Left);
            let wrist = Wrist { pitch_m, yaw_m, trocar_m, radius_m };
            let thread_m = world.config().thread.radius_m;
            clear_of_wrist(&planned, &wrist, thread_m, &jaws, geometry.winding_behind_m.max(0.0)).0
        }
        _ => planned,
    };
    let (centre, winding_start) = (circle.centre_m, circle.start_m);
    let shaft = (centre - s.trocar_m(ArmName::Right)).normalize();
    match across(shaft).filter(|_| geometry.right_jaws_across_winding > 0.0) {
        Some(jaws_across) => {
            let jaws = shaft.lerp(&jaws_across, geometry.right_jaws_across_winding);
            right.go_turning(Path::To(winding_start), s.d(2.0), jaws)
        }
        None => right.go(Path::To(winding_start), s.d(2.0)),
    }
    left.wait_until(left.time_s() + s.pause(0));
    match left_jaw_rad {
        None => left.wait_until(left.time_s() + s.pause(1)),
        Some(jaw_rad) => {
            left.jaw(jaw_rad, s.d(0.3));
            left.wait_until(left.time_s() + s.d(0.3) + s.pause(1));
        }
    }
    Winding { centre_m: centre, axis, jaws, advance_m, hinge, entry_m: entry, tail_point_m: tail_point }
}
