//! A clock for rigs of dummy devices: virtual time, or wall-clock time when asked.

use std::time::{Duration, Instant};

use crate::device::clock::CycleClock;
use crate::device::error::DeviceError;

/// Counts cycles of a fixed period; in real time it also sleeps until each cycle's end.
#[derive(Clone, Debug)]
pub struct VirtualClock {
    period_s: f64,
    real_time: bool,
    next: Option<Instant>,
}

impl VirtualClock {
    /// A clock of `period_s` that does not wait (as fast as the controller computes).
    pub fn new(period_s: f64) -> Self {
        Self { period_s, real_time: false, next: None }
    }

    /// A clock of `period_s` that sleeps until each cycle's end.
    pub fn real_time(period_s: f64) -> Self {
        Self { period_s, real_time: true, next: None }
    }
}

impl CycleClock for VirtualClock {
    fn period_s(&self) -> f64 {
        self.period_s
    }

    fn tick(&mut self) -> Result<(), DeviceError> {
        if self.real_time {
            let period = Duration::from_secs_f64(self.period_s);
            let next = self.next.unwrap_or_else(Instant::now) + period;
            let now = Instant::now();
            if next > now {
                std::thread::sleep(next - now);
            }
            // A cycle that overran starts the next one from now rather than racing to catch up.
            self.next = Some(if next > now { next } else { now });
        }
        Ok(())
    }
}
