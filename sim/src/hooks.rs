//! The scene's contact filter: pairs of colliders that must not touch this step. Thread segments inside
//! the tissue pass through the flaps; a held segment (and its neighbours, and whatever lies between
//! closing jaws) passes through the jaws holding it, which hold it by the grasp constraint instead.
//! Everything else collides as the collision groups say. Contacts of the thread with itself take the
//! thread's own friction ([`ThreadOnItself`]).

use std::collections::HashSet;

use rapier3d::prelude::*;

/// Collider pairs kept apart from contact for one step.
#[derive(Clone, Debug, Default)]
pub struct ContactFilter {
    excluded: HashSet<(ColliderHandle, ColliderHandle)>,
    /// The thread's friction on itself, if it has its own.
    pub thread_on_itself: Option<ThreadOnItself>,
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

    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        if let Some(on_itself) = &self.thread_on_itself {
            on_itself.modify_solver_contacts(context);
        }
    }
}

/// Suture on suture: every contact between two thread segments (the colliders that ask for it with
/// [`ActiveHooks::MODIFY_SOLVER_CONTACTS`], as [`crate::thread::Thread::build`] makes them when the
/// thread has a friction on itself) takes this friction, whatever the combine rule would give.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreadOnItself {
    /// The friction coefficient.
    pub friction: f64,
}

impl ThreadOnItself {
    /// The hook for `thread`, if it has a friction on itself.
    pub fn of(thread: &crate::thread::ThreadParams) -> Option<Self> {
        thread.friction_on_itself.map(|friction| Self { friction })
    }
}

impl PhysicsHooks for ThreadOnItself {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let segment = |h: ColliderHandle| {
            context
                .colliders
                .get(h)
                .is_some_and(|c| c.active_hooks().contains(ActiveHooks::MODIFY_SOLVER_CONTACTS))
        };
        if !(segment(context.collider1) && segment(context.collider2)) {
            return;
        }
        if let ModifiableContacts::Rigid(manifold) = &mut context.contacts {
            *manifold.friction = self.friction;
        }
    }
}
