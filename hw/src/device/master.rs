//! A haptic master device of the surgeon's console: a handle pose, a gripper, buttons, and force
//! feedback to the surgeon's hand.

use nalgebra::{IsometryMatrix3, Vector3};

use super::error::DeviceError;

/// What a master device reports each cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MasterState {
    /// The handle in the console's frame (m, rad).
    pub console_from_handle: IsometryMatrix3<f64>,
    /// The gripper's opening, rad.
    pub gripper_rad: f64,
    /// Buttons, one bit each (bit 0 the first button).
    pub buttons: u32,
    /// False when the driver repeats its last reading.
    pub fresh: bool,
}

impl Default for MasterState {
    fn default() -> Self {
        Self { console_from_handle: IsometryMatrix3::identity(), gripper_rad: 0.0, buttons: 0, fresh: true }
    }
}

/// The force to render on the surgeon's hand.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ForceFeedback {
    /// Force on the handle, console frame, N.
    pub console_force_n: Vector3<f64>,
}

/// A haptic master device.
pub trait MasterDevice: Send {
    /// Reads the handle.
    fn read(&mut self) -> Result<MasterState, DeviceError>;

    /// Writes the force feedback for the next cycle.
    fn write(&mut self, feedback: &ForceFeedback) -> Result<(), DeviceError>;
}

impl<T: MasterDevice + ?Sized> MasterDevice for Box<T> {
    fn read(&mut self) -> Result<MasterState, DeviceError> {
        (**self).read()
    }

    fn write(&mut self, feedback: &ForceFeedback) -> Result<(), DeviceError> {
        (**self).write(feedback)
    }
}
