//! CANopen for the instruments' motor controllers: the drive profile CiA 402 on CAN.
//!
//! - [`frame`]: a classic CAN frame and CANopen's COB-IDs (function code and node).
//! - [`sdo`]: expedited SDO transfers (reading and writing one object of up to four bytes) and their
//!   abort codes.
//! - [`cia402`]: the drive's state machine: states read from the statusword, the controlword commands
//!   that move between them.
//! - [`dictionary`]: the drive's objects this driver uses and the PDO mapping it needs.
//! - [`bus`]: the transport interface, and an in-process bus; [`udp`]: frames over UDP;
//!   `socketcan` (Linux): frames through SocketCAN, the lab's transport.
//! - [`drive`]: the instrument's four drives as one [`crate::device::InstrumentDrive`].
//! - [`emulator`]: emulated drives (state machine, first-order motors, EMCY, drop-outs).

pub mod bus;
pub mod cia402;
pub mod dictionary;
pub mod drive;
pub mod emulator;
pub mod frame;
pub mod sdo;
#[cfg(target_os = "linux")]
pub mod socketcan;
pub mod udp;

pub use frame::{CanFrame, CobId, FrameError};
