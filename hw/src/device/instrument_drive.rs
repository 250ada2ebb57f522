//! The instrument's own motors: roll about the shaft, wrist pitch and yaw, jaw opening.
//!
//! On EndoPAR small servo motors in the magnetic coupling drive them. A driver for a concrete bus
//! (a serial servo bus, CAN, EtherCAT) must:
//! - in `read`, return the four joint positions in radians in knotlab's conventions
//!   ([`crate::kinematics::ToolJoints`]: roll about the shaft, pitch, yaw, the angle between the jaws),
//!   converting from motor units and through the cable coupling, and set `fresh` to false when the bus
//!   gave no new sample this cycle (rather than blocking past its time-out);
//! - in `write`, send the four set-points, in the same conventions, to arrive before the next cycle;
//!   hold the last set-point when no `write` comes;
//! - leave limits to the decorators of [`super::limits`] (wrap it in them), and report bus faults as
//!   [`DeviceError::Fault`] or [`DeviceError::Io`], naming the device.

use crate::kinematics::ToolJoints;

use super::error::DeviceError;

/// What an instrument drive reports each cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InstrumentState {
    /// Measured roll, pitch, yaw and jaw opening, rad.
    pub joints: ToolJoints,
    /// False when the driver repeats its last measurement.
    pub fresh: bool,
}

/// The instrument's roll, wrist and jaw motors.
pub trait InstrumentDrive: Send {
    /// Reads the measured joint positions.
    fn read(&mut self) -> Result<InstrumentState, DeviceError>;

    /// Writes the set-points for the next cycle, rad.
    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError>;

    /// Ends the device's session.
    fn shutdown(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
}

impl<T: InstrumentDrive + ?Sized> InstrumentDrive for Box<T> {
    fn read(&mut self) -> Result<InstrumentState, DeviceError> {
        (**self).read()
    }

    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
        (**self).write(joints)
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        (**self).shutdown()
    }
}
