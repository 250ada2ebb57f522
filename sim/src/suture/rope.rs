//! The rope as the scene's suture, as the jaws see it: what each pair of jaws lets through of it
//! (the run it holds or just let go of, what it closes on), its grip sliding and slipping, and its
//! pull on the instruments.

use std::ops::Range;

use nalgebra::Vector3;
use rapier3d::prelude::*;

use super::hold::{Hold, HoldKind};
use super::{HoldCheck, JawsNow};
use crate::grasp::{GRASP_REACH_M, JAW_CENTRE_OFFSET_M, JawFaces, jaw_line_m};
use crate::physics::Physics;
use crate::rope::grasp::RopeGrasp;
use crate::rope::suture::SceneRope;

/// The rope held by jaws passes through them this far either side of the held run, m.
pub const JAW_CLEAR_M: f64 = 0.008;

/// Jaws holding the rope let it go when pulled this many times harder than their grip (across
/// them: along the rope, it slides through them at the grip).
pub const SLIP_OUT_FACTOR: f64 = 3.0;

/// The rope and, for each pair of jaws, the run of it they let go of and still let through.
pub(super) struct RopeSuture {
    pub(super) rope: SceneRope,
    /// By arm: the particles the jaws last held (and what lay along them), let through until the
    /// jaws are open and clear of them.
    let_go: Vec<Option<Range<usize>>>,
}

impl RopeSuture {
    pub(super) fn new(rope: SceneRope, arms: usize) -> Self {
        Self { rope, let_go: vec![None; arms] }
    }

    /// [`JAW_CLEAR_M`] in particles.
    fn clear(&self) -> usize {
        (JAW_CLEAR_M / self.rope.spacing_m).ceil() as usize
    }

    fn count(&self) -> usize {
        self.rope.ropes.x.len()
    }

    /// Lets each instrument's jaws pass what they hold of the rope and what lies along them: the
    /// run they grasp, or the swaged end of the needle they hold, and [`JAW_CLEAR_M`] of rope
    /// either side (pushed out of the jaws while its neighbours are held in, it would be torn
    /// between the two). Closing jaws that hold nothing let what lies between them pass, as the
    /// chain's contact filter does: the grasp takes it once they are closed.
    pub(super) fn clear_jaws(&mut self, physics: &Physics, jaws: &[JawsNow], thread_radius_m: f64) {
        let clear = self.clear();
        let count = self.count();
        for (a, jaw) in jaws.iter().enumerate() {
            let Some(run) = self.let_go[a].clone() else { continue };
            if jaw.slipped || !jaw.open {
                continue;
            }
            // Opened: the run goes back to touching the jaws once it is clear of them.
            let touches = run.clone().any(|p| {
                jaw.colliders
                    .iter()
                    .filter_map(|c| Some((*c, physics.colliders.get(*c)?)))
                    .any(|(handle, c)| self.rope.touches(handle, c, p))
            });
            if !touches {
                self.let_go[a] = None;
            }
        }
        for (a, jaw) in jaws.iter().enumerate() {
            if jaw.colliders.is_empty() {
                continue;
            }
            // The run through the jaws: around the particle nearest their line, while within reach.
            let between = || {
                let line = jaw_line_m(&jaw.world_from_tip, JAW_CENTRE_OFFSET_M);
                let faces = jaw.radius_m.map(|r| JawFaces::of(&jaw.world_from_tip, r, thread_radius_m));
                RopeGrasp::run_between(&self.rope.ropes, line, GRASP_REACH_M, faces.as_ref())
                    .map_or(0..0, |run| run.start.saturating_sub(clear)..(run.end + clear).min(count))
            };
            let held = match jaw.hold.map(|h| &h.kind) {
                Some(HoldKind::Joint(grasp)) if grasp.on_needle => 0..clear.min(count),
                Some(HoldKind::Grip { grasp, .. }) => grasp.widened(clear, count),
                None if self.let_go[a].is_some() => self.let_go[a].clone().unwrap_or(0..0),
                None if jaw.closing && !jaw.closed_empty => between(),
                _ => 0..0,
            };
            for (collider, exempt) in &mut self.rope.contacts.colliders {
                if jaw.colliders.contains(collider) {
                    *exempt = held.clone();
                }
            }
        }
    }

