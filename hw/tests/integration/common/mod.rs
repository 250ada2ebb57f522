//! Seeded sampling shared by the kinematics tests.
#![allow(dead_code)]

use knotlab_hw::kinematics::{ArmJoints, ArmModel, JointLimit, Tool, ToolJoints};
use nalgebra::Vector3;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// A uniform draw inside a limit.
pub fn draw(rng: &mut ChaCha8Rng, limit: &JointLimit) -> f64 {
    rng.random_range(limit.lower_rad..=limit.upper_rad)
}

/// A random joint vector inside every limit of `model` (jaw at a fixed opening).
pub fn random_joints(rng: &mut ChaCha8Rng, model: &ArmModel) -> ArmJoints {
    let arm_rad = std::array::from_fn(|i| draw(rng, &model.limits[i]));
    let tool = match &model.tool {
        Tool::Instrument { limits, .. } => ToolJoints {
            roll_rad: draw(rng, &limits.roll),
            pitch_rad: draw(rng, &limits.pitch),
            yaw_rad: draw(rng, &limits.yaw),
            jaw_rad: 0.3,
        },
        Tool::Endoscope { .. } => ToolJoints::default(),
    };
    ArmJoints { arm_rad, tool }
}

/// A trocar on the shaft of `joints`, with the pitch axis (instrument) or tip (endoscope) between 5 mm
/// and 22 cm past it.
pub fn trocar_on_shaft(rng: &mut ChaCha8Rng, model: &ArmModel, joints: &ArmJoints) -> Vector3<f64> {
    let axis = model.shaft_axis(joints);
    let shaft_m = match &model.tool {
        Tool::Instrument { geometry, .. } => geometry.shaft_m,
        Tool::Endoscope { geometry } => geometry.shaft_m,
    };
    let depth_m = rng.random_range(0.005..0.22);
    axis.origin_m + axis.direction * (shaft_m - depth_m)
}

/// Whether every joint of `joints` is inside the limits of `model`.
pub fn inside_limits(model: &ArmModel, joints: &ArmJoints) -> bool {
    let arm = joints.arm_rad.iter().zip(&model.limits).all(|(q, l)| l.lower_rad <= *q && *q <= l.upper_rad);
    let tool = match &model.tool {
        Tool::Instrument { limits, .. } => [
            (joints.tool.roll_rad, limits.roll),
            (joints.tool.pitch_rad, limits.pitch),
            (joints.tool.yaw_rad, limits.yaw),
        ]
        .iter()
        .all(|(q, l)| l.lower_rad <= *q && *q <= l.upper_rad),
        Tool::Endoscope { .. } => true,
    };
    arm && tool
}

/// Default trocar points for the shipped rig (as a scene would place them on the chest at z = 1.02 m).
pub fn default_trocar(arm: knotlab_hw::rig::ArmName) -> Vector3<f64> {
    use knotlab_hw::rig::ArmName;
    match arm {
        ArmName::Left => Vector3::new(-0.08, 0.12, 1.02),
        ArmName::Right => Vector3::new(-0.08, -0.12, 1.02),
        ArmName::Assist => Vector3::new(0.12, 0.10, 1.02),
        ArmName::Camera => Vector3::new(-0.14, 0.0, 1.02),
    }
}
