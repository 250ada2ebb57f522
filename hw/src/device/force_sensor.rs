//! The strain gauges on an instrument's shaft: the force the instrument feels.
//!
//! Frame: the shaft frame, which rolls with the instrument: its origin at the shaft base, z along the
//! shaft towards the tip, x and y the flange's x and y turned by the instrument roll (the frame after
//! the roll joint of [`crate::kinematics::tool`]). The controller turns readings into the world frame
//! with the arm's forward kinematics.
//!
//! A driver for a concrete strain-gauge amplifier must:
//! - in `read`, return the force on the instrument in newtons in the shaft frame (calibration matrix
//!   applied, the tare subtracted), with `fresh` false when the amplifier gave no new sample this cycle;
//! - in `zero`, take the current reading as the tare (the instrument free of contact);
//! - report amplifier or bus faults as [`DeviceError::Fault`] or [`DeviceError::Io`], naming the device.

use nalgebra::Vector3;

use super::error::DeviceError;

/// One force reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceReading {
    /// Force on the instrument, shaft frame, N.
    pub shaft_force_n: Vector3<f64>,
    /// False when the driver repeats its last reading.
    pub fresh: bool,
}

impl Default for ForceReading {
    fn default() -> Self {
        Self { shaft_force_n: Vector3::zeros(), fresh: true }
    }
}

/// The strain gauges of one instrument.
pub trait ForceSensor: Send {
    /// Reads the force on the instrument.
    fn read(&mut self) -> Result<ForceReading, DeviceError>;

    /// Takes the present reading as zero (tare).
    fn zero(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }

    /// Ends the device's session (a streaming sensor stops its stream).
    fn shutdown(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
}

impl<T: ForceSensor + ?Sized> ForceSensor for Box<T> {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        (**self).read()
    }

    fn zero(&mut self) -> Result<(), DeviceError> {
        (**self).zero()
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        (**self).shutdown()
    }
}
