//! Jaws holding the rope, as [`crate::grasp`] holds the chain: closing jaws take the run of the
//! rope that passes between them (its particles within reach of their line, hinge to tip) and hold
//! each where it lies in the jaws' frame ([`super::rigid::Attachment`]); opening lets go; a pull
//! beyond the grip slips.

use std::ops::Range;

use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

use super::Ropes;
use super::rigid::{Attachment, RigidContacts};
use knotlab_hw::geometry::segment_distance;

/// A run of the rope held by a body.
#[derive(Clone, Debug, PartialEq)]
pub struct RopeGrasp {
    /// The jaws' carrier.
    pub body: RigidBodyHandle,
    /// The held particles.
    pub particles: Range<usize>,
}

impl RopeGrasp {
    /// Takes the run of particles within `reach_m` of the jaws' line `hinge_m`..`tip_m` (world)
    /// around the one nearest it, if any is within reach, attaching each to `body` (at `body_pose`)
    /// where it lies. (The jaws' colliders must let the run through, and what lies along the jaws
    /// either side of it: pushed out of them while its neighbours are held in, it would be torn
    /// between the two. The scene sets that each step.)
    pub fn try_close(
        ropes: &Ropes,
        contacts: &mut RigidContacts,
        body: RigidBodyHandle,
        body_pose: &Pose,
        (hinge_m, tip_m): (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
    ) -> Option<Self> {
        let run = Self::run_along(ropes, (hinge_m, tip_m), reach_m)?;
        for p in run.clone() {
            let x = ropes.x[p];
            let local = body_pose.inverse_transform_point(Vector::new(x.x, x.y, x.z));
            contacts.attachments.push(Attachment {
                particle: p,
                body,
                local_m: Vector3::new(local.x, local.y, local.z),
            });
            contacts.attachment_impulses.push(Vector3::zeros());
        }
        Some(Self { body, particles: run })
    }

    /// The run of particles within `reach_m` of the jaws' line `hinge_m`..`tip_m` (world) around
    /// the one nearest it, in its strand; `None` if none is within reach.
    pub fn run_along(
        ropes: &Ropes,
        (hinge_m, tip_m): (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
    ) -> Option<Range<usize>> {
        let off = |p: usize| segment_distance(&ropes.x[p], &ropes.x[p], &hinge_m, &tip_m);
        let nearest = (0..ropes.x.len()).min_by(|a, b| off(*a).total_cmp(&off(*b)))?;
        if off(nearest) > reach_m {
            return None;
        }
        let strand = ropes.strands.iter().find(|s| s.contains(&nearest))?.clone();
        let mut first = nearest;
        while first > strand.start && off(first - 1) <= reach_m {
            first -= 1;
        }
        let mut last = nearest;
        while last + 1 < strand.end && off(last + 1) <= reach_m {
            last += 1;
        }
        Some(first..last + 1)
    }

    /// The held run widened by `clear` particles either side (within the `count` particles): what
    /// the jaws let through while they hold it or let go of it.
    pub fn widened(&self, clear: usize, count: usize) -> Range<usize> {
        self.particles.start.saturating_sub(clear)..(self.particles.end + clear).min(count)
    }

    /// The force the jaws held the rope with over the last step of `dt_s`, N.
    pub fn force_n(&self, contacts: &RigidContacts, dt_s: f64) -> Vector3<f64> {
        contacts
            .attachments
            .iter()
            .zip(&contacts.attachment_impulses)
            .filter(|(a, _)| a.body == self.body && self.particles.contains(&a.particle))
            .map(|(_, impulse)| impulse)
            .sum::<Vector3<f64>>()
            / dt_s
    }

    /// Lets go: the attachments go.
    pub fn release(self, contacts: &mut RigidContacts) {
        contacts.detach(|a| a.body == self.body && self.particles.contains(&a.particle));
    }
}
