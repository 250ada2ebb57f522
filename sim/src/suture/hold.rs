//! What a pair of jaws holds of the suture: the chain's segment or the needle on a fixed joint
//! ([`Grasp`]), or a run of the rope's particles in its grip ([`RopeGrasp`]).

use crate::grasp::Grasp;
use crate::rope::grasp::RopeGrasp;

/// A hold of one pair of jaws. Made by [`super::Suture::try_grasp`], ended by
/// [`super::Suture::release`].
#[derive(Clone, Debug, PartialEq)]
pub struct Hold {
    pub(super) kind: HoldKind,
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum HoldKind {
    /// A fixed joint on a segment of the chain, or on the needle (with either model).
    Joint(Grasp),
    /// A run of the rope in the jaws' grip; `sliding`: the rope slid through them in the last step.
    Grip { grasp: RopeGrasp, sliding: bool },
}

impl Hold {
    pub(super) fn joint(grasp: Grasp) -> Self {
        Self { kind: HoldKind::Joint(grasp) }
    }

    pub(super) fn grip(grasp: RopeGrasp) -> Self {
        Self { kind: HoldKind::Grip { grasp, sliding: false } }
    }

    /// Whether the jaws hold the needle.
    pub fn on_needle(&self) -> bool {
        matches!(&self.kind, HoldKind::Joint(g) if g.on_needle)
    }

    /// Where along the suture the jaws hold it: the segment (0 for the needle), or the middle of
    /// the held run of particles, counted from the needle end.
    pub fn at(&self) -> usize {
        match &self.kind {
            HoldKind::Joint(grasp) => grasp.segment,
            HoldKind::Grip { grasp, .. } => grasp.particles.start + grasp.particles.len() / 2,
        }
    }

    /// The fixed joint, when the hold is one (on the chain or on the needle).
    pub fn joint_grasp(&self) -> Option<&Grasp> {
        match &self.kind {
            HoldKind::Joint(grasp) => Some(grasp),
            HoldKind::Grip { .. } => None,
        }
    }
}
