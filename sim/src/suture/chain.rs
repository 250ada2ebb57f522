//! The capsule chain as the scene's suture (`thread.model = "chain"`): Rapier bodies jointed end
//! to end ([`Thread`]), the needle on the first segment, the thread tied to the flaps by sliding
//! joints ([`Stitch`]), and the contact filter that lets held segments through the jaws holding them.

use std::ops::RangeInclusive;

use nalgebra::{IsometryMatrix3, Point3, Vector3};
use rapier3d::prelude::*;

use super::JawsNow;
use crate::convert::to_na;
use crate::grasp::{GRASP_REACH_M, JAW_CENTRE_OFFSET_M};
use crate::hooks::{ContactFilter, ThreadOnItself};
use crate::needle::Needle;
use crate::physics::Physics;
use crate::scene::SceneConfig;
use crate::stitch::{Stitch, StitchEvent};
use crate::thread::Thread;
use crate::thread_watch::ThreadWatch;
use crate::tissue::{Flap, Tissue};

/// Thread within this distance of the centre of jaws whose grasp slipped (beyond a segment's length)
/// does not collide with them until they reopen, m.
pub const HELD_CLEARANCE_M: f64 = 0.003;

/// The chain, its stitch and what the stitch did.
pub struct ChainSuture {
    thread: Thread,
    stitch: Stitch,
    stitch_events: Vec<StitchEvent>,
    on_itself: Option<ThreadOnItself>,
    radius_m: f64,
}

impl ChainSuture {
    /// Lays the chain along `layout` (needle end first), puts the needle on its first segment and
    /// ties it to the flaps where it passes their stitch points.
    pub(super) fn build(
        config: &SceneConfig,
        layout: &[Vector3<f64>],
        physics: &mut Physics,
        tissue: &mut Tissue,
    ) -> (Self, Needle) {
        let thread = Thread::build(physics, &config.thread, &layout[0], &(layout[1] - layout[0]));
        thread.lay_along(physics, layout);
        let needle = Needle::attach(&config.needle, physics, &thread);
        let stitch = Stitch::anchor(physics, &thread, tissue, config.stitch.slide_friction_n);
        let chain = Self {
            thread,
            stitch,
            stitch_events: Vec::new(),
            on_itself: ThreadOnItself::of(&config.thread),
            radius_m: config.thread.radius_m,
        };
        (chain, needle)
    }

    /// The chain's bodies.
    pub fn thread(&self) -> &Thread {
        &self.thread
    }

    /// The joints tying it to the flaps.
    pub fn stitch(&self) -> &Stitch {
        &self.stitch
    }

    /// The thread's ends leaving a flap, in order.
    pub fn stitch_events(&self) -> &[StitchEvent] {
        &self.stitch_events
    }

    pub(super) fn centreline(&self, physics: &Physics) -> Vec<Vector3<f64>> {
        self.thread.centreline(physics)
    }

    pub(super) fn arc_at_m(&self, physics: &Physics, tissue: &Tissue, flap: Flap) -> Option<f64> {
        self.stitch.arc_at_m(physics, &self.thread, tissue, flap)
    }

    pub(super) fn inside(&self) -> Option<RangeInclusive<usize>> {
        self.stitch.segments_inside()
    }

    pub(super) fn capsules(&self, physics: &Physics) -> Vec<crate::tunnelling::Capsule> {
        self.thread.capsules(physics, 0.0)
    }

    pub(super) fn first_segment(&self) -> Option<RigidBodyHandle> {
        self.thread.segments.first().copied()
    }

    pub(super) fn segments(&self) -> &[RigidBodyHandle] {
        &self.thread.segments
    }

    /// Which segments touch which of `links` (an active contact between their colliders):
    /// `(segment, link name)`, sorted.
    pub(super) fn touching(
        &self,
        physics: &Physics,
        links: &[(String, RigidBodyHandle)],
    ) -> Vec<(usize, String)> {
        let link_of =
            |body: RigidBodyHandle| links.iter().find(|(_, h)| *h == body).map(|(name, _)| name.clone());
        let segment_of = |body: RigidBodyHandle| self.thread.segment_index(body);
        let mut found: Vec<(usize, String)> = physics
            .narrow_phase
            .contact_pairs()
            .filter(|pair| pair.has_any_active_contact())
            .filter_map(|pair| {
                let b1 = physics.colliders.get(pair.collider1)?.parent()?;
                let b2 = physics.colliders.get(pair.collider2)?.parent()?;
                match (segment_of(b1), segment_of(b2)) {
                    (Some(i), None) => Some((i, link_of(b2)?)),
                    (None, Some(i)) => Some((i, link_of(b1)?)),
                    _ => None,
                }
            })
            .collect();
        found.sort();
        found.dedup();
        found
    }

