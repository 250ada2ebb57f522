//! The devices one rig is made of, as the controller drives them.

use crate::rig::ArmName;

use super::arm_servo::ArmServo;
use super::clock::CycleClock;
use super::force_sensor::ForceSensor;
use super::instrument_drive::InstrumentDrive;
use super::master::MasterDevice;
use super::pedals::Pedals;

/// The devices of one arm.
pub struct ArmDevices {
    /// The six axes.
    pub servo: Box<dyn ArmServo>,
    /// The instrument's motors (none for the endoscope).
    pub instrument: Option<Box<dyn InstrumentDrive>>,
    /// The instrument's strain gauges, if fitted.
    pub force: Option<Box<dyn ForceSensor>>,
}

/// Every device of a rig.
pub struct DeviceSet {
    /// The arms that take part, each once.
    pub arms: Vec<(ArmName, ArmDevices)>,
    /// The foot pedals (the emergency stop is not optional).
    pub pedals: Box<dyn Pedals>,
    /// Master devices, by the arm each steers.
    pub masters: Vec<(ArmName, Box<dyn MasterDevice>)>,
    /// What paces the cycle.
    pub clock: Box<dyn CycleClock>,
}
