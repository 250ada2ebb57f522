//! One arm as the controller and the preview need it: its kinematic model and the trocar its tool
//! passes through.

use nalgebra::Vector3;

use crate::kinematics::ArmModel;
use crate::rig::ArmName;

/// One arm as the controller needs it: kinematics and the trocar its tool passes through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmSetup {
    /// Which arm.
    pub arm: ArmName,
    /// Its kinematic model (mounting, geometry, limits, tool).
    pub model: ArmModel,
    /// The trocar point, world frame, m (it belongs to the scene or the patient, not the rig).
    pub world_trocar_m: Vector3<f64>,
}
