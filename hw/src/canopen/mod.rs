//! CANopen for the instruments' motor controllers: the drive profile CiA 402 on CAN.
//!
//! - [`frame`]: a classic CAN frame and CANopen's COB-IDs (function code and node).
//! - [`sdo`]: expedited SDO transfers (reading and writing one object of up to four bytes) and their
//!   abort codes.
//! - [`cia402`]: the drive's state machine: states read from the statusword, the controlword commands
//!   that move between them.

pub mod cia402;
pub mod frame;
pub mod sdo;

pub use frame::{CanFrame, CobId, FrameError};
