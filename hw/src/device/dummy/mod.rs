//! Dummy drivers that ship with the traits (as openrr's `arci` ships its dummies): joints that follow
//! every command exactly, inputs set through handles a test or a user interface holds, and a virtual
//! clock. They make a rig without hardware and without a simulator.

mod clock;
mod inputs;
mod joints;

pub use clock::VirtualClock;
pub use inputs::{
    DummyForceSensor, DummyMaster, DummyPedals, ForceHandle, MasterHandle, PedalHandle, lock_handle,
};
pub use joints::{DummyArmServo, DummyInstrumentDrive};
