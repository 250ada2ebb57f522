//! What an arm carries: a wristed instrument or the endoscope, their geometry and forward kinematics.
//!
//! Both sit on the flange's z axis (a collinear coupling), so the instrument's roll turns about the
//! same axis as arm axis 6. Instrument frames: roll about z at the shaft base; wrist pitch about x at the
//! end of the shaft; wrist yaw about y, `wrist_m` further along the wrist link; the tip on the jaws'
//! centre line, `jaw_m` beyond the yaw axis. The tip frame's z is the jaw direction, its y the yaw axis.

use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};

use super::joints::ToolJoints;
use super::limits::JointLimit;

/// Closest the tip (or the point that fixes the shaft) may come to the trocar, m (as the dVRK).
pub const MIN_TROCAR_DISTANCE_M: f64 = 1e-3;

/// Dimensions of a da Vinci EndoWrist-style instrument.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstrumentGeometry {
    /// Flange face to the shaft base (coupling and housing), m.
    pub coupling_m: f64,
    /// Shaft base to the wrist pitch axis, m.
    pub shaft_m: f64,
    /// Pitch axis to yaw axis, m.
    pub wrist_m: f64,
    /// Yaw axis to jaw tip, m.
    pub jaw_m: f64,
    /// Deepest the pitch axis may go past the trocar, m.
    pub max_insertion_m: f64,
}

impl InstrumentGeometry {
    /// The large needle driver of shared/reference/rig.md on knotlab's coupling.
    pub const LARGE_NEEDLE_DRIVER: Self =
        Self { coupling_m: 0.12, shaft_m: 0.4318, wrist_m: 0.0091, jaw_m: 0.010, max_insertion_m: 0.24 };

    /// Flange to tip for the given instrument joints (the jaw opening does not move the tip frame).
    pub fn flange_from_tip(&self, joints: &ToolJoints) -> IsometryMatrix3<f64> {
        let t = |z: f64| IsometryMatrix3::from_parts(Translation3::new(0.0, 0.0, z), Rotation3::identity());
        let r = |axis: Vector3<f64>, q: f64| {
            IsometryMatrix3::from_parts(Translation3::identity(), Rotation3::new(axis * q))
        };
        t(self.coupling_m)
            * r(Vector3::z(), joints.roll_rad)
            * t(self.shaft_m)
            * r(Vector3::x(), joints.pitch_rad)
            * t(self.wrist_m)
            * r(Vector3::y(), joints.yaw_rad)
            * t(self.jaw_m)
    }
}

/// Limits of the instrument's joints.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstrumentLimits {
    /// Roll about the shaft.
    pub roll: JointLimit,
    /// Wrist pitch.
    pub pitch: JointLimit,
    /// Wrist yaw.
    pub yaw: JointLimit,
    /// Jaw opening (the angle between the jaws).
    pub jaw: JointLimit,
}

/// Dimensions of the stereo endoscope (a straight scope: it looks along its shaft).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EndoscopeGeometry {
    /// Flange face to the shaft base, m.
    pub coupling_m: f64,
    /// Shaft base to the tip, m.
    pub shaft_m: f64,
    /// Deepest the tip may go past the trocar, m.
    pub max_insertion_m: f64,
}

impl EndoscopeGeometry {
    /// knotlab's 10 mm stereo endoscope.
    pub const STEREO_10MM: Self = Self { coupling_m: 0.12, shaft_m: 0.40, max_insertion_m: 0.25 };

    /// Flange to tip.
    pub fn flange_from_tip(&self) -> IsometryMatrix3<f64> {
        IsometryMatrix3::from_parts(
            Translation3::new(0.0, 0.0, self.coupling_m + self.shaft_m),
            Rotation3::identity(),
        )
    }
}

/// The tool on an arm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tool {
    /// A wristed instrument.
    Instrument {
        /// Its dimensions.
        geometry: InstrumentGeometry,
        /// Its joint limits.
        limits: InstrumentLimits,
    },
    /// The stereo endoscope.
    Endoscope {
        /// Its dimensions.
        geometry: EndoscopeGeometry,
    },
}

impl Tool {
    /// Flange to tip.
    pub fn flange_from_tip(&self, joints: &ToolJoints) -> IsometryMatrix3<f64> {
        match self {
            Tool::Instrument { geometry, .. } => geometry.flange_from_tip(joints),
            Tool::Endoscope { geometry } => geometry.flange_from_tip(),
        }
    }

    /// Flange face to the shaft base, m.
    pub fn coupling_m(&self) -> f64 {
        match self {
            Tool::Instrument { geometry, .. } => geometry.coupling_m,
            Tool::Endoscope { geometry } => geometry.coupling_m,
        }
    }
}
