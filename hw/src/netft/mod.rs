//! ATI Net F/T force sensors over RDT (Raw Data Transfer, UDP): the wire format, the driver that
//! makes a Net F/T box a [`crate::device::ForceSensor`], and an emulator of the box for tests and for
//! trying a rig without the sensor.
//!
//! - [`rdt`]: the 8-byte request and the 36-byte record, big-endian, as the box's manual lays them out.
//! - [`sensor`]: the driver: starts the box's stream, takes the newest record each cycle, counts the
//!   records lost from the sequence numbers, sets the box's bias, turns counts into newtons through the
//!   calibration's counts per force and the sensor's frame into the shaft's, and faults when the stream
//!   stalls.
//! - [`emulator`]: the box's side: streams a force you set at its rate, biases on request, drops
//!   records on request, stalls on request.

pub mod emulator;
pub mod rdt;
pub mod sensor;

pub use rdt::{RdtCommand, RdtError, Record, Request};
pub use sensor::{NetFtConfig, NetFtSensor, NetFtStats};

/// The box's RDT port.
pub const RDT_PORT: u16 = 49152;
