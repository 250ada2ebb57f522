//! One arm in the simulation: its servos, what it was told, its jaws' state and its gauge's reading.

use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::rig::ArmName;
use nalgebra::Vector3;
use rapier3d::prelude::*;

use crate::servo::{ServoModel, ServoState};
use crate::suture::Hold;

/// What an instrument's jaws are doing with the suture: one state machine per arm. Opening them
/// (past where they took their hold) takes every state back to [`JawState::Free`].
#[derive(Clone, Debug, PartialEq)]
pub enum JawState {
    /// Open, or closing on nothing yet: they take what they squeeze or close on.
    Free,
    /// Holding the suture or the needle.
    Holding {
        /// What they hold.
        hold: Hold,
        /// The jaw command when the hold was taken, rad: told to open past it, the jaws let go.
        at_jaw_rad: f64,
    },
    /// Their hold slipped: lost until the jaws reopen.
    Slipped,
    /// They closed on nothing and stay empty until they reopen: what later touches closed jaws is
    /// not taken (and collides with them).
    ClosedEmpty,
}

/// One arm in the simulation: its servos and what it was told.
pub struct SimArm {
    /// Which arm.
    pub name: ArmName,
    /// Servos in [`ArmJoints::ORDER`] (the endoscope's tool servos are unused).
    pub servos: Vec<ServoModel>,
    /// Their states.
    pub states: Vec<ServoState>,
    /// The last joint command.
    pub command: ArmJoints,
    /// What the jaws are doing.
    pub jaws: JawState,
    /// Force on the instrument from contacts and grasps, as the strain gauges read it (filtered,
    /// with noise), world frame, N.
    pub force_n: Vector3<f64>,
    /// The physical force through the gauges' filter (before the noise), world frame, N.
    pub filtered_force_n: Vector3<f64>,
    /// The bodies of the instrument (the flange and every link below it): what the gauge feels.
    pub instrument_bodies: Vec<RigidBodyHandle>,
    /// The colliders of the jaws and the clevis carrying them.
    pub jaw_colliders: Vec<ColliderHandle>,
}

impl SimArm {
    /// What the jaws hold, if anything.
    pub fn hold(&self) -> Option<&Hold> {
        match &self.jaws {
            JawState::Holding { hold, .. } => Some(hold),
            _ => None,
        }
    }

    /// Whether the jaws hold the thread or the needle.
    pub fn holds(&self) -> bool {
        self.hold().is_some()
    }

    /// Whether the jaws hold the needle.
    pub fn holds_needle(&self) -> bool {
        self.hold().is_some_and(Hold::on_needle)
    }

    /// Where along the thread the jaws hold it: the chain's segment, or the rope's particle in the
    /// middle of the held run (an index into the thread's centreline either way, from the needle
    /// end).
    pub fn held_at(&self) -> Option<usize> {
        self.hold().map(Hold::at)
    }

    /// Whether the jaws' hold slipped and they have not reopened since.
    pub fn slipped(&self) -> bool {
        self.jaws == JawState::Slipped
    }

    /// Whether the jaws closed on nothing and have not reopened since.
    pub fn closed_empty(&self) -> bool {
        self.jaws == JawState::ClosedEmpty
    }

    /// The joints as the links stand now (after lag, play and calibration).
    pub fn actual(&self) -> ArmJoints {
        let v: [f64; 10] = std::array::from_fn(|i| self.states[i].link_rad);
        ArmJoints::from_array(v)
    }
}
