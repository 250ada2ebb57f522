//! The rig config (TOML): which backend drives each device (`sim`, `melfa`, `dummy`), where the trocars
//! are, and the controller's tuning. Sim or real is chosen here, not in code.
//!
//! - [`schema`]: the file's contents.
//! - [`load`]: reading it, with errors naming the file, line, key and reason.
//! - [`build`]: turning it into devices (wrapped in their limit decorators) and a controller; `sim`
//!   devices come from a [`build::SimulatedScene`] that the `sim` crate implements, so `hw` needs no
//!   simulator.
//!
//! The shipped examples are `scenarios/rigs/sim.toml` and `scenarios/rigs/melfa.toml`.

pub mod build;
pub mod load;
pub mod schema;

pub use build::{BuiltRig, DummyHandles, RigBuildError, SimulatedScene, build_rig};
pub use load::{RigConfigError, load_rig_config, parse_rig_config};
pub use schema::{
    ArmConfig, Backend, ControllerSection, DeviceConfig, ForceConfig, InstrumentConfig, LayoutName,
    RigConfig, ServoConfig,
};
