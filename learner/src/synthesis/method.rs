//! The generalization methods a skill can be synthesized with, selectable by name.

use std::fmt;
use std::str::FromStr;

/// How the learned skill is carried to a new site.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// The paper's: 2D primitives regenerated through the fluid around (virtual) obstacles, the other
    /// primitives by their rules.
    Fluid,
    /// Dynamic movement primitives: each primitive's path learned as a DMP and run to the new start and
    /// goal.
    Dmp,
    /// The demonstration rigidly moved to the new stitch frame and played back.
    Replay,
}

impl Method {
    /// Every method, in a fixed order.
    pub const ALL: [Method; 3] = [Method::Fluid, Method::Dmp, Method::Replay];

    /// Its name: `fluid`, `dmp`, `replay`.
    pub fn as_str(self) -> &'static str {
        match self {
            Method::Fluid => "fluid",
            Method::Dmp => "dmp",
            Method::Replay => "replay",
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Method {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| format!("'{s}' is not a method (fluid, dmp or replay)"))
    }
}
