//! What one control cycle saw and did: the readings of every device and the commands, for a caller that
//! records demonstrations or logs a run.

use nalgebra::{IsometryMatrix3, Vector3};

use crate::device::PedalState;
use crate::kinematics::{ArmJoints, TipTarget};
use crate::rig::ArmName;

/// Where the controller stands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// No skill loaded: every arm holds.
    Idle,
    /// Executing a skill.
    Running,
    /// The skill ran to its end: every arm holds its last set-point.
    Finished,
    /// The emergency stop was pressed: no new motion is commanded (latched).
    EmergencyStopped,
    /// A device failed, a watchdog fired or a target was unreachable: no new motion is commanded.
    Faulted,
}

/// One arm in one cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmRecord {
    /// Which arm.
    pub arm: ArmName,
    /// Joints as the devices read them (the tool's from the instrument drive; zero without one).
    pub measured: ArmJoints,
    /// The set-point in force after this cycle.
    pub commanded: ArmJoints,
    /// Whether a new set-point was written this cycle.
    pub wrote: bool,
    /// The tip where the measured joints put it (forward kinematics).
    pub world_from_tip: IsometryMatrix3<f64>,
    /// The skill's target for this cycle, if the arm has a track and was commanded.
    pub target: Option<TipTarget>,
    /// Force on the instrument, shaft frame, N (zero without a sensor).
    pub shaft_force_n: Vector3<f64>,
    /// The same in the world frame, N.
    pub world_force_n: Vector3<f64>,
    /// Every device of the arm gave a fresh reading this cycle.
    pub fresh: bool,
    /// The controller limited this cycle's step to the joints' speed.
    pub clamped: bool,
}

/// One cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleRecord {
    /// The cycle's index from the controller's start (0 for the first step, and for the readings taken
    /// by [`super::Controller::new`]).
    pub cycle: u64,
    /// Device time at this cycle's reading, s (cycle times period).
    pub time_s: f64,
    /// Skill time of this cycle's targets, s (while running; the last one afterwards).
    pub skill_time_s: f64,
    /// Status after this cycle.
    pub status: Status,
    /// The pedals.
    pub pedals: PedalState,
    /// Every arm, in the order the devices were given.
    pub arms: Vec<ArmRecord>,
}

impl CycleRecord {
    /// The record of one arm.
    pub fn arm(&self, arm: ArmName) -> Option<&ArmRecord> {
        self.arms.iter().find(|a| a.arm == arm)
    }
}

/// An event that fired.
#[derive(Clone, Debug, PartialEq)]
pub struct FiredEvent {
    /// The arm.
    pub arm: ArmName,
    /// Index of the event in the arm's track.
    pub event: usize,
    /// Skill time it fired at, s.
    pub time_s: f64,
    /// The force that fired it, N.
    pub force_n: f64,
}

/// How a run to the end went.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunOutcome {
    /// The skill ran to its end.
    Completed,
    /// The emergency stop halted it.
    EmergencyStopped,
}

/// What a run to the end did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunSummary {
    /// How it ended.
    pub outcome: RunOutcome,
    /// Cycles run.
    pub cycles: u64,
    /// Skill time reached, s.
    pub skill_time_s: f64,
}
