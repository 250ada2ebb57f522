//! knotlab's robots: the rig description loaded from URDF, and the closed-form kinematics of the
//! RV-6SL arms carrying wristed instruments through trocars.
//!
//! - [`kinematics`]: allocation-free forward and trocar-constrained inverse kinematics (no URDF, no
//!   heap: the same math can run in a GPU kernel).
//! - [`rig`]: the rig read from URDF with urdf-rs, validated, walked as a joint tree, and turned into one
//!   [`kinematics::ArmModel`] per arm.

pub mod kinematics;
pub mod rig;