    /// The pairs that must not touch this step: segments inside the tissue and the flaps; the jaws
    /// and what they hold (the held segment and its neighbours), are closing on (what lies between
    /// them) or just lost (what is near their centre). Jaws that closed on nothing touch everything.
    pub(super) fn contact_filter(
        &self,
        physics: &Physics,
        tissue: &Tissue,
        jaws: &[JawsNow],
    ) -> ContactFilter {
        let mut filter = ContactFilter::default();
        filter.thread_on_itself = self.on_itself;
        let colliders_of = |i: usize| -> Vec<ColliderHandle> {
            self.thread.segments.get(i).map_or_else(Vec::new, |h| physics.bodies[*h].colliders().to_vec())
        };
        if let Some(range) = self.stitch.segments_inside() {
            let inside: Vec<ColliderHandle> = range.flat_map(colliders_of).collect();
            filter.exclude_all(&tissue.flap_colliders, &inside);
        }
        for jaw in jaws {
            if jaw.colliders.is_empty() {
                continue;
            }
            let mut near: Vec<usize> = Vec::new();
            if let Some(grasp) = jaw.hold.and_then(super::Hold::joint_grasp) {
                near.extend(grasp.segment.saturating_sub(2)..=grasp.segment + 2);
            }
            if jaw.slipped {
                // Slipped, until the jaws reopen: the thread found inside the jaws the moment it
                // slipped out would be thrown out at speed, so what is near their centre passes.
                // (Holding jaws do touch the rest of the thread: coils wound around them must slide
                // off over their tips.)
                let centre = jaw_centre_m(&jaw.world_from_tip);
                let clearance = HELD_CLEARANCE_M + self.thread.segment_length_m;
                for (i, h) in self.thread.segments.iter().enumerate() {
                    let t = physics.bodies[*h].translation();
                    if (to_na(t) - centre).norm() < clearance {
                        near.push(i);
                    }
                }
            }
            // Closing: what lies between the jaws does not push them apart; the grasp takes it
            // once they are closed.
            if jaw.closing && jaw.hold.and_then(super::Hold::joint_grasp).is_none() && !jaw.closed_empty {
                // What passes between the closing jaws (near their line), as the grasp will judge it.
                let (hinge, end) = crate::grasp::jaw_line_m(&jaw.world_from_tip, JAW_CENTRE_OFFSET_M);
                for (i, c) in self.thread.capsules(physics, 0.0).iter().enumerate() {
                    if knotlab_hw::geometry::segment_distance(&c.a_m, &c.b_m, &hinge, &end) < GRASP_REACH_M {
                        near.push(i);
                    }
                }
            }
            let held: Vec<ColliderHandle> = near.into_iter().flat_map(colliders_of).collect();
            filter.exclude_all(jaw.colliders, &held);
        }
        filter
    }

    /// After Rapier's step that ended at `time_s`: the watch judges the chain's move, the stitch's
    /// joints follow the thread.
    pub(super) fn after_step(
        &mut self,
        physics: &mut Physics,
        tissue: &Tissue,
        watch: &mut ThreadWatch,
        time_s: f64,
    ) {
        watch.update(physics, &self.thread, self.radius_m, time_s);
        let events = self.stitch.follow(physics, &self.thread, tissue, time_s);
        self.stitch_events.extend(events);
    }

    /// Unties the thread from the flaps.
    pub(super) fn unstitch(&mut self, physics: &mut Physics) {
        for hole in self.stitch.holes.iter_mut().chain(self.stitch.guides.iter_mut()) {
            if let Some(j) = hole.joint.take() {
                physics.impulse_joints.remove(j, true);
            }
            hole.segment = None;
        }
    }
}

/// Where the jaws hold, world frame, m.
fn jaw_centre_m(world_from_tip: &IsometryMatrix3<f64>) -> Vector3<f64> {
    (world_from_tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords
}
