//! Mitsubishi MELFA real-time external control ("MXT") over UDP: the packet and its two layouts, the
//! session driver that makes a MELFA controller an [`crate::device::ArmServo`], and an emulator of the
//! controller's side for tests and for trying a rig without the robot.
//!
//! - [`packet`]: the packet as typed values; [`codec`]: its bytes (196 for software H7 and later, 64
//!   before), byte-exact to the layout table of shared/reference/melfa-mxt.md.
//! - [`session`]: the driver: NULL to read the current joints, MOVE with CCount each cycle, END; receive
//!   time-out, loss counting, a fault after a run of losses, NULL keep-alive, per-cycle step clamping.
//! - [`emulator`]: the controller side: answers NULL with the joints, MOVE by moving a simulated arm
//!   (the controller's filter, limits, over-speed fault), END by ending the session.

pub mod codec;
pub mod emulator;
pub mod packet;
pub mod session;

pub use codec::PacketError;
pub use packet::{Command, Data, DataType, Io, Layout, Monitor, Packet, Pose};
pub use session::{MelfaArm, MelfaConfig};

/// Control cycle of CR750/CR751 (Q type) controllers, s.
pub const CR750_CYCLE_S: f64 = 0.00711;
/// Control cycle of CR800 (D/R type) controllers, s.
pub const CR800_CYCLE_S: f64 = 0.0035;
/// The controller's MXT port.
pub const CONTROLLER_PORT: u16 = 10000;
/// Replies lost in a row after which the link is down (the figure of Mitsubishi's own ROS 2 driver).
pub const MAX_LOST_REPLIES: u32 = 100;
