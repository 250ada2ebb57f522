//! Limits as decorators: each wraps a driver (an [`ArmServo`] or an [`InstrumentDrive`]) and refuses,
//! with a typed [`LimitError`], a command that breaks its limit; the wrapped driver never sees it.
//!
//! - [`PositionLimit`]: every joint inside its position limits (and finite).
//! - [`VelocityLimit`]: no joint faster than its speed limit, the step from the previous command taken
//!   over one cycle.
//! - [`StepLimit`]: no joint stepping further than a fixed amount per cycle.
//!
//! The step-based limits measure from the last command written through them; before the first write,
//! from the last reading. A write before any read has nothing to measure from and is refused.
//! Decorators stack: `PositionLimit::arm(VelocityLimit::arm(driver, ..), ..)`.

use crate::kinematics::{InstrumentLimits, JointId, JointLimit, ToolJoints};

use super::arm_servo::{ArmServo, ArmServoState, LinkStats};
use super::error::{DeviceError, LimitError};
use super::id::DeviceId;
use super::instrument_drive::{InstrumentDrive, InstrumentState};

/// The arm's joints in [`ArmServo`] order.
pub const ARM_JOINTS: [JointId; 6] =
    [JointId::Arm(1), JointId::Arm(2), JointId::Arm(3), JointId::Arm(4), JointId::Arm(5), JointId::Arm(6)];

/// The instrument's joints in [`tool_array`] order.
pub const TOOL_JOINTS: [JointId; 4] = [JointId::Roll, JointId::WristPitch, JointId::WristYaw, JointId::Jaw];

/// Roll, pitch, yaw, jaw as an array.
pub fn tool_array(joints: &ToolJoints) -> [f64; 4] {
    [joints.roll_rad, joints.pitch_rad, joints.yaw_rad, joints.jaw_rad]
}

fn tool_limits(limits: &InstrumentLimits) -> [JointLimit; 4] {
    [limits.roll, limits.pitch, limits.yaw, limits.jaw]
}

fn check_finite(device: DeviceId, ids: &[JointId], values: &[f64]) -> Result<(), LimitError> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(LimitError::NotFinite { device, joint: ids[i] }),
        None => Ok(()),
    }
}

/// Refuses commands outside the joints' position limits.
#[derive(Debug)]
pub struct PositionLimit<D> {
    inner: D,
    device: DeviceId,
    ids: Vec<JointId>,
    limits: Vec<JointLimit>,
}

impl<D> PositionLimit<D> {
    /// Wraps an arm servo with the limits of axes 1..=6.
    pub fn arm(inner: D, device: DeviceId, limits: [JointLimit; 6]) -> Self {
        Self { inner, device, ids: ARM_JOINTS.to_vec(), limits: limits.to_vec() }
    }

    /// Wraps an instrument drive with the instrument's limits.
    pub fn instrument(inner: D, device: DeviceId, limits: &InstrumentLimits) -> Self {
        Self { inner, device, ids: TOOL_JOINTS.to_vec(), limits: tool_limits(limits).to_vec() }
    }

    /// The wrapped driver.
    pub fn inner(&self) -> &D {
        &self.inner
    }

    fn check(&self, values: &[f64]) -> Result<(), LimitError> {
        check_finite(self.device, &self.ids, values)?;
        for ((&joint, limit), &value_rad) in self.ids.iter().zip(&self.limits).zip(values) {
            if !limit.contains(value_rad) {
                return Err(LimitError::Position {
                    device: self.device,
                    joint,
                    value_rad,
                    lower_rad: limit.lower_rad,
                    upper_rad: limit.upper_rad,
                });
            }
        }
        Ok(())
    }
}

/// What the step-based decorators share: the largest step per joint and the reference it is measured
/// from.
#[derive(Debug)]
struct StepGuard {
    device: DeviceId,
    ids: Vec<JointId>,
    max_step_rad: Vec<f64>,
    reference: Vec<f64>,
    have_reference: bool,
    written: bool,
}

impl StepGuard {
    fn new(device: DeviceId, ids: &[JointId], max_step_rad: Vec<f64>) -> Self {
        let n = ids.len();
        Self {
            device,
            ids: ids.to_vec(),
            max_step_rad,
            reference: vec![0.0; n],
            have_reference: false,
            written: false,
        }
    }

    /// Before the first write, readings are the reference.
    fn observe(&mut self, measured: &[f64]) {
        if !self.written {
            self.reference.copy_from_slice(measured);
            self.have_reference = true;
        }
    }

    /// The first joint whose step is too large: its index and step; or NaN for "no reference".
    fn violation(&self, values: &[f64]) -> Result<Option<(usize, f64)>, LimitError> {
        check_finite(self.device, &self.ids, values)?;
        if !self.have_reference {
            return Ok(Some((0, f64::INFINITY)));
        }
        Ok(values
            .iter()
            .zip(&self.reference)
            .zip(&self.max_step_rad)
            .map(|((v, r), m)| ((v - r).abs(), *m))
            .position(|(step, max)| step > max * (1.0 + 1e-9) + 1e-12)
            .map(|i| (i, (values[i] - self.reference[i]).abs())))
    }

    fn commit(&mut self, values: &[f64]) {
        self.reference.copy_from_slice(values);
        self.have_reference = true;
        self.written = true;
    }
}

