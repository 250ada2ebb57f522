//! Joint devices that are where they were last told to be, from the next read on.

use crate::device::arm_servo::{ArmServo, ArmServoState};
use crate::device::error::DeviceError;
use crate::device::instrument_drive::{InstrumentDrive, InstrumentState};
use crate::kinematics::ToolJoints;

/// An arm whose axes reach every set-point within one cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct DummyArmServo {
    joints_rad: [f64; 6],
}

impl DummyArmServo {
    /// Standing at `joints_rad`.
    pub fn new(joints_rad: [f64; 6]) -> Self {
        Self { joints_rad }
    }
}

impl ArmServo for DummyArmServo {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        Ok(ArmServoState { joints_rad: self.joints_rad, fresh: true })
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        self.joints_rad = *joints_rad;
        Ok(())
    }
}

/// An instrument whose motors reach every set-point within one cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct DummyInstrumentDrive {
    joints: ToolJoints,
}

impl DummyInstrumentDrive {
    /// Standing at `joints`.
    pub fn new(joints: ToolJoints) -> Self {
        Self { joints }
    }
}

impl InstrumentDrive for DummyInstrumentDrive {
    fn read(&mut self) -> Result<InstrumentState, DeviceError> {
        Ok(InstrumentState { joints: self.joints, fresh: true })
    }

    fn write(&mut self, joints: &ToolJoints) -> Result<(), DeviceError> {
        self.joints = *joints;
        Ok(())
    }
}
