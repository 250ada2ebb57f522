//! What can go wrong with a device: typed, naming the device, never a panic.

use crate::kinematics::JointId;

use super::id::DeviceId;

/// A command a limit decorator refused, and why.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum LimitError {
    /// A joint command outside the joint's position limits.
    #[error(
        "{device}: {joint} command {value_rad:.6} rad is outside its limits {lower_rad:.6}..{upper_rad:.6} rad"
    )]
    Position {
        /// The device.
        device: DeviceId,
        /// The joint.
        joint: JointId,
        /// The commanded position, rad.
        value_rad: f64,
        /// Its lower limit, rad.
        lower_rad: f64,
        /// Its upper limit, rad.
        upper_rad: f64,
    },
    /// A joint command that would move the joint faster than its speed limit in one cycle.
    #[error(
        "{device}: {joint} command asks for {velocity_rad_s:.4} rad/s, faster than its limit {max_rad_s:.4} rad/s"
    )]
    Velocity {
        /// The device.
        device: DeviceId,
        /// The joint.
        joint: JointId,
        /// The speed the command implies (step over one cycle), rad/s.
        velocity_rad_s: f64,
        /// The speed limit, rad/s.
        max_rad_s: f64,
    },
    /// A joint command that steps further in one cycle than allowed.
    #[error(
        "{device}: {joint} command steps {step_rad:.6} rad in one cycle, more than {max_step_rad:.6} rad"
    )]
    Step {
        /// The device.
        device: DeviceId,
        /// The joint.
        joint: JointId,
        /// The step from the previous command, rad.
        step_rad: f64,
        /// The largest step allowed, rad.
        max_step_rad: f64,
    },
    /// A joint command that is NaN or infinite.
    #[error("{device}: {joint} command is not a finite number")]
    NotFinite {
        /// The device.
        device: DeviceId,
        /// The joint.
        joint: JointId,
    },
}

/// Why a device could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum DeviceError {
    /// A command was refused by a limit decorator.
    #[error(transparent)]
    Limit(#[from] LimitError),
    /// The device did not answer in time and has nothing, not even a stale value, to give.
    #[error("{device}: no answer within {waited_s:.4} s")]
    Timeout {
        /// The device.
        device: DeviceId,
        /// How long the driver waited, s.
        waited_s: f64,
    },
    /// The link to the device is considered down after a run of lost replies.
    #[error("{device}: link down: {lost} replies lost in a row ({detail})")]
    LinkDown {
        /// The device.
        device: DeviceId,
        /// Consecutive losses.
        lost: u32,
        /// Where the link goes and what was tried.
        detail: String,
    },
    /// The device's protocol was broken: a malformed or unexpected packet.
    #[error("{device}: {reason}")]
    Protocol {
        /// The device.
        device: DeviceId,
        /// What was wrong, naming the field.
        reason: String,
    },
    /// An operating-system error while talking to the device.
    #[error("{device}: {action}: {source}")]
    Io {
        /// The device.
        device: DeviceId,
        /// What the driver was doing ("sending MOVE to 192.168.0.20:10000").
        action: String,
        /// The error.
        source: std::io::Error,
    },
    /// The device reports a fault of its own (a simulation that went unhealthy, a tripped drive).
    #[error("{device}: fault: {reason}")]
    Fault {
        /// The device.
        device: DeviceId,
        /// What the device said.
        reason: String,
    },
    /// The device's session has been ended; it accepts no more commands.
    #[error("{device}: the session has ended")]
    Closed {
        /// The device.
        device: DeviceId,
    },
}

impl DeviceError {
    /// The device the error is about.
    pub fn device(&self) -> DeviceId {
        match self {
            DeviceError::Limit(
                LimitError::Position { device, .. }
                | LimitError::Velocity { device, .. }
                | LimitError::Step { device, .. }
                | LimitError::NotFinite { device, .. },
            )
            | DeviceError::Timeout { device, .. }
            | DeviceError::LinkDown { device, .. }
            | DeviceError::Protocol { device, .. }
            | DeviceError::Io { device, .. }
            | DeviceError::Fault { device, .. }
            | DeviceError::Closed { device } => *device,
        }
    }
}
