//! Between nalgebra's types (the kinematics, the rope, the knots) and Rapier's (glam's vectors,
//! rotations and poses), written once.

use nalgebra::{Isometry3, IsometryMatrix3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};
use rapier3d::math::{Pose, Rotation, Vector};

/// Rapier's vector from nalgebra's.
pub fn to_rapier(v: &Vector3<f64>) -> Vector {
    Vector::new(v.x, v.y, v.z)
}

/// nalgebra's vector from Rapier's.
pub fn to_na(v: Vector) -> Vector3<f64> {
    Vector3::new(v.x, v.y, v.z)
}

/// Rapier's pose from an nalgebra isometry.
pub fn to_pose(iso: &Isometry3<f64>) -> Pose {
    let q = iso.rotation;
    Pose::from_parts(to_rapier(&iso.translation.vector), Rotation::from_xyzw(q.i, q.j, q.k, q.w))
}

/// Rapier's pose from an nalgebra isometry with a rotation matrix.
pub fn matrix_to_pose(iso: &IsometryMatrix3<f64>) -> Pose {
    let q = UnitQuaternion::from_rotation_matrix(&iso.rotation);
    let t = iso.translation.vector;
    Pose::from_parts(Vector::new(t.x, t.y, t.z), Rotation::from_xyzw(q.i, q.j, q.k, q.w))
}

/// An nalgebra isometry (rotation matrix) from Rapier's pose.
pub fn to_isometry(pose: &Pose) -> IsometryMatrix3<f64> {
    let origin = to_na(pose.transform_point(Vector::ZERO));
    let column = |axis: Vector| to_na(pose.transform_vector(axis));
    let rotation = Matrix3::from_columns(&[column(Vector::X), column(Vector::Y), column(Vector::Z)]);
    IsometryMatrix3::from_parts(Translation3::from(origin), Rotation3::from_matrix_unchecked(rotation))
}
