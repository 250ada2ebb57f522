//! Names of devices, for messages and errors ("left arm servo", "pedals").

use std::fmt;

use crate::rig::ArmName;

/// What a device does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DeviceKind {
    /// The six arm axes ([`super::ArmServo`]).
    ArmServo,
    /// The instrument's roll, wrist and jaw motors ([`super::InstrumentDrive`]).
    InstrumentDrive,
    /// The strain gauges on the instrument's shaft ([`super::ForceSensor`]).
    ForceSensor,
    /// A haptic master device ([`super::MasterDevice`]).
    Master,
    /// The foot pedals ([`super::Pedals`]).
    Pedals,
    /// What paces the control cycle ([`super::CycleClock`]).
    Clock,
}

/// One device of a rig: its kind and, where it belongs to one, the arm (for a master device, the arm
/// it steers).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DeviceId {
    /// What it does.
    pub kind: DeviceKind,
    /// The arm it belongs to, if any.
    pub arm: Option<ArmName>,
}

impl DeviceId {
    /// A device of one arm.
    pub const fn of_arm(kind: DeviceKind, arm: ArmName) -> Self {
        Self { kind, arm: Some(arm) }
    }

    /// A device that belongs to no arm (pedals, the clock).
    pub const fn shared(kind: DeviceKind) -> Self {
        Self { kind, arm: None }
    }
}

impl fmt::Display for DeviceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.kind {
            DeviceKind::ArmServo => "arm servo",
            DeviceKind::InstrumentDrive => "instrument drive",
            DeviceKind::ForceSensor => "force sensor",
            DeviceKind::Master => "master device",
            DeviceKind::Pedals => "pedals",
            DeviceKind::Clock => "cycle clock",
        };
        match self.arm {
            Some(arm) => write!(f, "{arm} {what}"),
            None => f.write_str(what),
        }
    }
}
