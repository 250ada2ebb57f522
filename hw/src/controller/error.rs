//! Why the controller stopped or refused to start.

use crate::device::{DeviceError, DeviceId, DeviceKind};
use crate::kinematics::IkError;
use crate::rig::ArmName;
use crate::skill::SkillError;

use super::record::Status;

/// Why the controller cannot start, run a skill, or go on.
#[derive(Debug, thiserror::Error)]
pub enum ControllerError {
    /// The devices and the arm setups do not match, or a parameter is out of range.
    #[error("controller setup: {0}")]
    Setup(String),
    /// The skill fails its checks.
    #[error(transparent)]
    Skill(#[from] SkillError),
    /// The skill needs a device the rig lacks.
    #[error("skill track for the {arm} arm needs a {device:?} device: {why}")]
    SkillNeedsDevice {
        /// The arm.
        arm: ArmName,
        /// The missing device.
        device: DeviceKind,
        /// What needs it.
        why: &'static str,
    },
    /// A device failed; the run stopped and every arm holds its last set-point.
    #[error("device fault, motion stopped: {0}")]
    Device(#[from] DeviceError),
    /// A device gave no fresh reading for too long; the run stopped.
    #[error("watchdog: {device} gave no fresh reading for {cycles} cycles ({seconds:.3} s); motion stopped")]
    Watchdog {
        /// The device.
        device: DeviceId,
        /// Stale cycles in a row.
        cycles: u32,
        /// The same in seconds.
        seconds: f64,
    },
    /// The skill's target cannot be reached; the run stopped.
    #[error("{arm} arm at skill time {time_s:.4} s: target unreachable ({source}); motion stopped")]
    Ik {
        /// The arm.
        arm: ArmName,
        /// When, s from the skill's start.
        time_s: f64,
        /// Why.
        source: IkError,
    },
    /// An emergency stop cannot be cleared while the pedal is pressed.
    #[error("the emergency stop pedal is still pressed")]
    EmergencyStopHeld,
    /// `run_to_end` without a skill.
    #[error("no skill loaded")]
    NoSkill,
    /// A step after the run faulted, a skill while emergency-stopped, or a reset with nothing to reset.
    #[error("the controller is {status:?}: not possible now")]
    NotRunning {
        /// Its status.
        status: Status,
    },
}
