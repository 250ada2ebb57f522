//! Device traits, one small trait per capability, and what ships with them: limit decorators, dummy
//! drivers and the set of devices one rig is made of.
//!
//! Each control cycle runs in the ros2_control manner: the controller `read`s every device, computes,
//! then `write`s the devices it commands, then lets the [`CycleClock`] end the cycle. Reads and writes are
//! synchronous and cheap; a driver that talks to hardware does its waiting in `read` (or in the clock).
//! A driver that gets no `write` in a cycle holds its last set-point. Units are SI and radians.
//!
//! | capability | trait | sim | melfa | dummy |
//! |---|---|---|---|---|
//! | the six arm axes | [`ArmServo`] | yes | yes (UDP, [`crate::melfa`]) | yes |
//! | instrument roll, wrist, jaw | [`InstrumentDrive`] | yes | - | yes |
//! | the shaft's strain gauges | [`ForceSensor`] | yes | - | yes |
//! | a haptic master device | [`MasterDevice`] | - | - | yes |
//! | foot pedals, emergency stop | [`Pedals`] | - | - | yes |
//! | the cycle's pace | [`CycleClock`] | yes | yes | yes |
//!
//! Limits are decorators that wrap a driver and refuse out-of-range commands with a typed
//! [`LimitError`] ([`limits`]). The dummy drivers ([`dummy`]) follow their commands perfectly and take
//! their inputs from handles a test or a user interface holds.

pub mod arm_servo;
pub mod clock;
pub mod dummy;
pub mod error;
pub mod force_sensor;
pub mod gamepad;
pub mod id;
pub mod instrument_drive;
pub mod limits;
pub mod master;
pub mod pedals;
pub mod set;

pub use arm_servo::{ArmServo, ArmServoState, LinkStats};
pub use clock::CycleClock;
pub use error::{DeviceError, LimitError};
pub use force_sensor::{ForceReading, ForceSensor};
pub use id::{DeviceId, DeviceKind};
pub use instrument_drive::{InstrumentDrive, InstrumentState};
pub use limits::{PositionLimit, StepLimit, VelocityLimit};
pub use master::{ForceFeedback, MasterDevice, MasterState};
pub use pedals::{PedalState, Pedals};
pub use set::{ArmDevices, DeviceSet};
