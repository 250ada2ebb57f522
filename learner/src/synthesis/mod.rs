//! Skill synthesis: from what was learned to a Skill the controller runs at a new stitch site.
//!
//! - [`site`]: the new stitch frame and the rigid motion to it.
//! - [`skill`]: the skill from the primitives by the rules of each type (methods fluid and DMP).
//! - [`schedule`]: its clock: pauses and waits between primitives as demonstrated.
//! - [`track`]: building one instrument's keys.
//! - [`dmp`]: dynamic movement primitives.
//! - [`replay`](mod@replay): the baseline that replays the demonstration, rigidly moved.
//! - [`method`]: the methods by name (`fluid`, `dmp`, `replay`).
//! - [`offsets`]: a skill with each primitive moved by an offset of its own.
//! - [`orientation`]: how keys orient the tip (the jaws' direction, not the roll).
//! - [`approach`]: the way in from where the instruments are to the skill's first poses.
//! - [`take`]: which primitives bring open jaws round the thread they then close on.
//! - [`winding`]: a winding aimed round the jaws it winds round, as their wrist can hold them.

pub mod approach;
pub mod dmp;
pub mod method;
pub mod offsets;
pub mod orientation;
pub mod replay;
pub mod schedule;
pub mod site;
pub mod skill;
pub mod take;
pub mod track;
pub mod winding;

pub use approach::{ApproachSettings, StartPose, prepend_approach};
pub use method::Method;
pub use offsets::{PrimitiveOffset, PrimitiveSpan, offset_primitives};
pub use replay::{ReplaySettings, replay};
pub use schedule::{Schedule, Slot};
pub use site::{Reach, relocation};
pub use skill::{AT_REST_M, ObstacleSource, PrimitiveSettings, REACH_MARGIN_M, Site, Synthesis, synthesize};
pub use take::{Take, takes};

use nalgebra::Vector3;
use thiserror::Error;

use knotlab_hw::rig::ArmName;

/// The trocar points at the site, world frame, m.
#[derive(Clone, Debug, PartialEq)]
pub struct Trocars(pub Vec<(ArmName, Vector3<f64>)>);

impl Trocars {
    /// The trocar of `arm`.
    pub fn of(&self, arm: ArmName) -> Result<Vector3<f64>, SynthesisError> {
        self.0
            .iter()
            .find(|(a, _)| *a == arm)
            .map(|(_, p)| *p)
            .ok_or_else(|| SynthesisError::Empty { what: format!("the trocar of the {arm} arm") })
    }
}

/// Why a skill could not be synthesized.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SynthesisError {
    /// Something needed is empty.
    #[error("{what} is empty")]
    Empty {
        /// What.
        what: String,
    },
    /// A setting or an input value is out of its range.
    #[error("{field}: {reason}")]
    Invalid {
        /// The field.
        field: String,
        /// Why.
        reason: String,
    },
}