    /// Grips the run of the rope between jaws on `clevis` whose tip stands at `world_from_tip`.
    pub(super) fn try_grip(
        &mut self,
        physics: &Physics,
        clevis: RigidBodyHandle,
        world_from_tip: &nalgebra::IsometryMatrix3<f64>,
        faces: Option<&JawFaces>,
        grip_force_n: f64,
    ) -> Option<Hold> {
        let clevis_pose = *physics.bodies[clevis].position();
        let line = jaw_line_m(world_from_tip, JAW_CENTRE_OFFSET_M);
        let (ropes, contacts) = (&self.rope.ropes, &mut self.rope.contacts);
        let grasp =
            RopeGrasp::try_close_between(ropes, contacts, clevis, &clevis_pose, line, GRASP_REACH_M, faces)?;
        grasp.grip(contacts, grip_force_n);
        Some(Hold::grip(grasp))
    }

    /// Lets go of what arm `a`'s jaws hold; what they held stays let through until they are clear
    /// of it (the swaged end of a needle they held only if `needle_out`).
    pub(super) fn release(&mut self, a: usize, hold: Hold, needle_out: bool) -> Option<crate::grasp::Grasp> {
        match hold.kind {
            HoldKind::Joint(grasp) => {
                if needle_out && grasp.on_needle {
                    self.let_go[a] = Some(0..self.clear().min(self.count()));
                }
                Some(grasp)
            }
            HoldKind::Grip { grasp, .. } => {
                self.let_go[a] = Some(grasp.widened(self.clear(), self.count()));
                grasp.release(&mut self.rope.contacts);
                None
            }
        }
    }

    /// Pulled along itself beyond the grip, the rope slides through the jaws (the solver holds
    /// the pull there), which hand the hold on as it goes, until none is left to come in; yanked
    /// far harder than the grip (across the jaws, say), it is torn out.
    pub(super) fn check_grip(
        &mut self,
        hold: &mut Hold,
        physics: &Physics,
        dt_s: f64,
        grip_force_n: f64,
    ) -> Option<HoldCheck> {
        let HoldKind::Grip { grasp, sliding: was_sliding } = &mut hold.kind else { return None };
        let rope = &mut self.rope;
        let force_n = grasp.force_n(&rope.contacts, dt_s).norm();
        let mut out = force_n > SLIP_OUT_FACTOR * grip_force_n;
        let pose = *physics.bodies[grasp.body].position();
        while !out {
            match grasp.follow_slide(&rope.ropes, &mut rope.contacts, &pose, rope.spacing_m) {
                Some(true) => {}
                Some(false) => out = true,
                None => break,
            }
        }
        let sliding = rope.contacts.grips.iter().any(|g| g.body == grasp.body && g.sliding);
        let started = sliding && !std::mem::replace(was_sliding, sliding);
        Some(if out {
            HoldCheck::SlippedOut { force_n }
        } else if started {
            HoldCheck::Slid { force_n }
        } else {
            HoldCheck::Held
        })
    }

    /// Adds the rope's pull on an instrument's `bodies` over the last step of `dt_s` to `total_n`:
    /// its contacts and its grip, and its pull on the needle the jaws hold, which reaches them
    /// through the needle (applied to the needle before Rapier's step, the joint takes it up in
    /// its first substeps and its last one, all the joint's impulse reads, shows none of it).
    pub(super) fn add_pull(
        &self,
        total_n: &mut Vector3<f64>,
        hold: Option<&Hold>,
        bodies: &[RigidBodyHandle],
        dt_s: f64,
    ) {
        for h in bodies {
            *total_n += self.rope.contacts.impulse_on(*h) / dt_s;
        }
        if hold.is_some_and(Hold::on_needle) {
            *total_n += self.rope.contacts.impulse_on(self.rope.needle_body) / dt_s;
        }
    }
}