/// Refuses commands that would move a joint faster than its speed limit: the step from the previous
/// command, over one cycle of `period_s`.
#[derive(Debug)]
pub struct VelocityLimit<D> {
    inner: D,
    guard: StepGuard,
    max_rad_s: Vec<f64>,
    period_s: f64,
}

impl<D> VelocityLimit<D> {
    /// Wraps an arm servo with the speed limits of axes 1..=6, for a cycle of `period_s`.
    pub fn arm(inner: D, device: DeviceId, limits: [JointLimit; 6], period_s: f64) -> Self {
        let max: Vec<f64> = limits.iter().map(|l| l.max_velocity_rad_s).collect();
        Self::new(inner, device, &ARM_JOINTS, max, period_s)
    }

    /// Wraps an instrument drive with the instrument's speed limits, for a cycle of `period_s`.
    pub fn instrument(inner: D, device: DeviceId, limits: &InstrumentLimits, period_s: f64) -> Self {
        let max: Vec<f64> = tool_limits(limits).iter().map(|l| l.max_velocity_rad_s).collect();
        Self::new(inner, device, &TOOL_JOINTS, max, period_s)
    }

    fn new(inner: D, device: DeviceId, ids: &[JointId], max_rad_s: Vec<f64>, period_s: f64) -> Self {
        let steps = max_rad_s.iter().map(|v| v * period_s).collect();
        Self { inner, guard: StepGuard::new(device, ids, steps), max_rad_s, period_s }
    }

    /// The wrapped driver.
    pub fn inner(&self) -> &D {
        &self.inner
    }

    fn check(&self, values: &[f64]) -> Result<(), LimitError> {
        match self.guard.violation(values)? {
            Some((i, step)) => Err(LimitError::Velocity {
                device: self.guard.device,
                joint: self.guard.ids[i],
                velocity_rad_s: step / self.period_s,
                max_rad_s: self.max_rad_s[i],
            }),
            None => Ok(()),
        }
    }
}

/// Refuses commands that step a joint further than a fixed amount in one cycle.
#[derive(Debug)]
pub struct StepLimit<D> {
    inner: D,
    guard: StepGuard,
}

impl<D> StepLimit<D> {
    /// Wraps an arm servo: at most `max_step_rad[i]` per cycle on axis i + 1.
    pub fn arm(inner: D, device: DeviceId, max_step_rad: [f64; 6]) -> Self {
        Self { inner, guard: StepGuard::new(device, &ARM_JOINTS, max_step_rad.to_vec()) }
    }

    /// Wraps an instrument drive: at most `max_step_rad` per cycle on roll, pitch, yaw and jaw.
    pub fn instrument(inner: D, device: DeviceId, max_step_rad: [f64; 4]) -> Self {
        Self { inner, guard: StepGuard::new(device, &TOOL_JOINTS, max_step_rad.to_vec()) }
    }

    /// The wrapped driver.
    pub fn inner(&self) -> &D {
        &self.inner
    }

    fn check(&self, values: &[f64]) -> Result<(), LimitError> {
        match self.guard.violation(values)? {
            Some((i, step_rad)) => Err(LimitError::Step {
                device: self.guard.device,
                joint: self.guard.ids[i],
                step_rad,
                max_step_rad: self.guard.max_step_rad[i],
            }),
            None => Ok(()),
        }
    }
}

impl<D: ArmServo> ArmServo for PositionLimit<D> {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        self.inner.read()
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        self.check(joints_rad)?;
        self.inner.write(joints_rad)
    }

    fn link_stats(&self) -> Option<LinkStats> {
        self.inner.link_stats()
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        self.inner.shutdown()
    }
}

impl<D: InstrumentDrive> InstrumentDrive for PositionLimit<D> {
    fn read(&mut self) -> Result<InstrumentState, DeviceError> {
        self.inner.read()
    }

    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
        self.check(&tool_array(joints))?;
        self.inner.write(joints)
    }

    fn shutdown(&mut self) -> Result<(), DeviceError> {
        self.inner.shutdown()
    }
}

/// Implements both joint-device traits for a step-based decorator with a `guard` and a `check`.
macro_rules! step_decorator {
    ($name:ident) => {
        impl<D: ArmServo> ArmServo for $name<D> {
            fn read(&mut self) -> Result<ArmServoState, DeviceError> {
                let state = self.inner.read()?;
                self.guard.observe(&state.joints_rad);
                Ok(state)
            }

            fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
                self.check(joints_rad)?;
                self.inner.write(joints_rad)?;
                self.guard.commit(joints_rad);
                Ok(())
            }

            fn link_stats(&self) -> Option<LinkStats> {
                self.inner.link_stats()
            }

            fn shutdown(&mut self) -> Result<(), DeviceError> {
                self.inner.shutdown()
            }
        }

        impl<D: InstrumentDrive> InstrumentDrive for $name<D> {
            fn read(&mut self) -> Result<InstrumentState, DeviceError> {
                let state = self.inner.read()?;
                self.guard.observe(&tool_array(&state.joints));
                Ok(state)
            }

            fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
                let values = tool_array(joints);
                self.check(&values)?;
                self.inner.write(joints)?;
                self.guard.commit(&values);
                Ok(())
            }

            fn shutdown(&mut self) -> Result<(), DeviceError> {
                self.inner.shutdown()
            }
        }
    };
}

step_decorator!(VelocityLimit);
step_decorator!(StepLimit);
