//! What paces the control cycle: the simulation's step, a real controller's packet exchange, or a
//! virtual clock.

use super::error::DeviceError;

/// Ends each control cycle. The controller calls [`CycleClock::tick`] once per cycle, after writing.
pub trait CycleClock: Send {
    /// The cycle's period, s (1 ms in simulation; 7.11 or 3.5 ms on a MELFA controller).
    fn period_s(&self) -> f64;

    /// Ends the cycle: steps the simulation, waits for the next period, or (when the devices' own
    /// exchanges pace the loop) does nothing.
    fn tick(&mut self) -> Result<(), DeviceError>;
}

impl<T: CycleClock + ?Sized> CycleClock for Box<T> {
    fn period_s(&self) -> f64 {
        (**self).period_s()
    }

    fn tick(&mut self) -> Result<(), DeviceError> {
        (**self).tick()
    }
}

/// A clock for rigs whose devices pace the loop themselves (a MELFA controller answers once per
/// cycle, so waiting for its reply is waiting for the cycle): `tick` does nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PacedByDevices {
    /// The devices' period, s.
    pub period_s: f64,
}

impl CycleClock for PacedByDevices {
    fn period_s(&self) -> f64 {
        self.period_s
    }

    fn tick(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
}
