//! The console's foot pedals: the emergency stop and assignable pedals.

use super::error::DeviceError;

/// How many assignable pedals a console has.
pub const ASSIGNABLE_PEDALS: usize = 4;

/// What the pedals report each cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PedalState {
    /// The emergency stop is pressed.
    pub emergency_stop: bool,
    /// The assignable pedals (clutch, camera, ...), pressed or not.
    pub assignable: [bool; ASSIGNABLE_PEDALS],
    /// False when the driver repeats its last reading.
    pub fresh: bool,
}

impl Default for PedalState {
    fn default() -> Self {
        Self { emergency_stop: false, assignable: [false; ASSIGNABLE_PEDALS], fresh: true }
    }
}

/// The foot pedals (read only).
pub trait Pedals: Send {
    /// Reads the pedals.
    fn read(&mut self) -> Result<PedalState, DeviceError>;
}

impl<T: Pedals + ?Sized> Pedals for Box<T> {
    fn read(&mut self) -> Result<PedalState, DeviceError> {
        (**self).read()
    }
}
