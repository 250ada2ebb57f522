//! Where a skill is instantiated: the new stitch frame, the rigid motion that carries the
//! demonstration's world to the new site, and what each instrument reaches there.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use knotlab_hw::kinematics::TipTarget;
use knotlab_hw::rig::ArmName;

use crate::primitive::Pose;

/// Whether an instrument can take a tip target (its arm's inverse kinematics with the shaft through
/// its trocar, as the kinematic preview solves it).
#[derive(Clone, Copy)]
pub struct Reach<'a>(pub &'a dyn Fn(ArmName, &TipTarget) -> bool);

impl std::fmt::Debug for Reach<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Reach(..)")
    }
}

/// The rigid motion `new_world_from_demo_world` that puts the demonstration's stitch frame onto the new
/// one: a point placed relative to the old stitch lands at the same place relative to the new one.
pub fn relocation(
    demo_world_from_stitch: &Isometry3<f64>,
    new_world_from_stitch: &Isometry3<f64>,
) -> Isometry3<f64> {
    new_world_from_stitch * demo_world_from_stitch.inverse()
}

/// A knowledge-base pose (stitch frame) as a rigid transform `stitch_from_tip`.
pub fn pose_isometry(pose: &Pose) -> Isometry3<f64> {
    let [x, y, z, w] = pose.quaternion_xyzw;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(pose.position_m)),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point fixed in the stitch frame is relocated to the same place relative to the new stitch.
    #[test]
    fn a_point_keeps_its_place_relative_to_the_stitch() {
        let demo = Isometry3::new(Vector3::new(0.0, 0.0, 0.95), Vector3::new(0.0, 0.0, 0.2));
        let new = Isometry3::new(Vector3::new(0.02, -0.01, 0.96), Vector3::new(0.0, 0.0, -0.3));
        let moved = relocation(&demo, &new);
        let in_stitch = nalgebra::Point3::new(0.01, 0.02, 0.03);
        let old_world = demo * in_stitch;
        let new_world = moved * old_world;
        assert!((new_world - new * in_stitch).norm() < 1e-12);
    }
}
