//! knotlab's robots: the rig description loaded from URDF, the closed-form kinematics of the RV-6SL
//! arms carrying wristed instruments through trocars, the device traits every backend implements, the
//! controller that runs a skill on any of them, and the MELFA real-time driver with its emulator.
//!
//! - [`kinematics`]: allocation-free forward and trocar-constrained inverse kinematics (no URDF, no
//!   heap: the same math can run in a GPU kernel).
//! - [`rig`]: the rig read from URDF with urdf-rs, validated, walked as a joint tree, and turned into one
//!   [`kinematics::ArmModel`] per arm.
//! - [`device`]: one trait per capability (arm servo, instrument drive, force sensor, master device,
//!   pedals, cycle clock), limit decorators, dummy drivers.
//! - [`rig_config`]: the rig config (TOML) choosing a backend per device, and building the devices.
//! - [`skill`]: the Skill the learner produces and the controller executes.
//! - [`arm_setup`]: one arm as the controller and the preview need it: its kinematics and its trocar.
//! - [`controller`]: the skill executor.
//! - [`gate`]: the gate between a preview and real hardware.
//! - [`canopen`]: CANopen frames, expedited SDO and the CiA 402 drive state machine.
//! - [`melfa`]: Mitsubishi MELFA real-time external control over UDP, and a controller emulator.
//! - [`netft`]: ATI Net F/T force sensors over RDT (UDP), and an emulator of the box.

pub mod arm_setup;
pub mod canopen;
pub mod controller;
pub mod device;
pub mod gate;
pub mod geometry;
pub mod kinematics;
pub mod melfa;
pub mod netft;
pub mod rig;
pub mod rig_config;
pub mod skill;
pub mod toml_file;
