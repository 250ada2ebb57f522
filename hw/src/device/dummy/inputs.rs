//! Input devices whose readings come from shared handles: set the force, press the pedal.

use std::sync::{Arc, Mutex, MutexGuard};

use nalgebra::{IsometryMatrix3, Vector3};

use crate::device::error::DeviceError;
use crate::device::force_sensor::{ForceReading, ForceSensor};
use crate::device::master::{ForceFeedback, MasterDevice, MasterState};
use crate::device::pedals::{PedalState, Pedals};

/// Locks a handle's value; a value poisoned by a panicking holder is still plain data, so it is used
/// as it stands.
pub fn lock_handle<T>(value: &Mutex<T>) -> MutexGuard<'_, T> {
    value.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Sets what a [`DummyForceSensor`] reads.
#[derive(Clone, Debug, Default)]
pub struct ForceHandle(Arc<Mutex<Vector3<f64>>>);

impl ForceHandle {
    /// The force the sensor reads from now on, shaft frame, N.
    pub fn set(&self, shaft_force_n: Vector3<f64>) {
        *lock_handle(&self.0) = shaft_force_n;
    }

    /// The force the sensor reads now.
    pub fn get(&self) -> Vector3<f64> {
        *lock_handle(&self.0)
    }
}

/// A force sensor that reads whatever its [`ForceHandle`] says (zero at first).
#[derive(Clone, Debug, Default)]
pub struct DummyForceSensor {
    handle: ForceHandle,
    tare_n: Vector3<f64>,
}

impl DummyForceSensor {
    /// A sensor reading zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// The handle that sets its readings.
    pub fn handle(&self) -> ForceHandle {
        self.handle.clone()
    }
}

impl ForceSensor for DummyForceSensor {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        Ok(ForceReading { shaft_force_n: self.handle.get() - self.tare_n, fresh: true })
    }

    fn zero(&mut self) -> Result<(), DeviceError> {
        self.tare_n = self.handle.get();
        Ok(())
    }
}

/// Presses and releases the pedals of a [`DummyPedals`].
#[derive(Clone, Debug, Default)]
pub struct PedalHandle(Arc<Mutex<PedalState>>);

impl PedalHandle {
    /// Presses (true) or releases (false) the emergency stop.
    pub fn set_emergency_stop(&self, pressed: bool) {
        lock_handle(&self.0).emergency_stop = pressed;
    }

    /// Presses or releases assignable pedal `index` (out-of-range indices are ignored).
    pub fn set_assignable(&self, index: usize, pressed: bool) {
        if let Some(p) = lock_handle(&self.0).assignable.get_mut(index) {
            *p = pressed;
        }
    }

    /// The pedals as they are now.
    pub fn get(&self) -> PedalState {
        *lock_handle(&self.0)
    }
}

/// Pedals pressed through a [`PedalHandle`] (all released at first).
#[derive(Clone, Debug, Default)]
pub struct DummyPedals {
    handle: PedalHandle,
}

impl DummyPedals {
    /// All pedals released.
    pub fn new() -> Self {
        Self::default()
    }

    /// The handle that presses them.
    pub fn handle(&self) -> PedalHandle {
        self.handle.clone()
    }
}

impl Pedals for DummyPedals {
    fn read(&mut self) -> Result<PedalState, DeviceError> {
        Ok(PedalState { fresh: true, ..self.handle.get() })
    }
}

/// Moves the handle of a [`DummyMaster`] and shows the force fed back to it.
#[derive(Clone, Debug, Default)]
pub struct MasterHandle(Arc<Mutex<(MasterState, ForceFeedback)>>);

impl MasterHandle {
    /// Puts the handle at a pose, with a gripper opening and buttons.
    pub fn set(&self, console_from_handle: IsometryMatrix3<f64>, gripper_rad: f64, buttons: u32) {
        lock_handle(&self.0).0 = MasterState { console_from_handle, gripper_rad, buttons, fresh: true };
    }

    /// The force feedback last written to the device.
    pub fn feedback(&self) -> ForceFeedback {
        lock_handle(&self.0).1
    }
}

/// A master device moved through a [`MasterHandle`].
#[derive(Clone, Debug, Default)]
pub struct DummyMaster {
    handle: MasterHandle,
}

impl DummyMaster {
    /// The handle at the console's origin, gripper closed, no button pressed.
    pub fn new() -> Self {
        Self::default()
    }

    /// The handle that moves it.
    pub fn handle(&self) -> MasterHandle {
        self.handle.clone()
    }
}

impl MasterDevice for DummyMaster {
    fn read(&mut self) -> Result<MasterState, DeviceError> {
        Ok(lock_handle(&self.handle.0).0)
    }

    fn write(&mut self, feedback: &ForceFeedback) -> Result<(), DeviceError> {
        lock_handle(&self.handle.0).1 = *feedback;
        Ok(())
    }
}
