//! Joint vectors of one arm and its tool.

use super::limits::JointId;

/// The instrument's joints; all zero (and unused) for the endoscope.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ToolJoints {
    /// Roll about the shaft, rad.
    pub roll_rad: f64,
    /// Wrist pitch, rad.
    pub pitch_rad: f64,
    /// Wrist yaw, rad.
    pub yaw_rad: f64,
    /// Jaw opening (angle between the jaws), rad; each jaw turns half of it.
    pub jaw_rad: f64,
}

/// Every joint of one arm: the six RV-6SL axes and the tool's joints.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArmJoints {
    /// Axes 1..=6, rad.
    pub arm_rad: [f64; 6],
    /// The tool's joints.
    pub tool: ToolJoints,
}

impl ArmJoints {
    /// Number of values in [`ArmJoints::to_array`]: six arm axes, roll, pitch, yaw, jaw.
    pub const LEN: usize = 10;

    /// The order of [`ArmJoints::to_array`].
    pub const ORDER: [JointId; 10] = [
        JointId::Arm(1),
        JointId::Arm(2),
        JointId::Arm(3),
        JointId::Arm(4),
        JointId::Arm(5),
        JointId::Arm(6),
        JointId::Roll,
        JointId::WristPitch,
        JointId::WristYaw,
        JointId::Jaw,
    ];

    /// Arm axes with the tool at zero.
    pub fn from_arm(arm_rad: [f64; 6]) -> Self {
        Self { arm_rad, tool: ToolJoints::default() }
    }

    /// All values in [`ArmJoints::ORDER`].
    pub fn to_array(&self) -> [f64; 10] {
        let a = self.arm_rad;
        let t = self.tool;
        [a[0], a[1], a[2], a[3], a[4], a[5], t.roll_rad, t.pitch_rad, t.yaw_rad, t.jaw_rad]
    }

    /// From values in [`ArmJoints::ORDER`].
    pub fn from_array(v: [f64; 10]) -> Self {
        Self {
            arm_rad: [v[0], v[1], v[2], v[3], v[4], v[5]],
            tool: ToolJoints { roll_rad: v[6], pitch_rad: v[7], yaw_rad: v[8], jaw_rad: v[9] },
        }
    }

    /// The value of one joint.
    pub fn get(&self, joint: JointId) -> f64 {
        match joint {
            JointId::Arm(i) => self.arm_rad[usize::from(i.clamp(1, 6)) - 1],
            JointId::Roll => self.tool.roll_rad,
            JointId::WristPitch => self.tool.pitch_rad,
            JointId::WristYaw => self.tool.yaw_rad,
            JointId::Jaw => self.tool.jaw_rad,
        }
    }
}
