//! Jaws holding the rope, as [`crate::grasp`] holds the chain: closing jaws take the run of the
//! rope that passes between them (its particles within reach of their line, hinge to tip) and hold
//! each where it lies in the jaws' frame ([`super::rigid::Attachment`]); opening lets go; pulled
//! along itself harder than the grip, the rope slides through the jaws ([`RopeGrasp::grip`]), and
//! out of them at its end.

use std::ops::Range;

use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

use super::Ropes;
use super::rigid::{Attachment, Grip, RigidContacts};
use crate::convert::{to_na, to_rapier};
use crate::grasp::JawFaces;
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
        line: (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
    ) -> Option<Self> {
        Self::try_close_between(ropes, contacts, body, body_pose, line, reach_m, None)
    }

    /// [`Self::try_close`] taking only particles between the jaws' `faces`, if given (a coil wound
    /// round the jaws lies beside them).
    pub fn try_close_between(
        ropes: &Ropes,
        contacts: &mut RigidContacts,
        body: RigidBodyHandle,
        body_pose: &Pose,
        (hinge_m, tip_m): (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
        faces: Option<&JawFaces>,
    ) -> Option<Self> {
        let run = Self::run_between(ropes, (hinge_m, tip_m), reach_m, faces)?;
        for p in run.clone() {
            let x = ropes.x[p];
            let local = body_pose.inverse_transform_point(to_rapier(&x));
            contacts.attachments.push(Attachment { particle: p, body, local_m: to_na(local) });
            contacts.attachment_impulses.push(Vector3::zeros());
        }
        Some(Self { body, particles: run })
    }

    /// The run of particles within `reach_m` of the jaws' line `hinge_m`..`tip_m` (world) around
    /// the one nearest it, in its strand; `None` if none is within reach.
    pub fn run_along(
        ropes: &Ropes,
        line: (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
    ) -> Option<Range<usize>> {
        Self::run_between(ropes, line, reach_m, None)
    }

    /// [`Self::run_along`] around the particle nearest the line of those between the jaws'
    /// `faces`, if given; its run stays within reach of the line.
    pub fn run_between(
        ropes: &Ropes,
        (hinge_m, tip_m): (Vector3<f64>, Vector3<f64>),
        reach_m: f64,
        faces: Option<&JawFaces>,
    ) -> Option<Range<usize>> {
        let off = |p: usize| segment_distance(&ropes.x[p], &ropes.x[p], &hinge_m, &tip_m);
        let between = |p: &usize| faces.is_none_or(|f| f.between(&ropes.x[*p]));
        let nearest = (0..ropes.x.len()).filter(between).min_by(|a, b| off(*a).total_cmp(&off(*b)))?;
        if off(nearest) > reach_m {
            return None;
        }
        let strand = ropes.strand_holding(nearest)?;
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

    /// The jaws hold the run by friction: pulled along itself harder than `limit_n`, it slides
    /// through them ([`Grip`]). Jaws squeezing a suture do; a grip that let go altogether above its
    /// limit would let two grips on a taut thread tear one of them loose in a step.
    pub fn grip(&self, contacts: &mut RigidContacts, limit_n: f64) {
        contacts.grips.retain(|g| g.body != self.body);
        contacts.grips.push(Grip {
            body: self.body,
            limit_n,
            slid_local_m: Vector3::zeros(),
            sliding: false,
        });
    }

    /// Once the run has slid a particle's spacing `spacing_m` through the jaws (at `body_pose`),
    /// hands the hold on to the particles that have come into them, where the ones before them
    /// were held: `Some(true)`; `Some(false)` if no rope is left to come in (it slides out of the
    /// jaws); `None` if it has not slid that far (or is not gripped).
    pub fn follow_slide(
        &mut self,
        ropes: &Ropes,
        contacts: &mut RigidContacts,
        body_pose: &Pose,
        spacing_m: f64,
    ) -> Option<bool> {
        let g = contacts.grips.iter().position(|g| g.body == self.body)?;
        let slid = contacts.grips[g].slid_local_m;
        if slid.norm() < spacing_m {
            return None;
        }
        let strand = ropes.strand_holding(self.particles.start)?;
        let origin = body_pose.transform_point(Vector::ZERO);
        let slid_world = to_na(body_pose.transform_point(to_rapier(&slid)) - origin);
        // The particles that have come to where the held ones were lie back against the slide.
        let forward = ropes.way_through(&self.particles)?.dot(&slid_world) < 0.0;
        let run = if forward {
            (self.particles.end < strand.end).then(|| self.particles.start + 1..self.particles.end + 1)
        } else {
            (self.particles.start > strand.start).then(|| self.particles.start - 1..self.particles.end - 1)
        };
        let Some(run) = run else { return Some(false) };
        let back = slid.normalize() * spacing_m;
        for attachment in contacts.attachments.iter_mut() {
            if attachment.body == self.body && self.particles.contains(&attachment.particle) {
                attachment.particle = if forward { attachment.particle + 1 } else { attachment.particle - 1 };
                attachment.local_m -= back;
            }
        }
        contacts.grips[g].slid_local_m -= back;
        self.particles = run;
        Some(true)
    }

    /// Lets go: the attachments go, and the grip.
    pub fn release(self, contacts: &mut RigidContacts) {
        contacts.grips.retain(|g| g.body != self.body);
        contacts.detach(|a| a.body == self.body && self.particles.contains(&a.particle));
    }
}
