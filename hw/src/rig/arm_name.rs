//! The four arms of the rig by role.

use std::fmt;
use std::str::FromStr;

/// An arm, named by what it does; also the prefix of its links and joints in the URDF.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ArmName {
    /// The surgeon's left instrument.
    Left,
    /// The surgeon's right instrument.
    Right,
    /// The third (assisting) instrument.
    Assist,
    /// The stereo endoscope.
    Camera,
}

impl ArmName {
    /// All four, in a fixed order.
    pub const ALL: [ArmName; 4] = [ArmName::Left, ArmName::Right, ArmName::Assist, ArmName::Camera];

    /// The name used on the command line and as the URDF prefix.
    pub fn as_str(self) -> &'static str {
        match self {
            ArmName::Left => "left",
            ArmName::Right => "right",
            ArmName::Assist => "assist",
            ArmName::Camera => "camera",
        }
    }

    /// A comfortable pose on the shipped rig, the tool tip near the operating site, every axis at
    /// least 0.8 rad inside its limits: the seed "nearest the current joints" starts from when no
    /// current joints are known. Degrees here, radians out.
    pub fn ready_joints(self) -> crate::kinematics::ArmJoints {
        let deg: [f64; 6] = match self {
            ArmName::Left => [30.0, -23.0, 113.0, 63.0, -50.0, -32.0],
            ArmName::Right => [-30.0, -23.0, 113.0, -63.0, -50.0, 25.0],
            ArmName::Assist => [30.0, -23.0, 111.0, 66.0, -49.0, -41.0],
            ArmName::Camera => [0.0, -26.0, 113.0, 0.0, -18.0, 0.0],
        };
        crate::kinematics::ArmJoints::from_arm(deg.map(f64::to_radians))
    }

    /// Whether it carries a wristed instrument (all but the camera).
    pub fn carries_instrument(self) -> bool {
        self != ArmName::Camera
    }
}

impl fmt::Display for ArmName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// An arm name that is none of the four.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown arm '{0}': expected left, right, assist or camera")]
pub struct UnknownArm(pub String);

impl FromStr for ArmName {
    type Err = UnknownArm;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        ArmName::ALL.into_iter().find(|a| a.as_str() == s).ok_or_else(|| UnknownArm(s.to_owned()))
    }
}
