//! The scene's contact filter: pairs of colliders that must not touch this step. Thread segments inside
//! the tissue pass through the flaps; a held segment (and its neighbours, and whatever lies between
//! closing jaws) passes through the jaws holding it, which hold it by the grasp constraint instead.
//! Everything else collides as the collision groups say.

use std::collections::HashSet;

use rapier3d::prelude::*;

/// Collider pairs kept apart from contact for one step.
#[derive(Clone, Debug, Default)]
pub struct ContactFilter {
    excluded: HashSet<(ColliderHandle, ColliderHandle)>,
}

fn ordered(a: ColliderHandle, b: ColliderHandle) -> (ColliderHandle, ColliderHandle) {
    if a.into_raw_parts() <= b.into_raw_parts() { (a, b) } else { (b, a) }
}

impl ContactFilter {
    /// No contact between any collider of `a` and any of `b`.
    pub fn exclude_all(&mut self, a: &[ColliderHandle], b: &[ColliderHandle]) {
        for x in a {
            for y in b {
                self.excluded.insert(ordered(*x, *y));
            }
        }
    }

    /// Whether the pair is kept apart.
    pub fn excludes(&self, a: ColliderHandle, b: ColliderHandle) -> bool {
        self.excluded.contains(&ordered(a, b))
    }
}

impl PhysicsHooks for ContactFilter {
    fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
        if self.excludes(context.collider1, context.collider2) {
            None
        } else {
            Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
        }
    }
}
