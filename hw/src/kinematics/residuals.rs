//! How well a joint solution meets its target: tip error, orientation error, shaft-to-trocar distance.

use nalgebra::{Rotation3, Vector3};

use super::joints::ArmJoints;
use super::model::ArmModel;
use super::trocar_ik::{TipOrientation, TipTarget};

/// The angle of the rotation taking `a` to `b`, rad, accurate near zero (`atan2` of the sine and
/// cosine parts, where `acos` of the trace would lose half the digits).
pub fn rotation_distance_rad(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    let r = a.matrix().transpose() * b.matrix();
    let sin_part =
        Vector3::new(r[(2, 1)] - r[(1, 2)], r[(0, 2)] - r[(2, 0)], r[(1, 0)] - r[(0, 1)]).norm() * 0.5;
    let cos_part = (r.trace() - 1.0) * 0.5;
    sin_part.atan2(cos_part)
}

/// The angle between two directions, rad, accurate near zero and near pi.
pub fn direction_distance_rad(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    a.cross(b).norm().atan2(a.dot(b))
}

/// Residuals of a solution, computed by forward kinematics.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IkResiduals {
    /// Distance between the reached tip and the target, m.
    pub tip_error_m: f64,
    /// Angle between the reached and the asked orientation, rad: the jaw direction for a jaw
    /// direction or along-shaft target, the whole frame for a frame target.
    pub orientation_error_rad: f64,
    /// Distance of the shaft's axis from the trocar point, m.
    pub trocar_distance_m: f64,
}

impl IkResiduals {
    /// Measures `joints` against `target` and `world_trocar_m` on `model`.
    pub fn measure(
        model: &ArmModel,
        joints: &ArmJoints,
        target: &TipTarget,
        world_trocar_m: &Vector3<f64>,
    ) -> Self {
        let tip = model.world_from_tip(joints);
        let reached_jaw = tip.rotation * Vector3::z();
        let orientation_error_rad = match target.orientation {
            TipOrientation::AlongShaft => {
                direction_distance_rad(&reached_jaw, &(target.world_position_m - world_trocar_m))
            }
            TipOrientation::JawDirection(jaw) => direction_distance_rad(&reached_jaw, &jaw),
            TipOrientation::Frame(rotation) => rotation_distance_rad(&tip.rotation, &rotation),
        };
        Self {
            tip_error_m: (tip.translation.vector - target.world_position_m).norm(),
            orientation_error_rad,
            trocar_distance_m: model.shaft_axis(joints).distance_m(world_trocar_m),
        }
    }
}
