//! From knotlab's f64 nalgebra geometry to Rerun's f32 components.

use nalgebra::{Rotation3, UnitQuaternion, Vector3};

use super::sdk;

/// A point or vector as Rerun takes it.
pub fn v3(v: &Vector3<f64>) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// A rotation as Rerun's quaternion.
pub fn quaternion(rotation: &Rotation3<f64>) -> sdk::Quaternion {
    let q = UnitQuaternion::from_rotation_matrix(rotation);
    sdk::Quaternion::from_xyzw([q.i as f32, q.j as f32, q.k as f32, q.w as f32])
}

/// The rotation taking +z onto `direction` (identity for a zero vector), as Rerun's quaternion.
pub fn z_onto(direction: &Vector3<f64>) -> sdk::Quaternion {
    let q = UnitQuaternion::rotation_between(&Vector3::z(), direction)
        .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI));
    let q = if direction.norm() < 1e-12 { UnitQuaternion::identity() } else { q };
    sdk::Quaternion::from_xyzw([q.i as f32, q.j as f32, q.k as f32, q.w as f32])
}

/// The arm names in entity paths, and their colours (as in the snapshot pictures).
pub fn arm_color(arm: &str) -> sdk::Color {
    match arm {
        "left" => sdk::Color::from_rgb(90, 140, 100),
        "right" => sdk::Color::from_rgb(80, 110, 160),
        "assist" => sdk::Color::from_rgb(140, 100, 150),
        _ => sdk::Color::from_rgb(110, 110, 120),
    }
}
