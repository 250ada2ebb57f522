//! The six axes of one arm, driven by joint position set-points.

use super::error::DeviceError;

/// What an arm servo reports each cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArmServoState {
    /// Measured positions of axes 1..=6, rad.
    pub joints_rad: [f64; 6],
    /// False when the driver has no new measurement this cycle (a lost reply) and repeats its last one.
    pub fresh: bool,
}

/// Counters of a driver that talks over a lossy link.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LinkStats {
    /// Exchanges started (one per cycle).
    pub exchanges: u64,
    /// Replies that did not come in time, in all.
    pub lost_total: u64,
    /// Replies lost in a row up to now.
    pub lost_in_a_row: u32,
    /// Late replies thrown away before a new exchange.
    pub late_discarded: u64,
    /// Cycles with no fresh set-point, where a keep-alive was sent instead.
    pub keep_alives: u64,
    /// Cycles whose set-point the driver clamped to its per-cycle step.
    pub clamped: u64,
}

/// The arm's six axes. `read` returns where they stand; `write` gives the set-point for the next cycle.
/// A driver that gets no `write` in a cycle holds its last set-point.
pub trait ArmServo: Send {
    /// Reads the measured joint positions (blocking at most the driver's receive time-out).
    fn read(&mut self) -> Result<ArmServoState, DeviceError>;

    /// Writes the joint position set-point, rad.
    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError>;

    /// Link counters, for drivers that talk over a lossy link.
    fn link_stats(&self) -> Option<LinkStats> {
        None
    }

    /// Ends the device's session (after which it accepts no commands).
    fn shutdown(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
}

impl<T: ArmServo + ?Sized> ArmServo for Box<T> {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        (**self).read()
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        (**self).write(joints_rad)
    }

    fn link_stats(&self) -> Option<LinkStats> {
        (**self).link_stats()
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        (**self).shutdown()
    }
}
