//! The hw crate's integration tests, one binary: one link, and the tests of every file run side by side. Each module
//! guards what its doc comment says.

mod common;
mod rigs;

mod canopen_drive;
mod controller_dummy;
mod fk_agreement;
mod ik_errors;
mod ik_nearest_first;
mod ik_roundtrip;
mod limit_decorators;
mod melfa_packet_bytes;
mod melfa_session;
mod netft_sensor;
mod preview_gate;
mod rig_config_errors;
mod teleoperation;
mod urdf_errors;
