//! Closed-form kinematics of knotlab's arms: the RV-6SL, the instrument or endoscope on its flange, and
//! inverse kinematics with the shaft through a trocar. No heap, no URDF: [`ArmModel`] is plain data.
//!
//! Frames and units: world z up, metres, radians; transforms are named `to_from_from`
//! (`world_from_tip` maps tip coordinates into the world). See [`rv6sl`] for the arm's zero pose and
//! [`tool`] for the instrument's frames.

pub mod arm_ik;
pub mod error;
pub mod joints;
pub mod limits;
pub mod model;
pub mod residuals;
pub mod rv6sl;
pub mod tool;
pub mod trocar_ik;

pub use error::IkError;
pub use joints::{ArmJoints, ToolJoints};
pub use limits::{JointId, JointLimit};
pub use model::{ArmModel, ShaftAxis};
pub use residuals::IkResiduals;
pub use rv6sl::Rv6slGeometry;
pub use tool::{EndoscopeGeometry, InstrumentGeometry, InstrumentLimits, Tool};
pub use trocar_ik::{TipOrientation, TipTarget};
