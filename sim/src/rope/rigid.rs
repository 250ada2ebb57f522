//! The rope among Rapier's rigid bodies: each substep, every particle near a collider is pushed out
//! of it to the rope's radius (at metal [`super::RopeParams::radius_at_metal_m`]), with Coulomb
//! friction against the collider's own motion over the substep (the rope's contact rule,
//! `super::contact`, against a solid), and particles attached to
//! a body follow it. On an elastic rope (a finite axial stiffness) they are put where the body
//! holds them (the jaws' grasp, the needle's swage) before the rope's lengths are solved, which
//! then move only the rest of the rope: the pull on the body is what that solve would have moved
//! its particles by (moved and put back instead, the lengths next to them were left stretched by
//! the pull, and by twice their rest under a hard one). On an inextensible rope, which has no
//! solution drawn taut between two such holds, they are solved with the rope and put on the body
//! afterwards. The bodies move as Rapier will move them in the
//! step (a kinematic body from its pose to its next one, a dynamic body on its velocities), and
//! what the rope does to each body is summed as an impulse: applied to the dynamic ones before
//! their step ([`RigidContacts::apply_impulses`]), read as the instruments' gauges would on the
//! kinematic ones.

use std::ops::Range;

use nalgebra::Vector3;
use rapier3d::math::{Pose, Rotation};
use rapier3d::prelude::*;

use super::{Ropes, Surroundings};
use crate::convert::{to_na, to_rapier};

/// Particles boxed together when the colliders' candidates are sought.
const PARTICLES_PER_BOX: usize = 16;

/// A particle held at a point fixed in a body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attachment {
    /// The rope's particle.
    pub particle: usize,
    /// The body.
    pub body: RigidBodyHandle,
    /// The point in the body's frame, m.
    pub local_m: Vector3<f64>,
}

/// The attachments of one body that hold a run of the rope by friction, as jaws squeezing a suture
/// do: pulled along the rope harder than `limit_n`, the run slides through them (each substep the
/// attachments' points give way along the rope by as much as holds the pull to the limit), and
/// they go on holding it ([`crate::rope::grasp::RopeGrasp::follow_slide`] hands the hold on to
/// the next particles as it goes).
#[derive(Clone, Debug, PartialEq)]
pub struct Grip {
    /// The body: the grip is its attachments (a body holds one run of the rope at a time).
    pub body: RigidBodyHandle,
    /// The most it holds the rope with along itself, N.
    pub limit_n: f64,
    /// How far the run has slid through it since its particles were last handed on, in the body's
    /// frame, m.
    pub slid_local_m: Vector3<f64>,
    /// Whether it slid in the last step.
    pub sliding: bool,
}

/// A point fixed in a body that the rope passes through, free to slide along itself (a stitch's
/// hole through a flap): each substep the rope's point there is moved onto it across the rope, not
/// along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Guide {
    /// The body.
    pub body: RigidBodyHandle,
    /// The point in the body's frame, m.
    pub local_m: Vector3<f64>,
    /// Where the rope passes it: a particle's index plus the fraction of the way to the next.
    pub at: f64,
}

impl Guide {
    /// A guide at `point_m` (world), fixed in `body` (at `body_pose`), on the rope of `strand` where
    /// it passes nearest the point.
    pub fn threaded(
        ropes: &Ropes,
        strand: Range<usize>,
        body: RigidBodyHandle,
        body_pose: &Pose,
        point_m: &Vector3<f64>,
    ) -> Self {
        let last = strand.end.saturating_sub(1);
        let nearest = strand
            .clone()
            .min_by(|a, b| (ropes.x[*a] - point_m).norm().total_cmp(&(ropes.x[*b] - point_m).norm()))
            .unwrap_or(strand.start);
        Self {
            body,
            local_m: to_na(body_pose.inverse_transform_point(to_rapier(point_m))),
            at: nearest_on_rope(ropes, point_m, nearest, last),
        }
    }
}

/// What the rope touches among the rigid bodies, and what it did to them.
#[derive(Clone, Debug, Default)]
pub struct RigidContacts {
    /// The colliders the rope collides with, each with particles it lets through (the thread in
    /// a flap's stitch, say; an empty range for none).
    pub colliders: Vec<(ColliderHandle, Range<usize>)>,
    /// The colliders that push the rope at its collision radius, not at its radius at metal
    /// ([`super::RopeParams::radius_at_metal_m`]): the tissue's, rigid boxes standing in for flesh
    /// a real suture presses into, on which the knot rests at the section its crossings are
    /// resolved at.
    pub at_collision_radius: Vec<ColliderHandle>,
    /// The rope's friction coefficient, combined with each collider's as Rapier combines two
    /// colliders' (their average, unless the collider asks otherwise), as the chain's segments are.
    pub friction: f64,
    /// The particles held by bodies.
    pub attachments: Vec<Attachment>,
    /// The impulse each attachment gave its particle over the last step, N s (as `attachments`).
    pub attachment_impulses: Vec<Vector3<f64>>,
    /// Attachments that hold by friction (jaws on the suture); the rest hold whatever pulls.
    pub grips: Vec<Grip>,
    /// The points the rope slides through, in order along it.
    pub guides: Vec<Guide>,
    /// The impulse the rope gave each body over the last step, N s, and its moment about the body's
    /// centre of mass, N m s (world frame), in the order the rope first touched them.
    pub impulses: Vec<(RigidBodyHandle, Vector3<f64>, Vector3<f64>)>,
    /// Collider-particle pairs in contact in the last substep.
    pub contacts_last: usize,
}

/// Where `body` will be after `dt_s` as Rapier steps it: a kinematic body at its next pose, a
/// dynamic one moved by its velocities, a fixed one where it is.
fn pose_after(body: &RigidBody, dt_s: f64) -> Pose {
    if body.is_kinematic() {
        *body.next_position()
    } else if body.is_dynamic() {
        let now = body.position();
        let turn = Rotation::from_scaled_axis(body.angvel() * dt_s);
        // About the centre of mass: it moves with the linear velocity, the body turns about it.
        let com = body.center_of_mass();
        let com_after = com + body.linvel() * dt_s;
        let rotation = (turn * now.rotation).normalize();
        let translation = com_after + turn * (now.translation - com);
        Pose::from_parts(translation, rotation)
    } else {
        *body.position()
    }
}

impl RigidContacts {
    /// Clears the impulses summed over the last step.
    pub fn clear_impulses(&mut self) {
        self.impulses.clear();
        self.attachment_impulses = vec![Vector3::zeros(); self.attachments.len()];
        for grip in &mut self.grips {
            grip.sliding = false;
        }
    }

    /// Removes the attachments `which` picks, with their impulses.
    pub fn detach(&mut self, which: impl Fn(&Attachment) -> bool) {
        let keep: Vec<bool> = self.attachments.iter().map(|a| !which(a)).collect();
        let mut k = 0;
        self.attachments.retain(|_| {
            k += 1;
            keep[k - 1]
        });
        let mut k = 0;
        self.attachment_impulses.retain(|_| {
            k += 1;
            keep.get(k - 1).copied().unwrap_or(false)
        });
    }

    /// The particles between the first guide and the last (the thread in the stitch), if any.
    pub fn between_guides(&self) -> Range<usize> {
        match (self.guides.first(), self.guides.last()) {
            (Some(first), Some(last)) => (first.at.floor() as usize)..(last.at.ceil() as usize + 1),
            _ => 0..0,
        }
    }

    /// The impulse the rope gave `body` over the last step, N s.
    pub fn impulse_on(&self, body: RigidBodyHandle) -> Vector3<f64> {
        self.impulses.iter().find(|(h, _, _)| *h == body).map_or(Vector3::zeros(), |(_, i, _)| *i)
    }

    /// Applies the summed impulses to the dynamic bodies (call between the rope's step and Rapier's).
    pub fn apply_impulses(&self, bodies: &mut RigidBodySet) {
        for (handle, impulse, moment) in &self.impulses {
            if let Some(body) = bodies.get_mut(*handle)
                && body.is_dynamic()
            {
                body.apply_impulse(to_rapier(impulse), true);
                body.apply_torque_impulse(to_rapier(moment), true);
            }
        }
    }

    /// Steps `ropes` by `dt_s` among `bodies` and `colliders` as they stand before Rapier's step
    /// (kinematic bodies with their next poses set), summing the impulses anew.
    pub fn step(&mut self, ropes: &mut Ropes, dt_s: f64, bodies: &RigidBodySet, colliders: &ColliderSet) {
        self.step_with(ropes, dt_s, bodies, colliders, &mut ());
    }

    /// [`Self::step`] with `more` surroundings resolved after the bodies each substep.
    pub fn step_with(
        &mut self,
        ropes: &mut Ropes,
        dt_s: f64,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        more: &mut dyn Surroundings,
    ) {
        self.clear_impulses();
        let substeps = ropes.params.substeps.max(1);
        let candidates = self.candidates(ropes, dt_s, bodies, colliders);
        let mut among = Among {
            contacts: self,
            bodies,
            colliders,
            dt_s,
            substeps,
            substep: 0,
            more,
            candidates,
            pushed: Vec::new(),
            poses: Vec::new(),
            slipping: Vec::new(),
            slid_by_friction_m: Vec::new(),
        };
        ropes.step_in(dt_s, &mut among);
    }

    /// For each collider (as `colliders`), the particles that may touch it during the step: those
    /// within the rope's radius and contact margin of the box it sweeps through the step, but for
    /// those held by an attachment. A held particle is where the body holding it puts it; a collider
    /// pushing it meanwhile only made the two fight, micrometres costing newtons (jaws drifting 2 µm
    /// a step onto a tail lying on a flap read 0.5 to 6 N in four steps and slipped).
    fn candidates(
        &self,
        ropes: &Ropes,
        dt_s: f64,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<Vec<usize>> {
        let reach =
            ropes.params.radius_m.max(ropes.params.radius_at_metal_m()) + ropes.params.contact_margin_m;
        let mut held = vec![false; ropes.x.len()];
        for a in &self.attachments {
            if let Some(h) = held.get_mut(a.particle) {
                *h = true;
            }
        }
        // The box round each run of particles, so that a collider's box is tested against the
        // particles only where it meets theirs.
        let runs: Vec<(Range<usize>, Aabb)> = (0..ropes.x.len())
            .step_by(PARTICLES_PER_BOX)
            .map(|start| {
                let run = start..(start + PARTICLES_PER_BOX).min(ropes.x.len());
                let points = &ropes.x[run.clone()];
                let (lo, hi) =
                    points.iter().fold((points[0], points[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
                (run, Aabb::new(to_rapier(&lo), to_rapier(&hi)))
            })
            .collect();
        self.colliders
            .iter()
            .map(|(handle, _)| {
                let Some(collider) = colliders.get(*handle) else { return Vec::new() };
                let Some(body) = collider.parent().and_then(|b| bodies.get(b)) else { return Vec::new() };
                let local = collider.position_wrt_parent().copied().unwrap_or_default();
                let (start, end) = (body.position() * local, pose_after(body, dt_s) * local);
                let aabb = collider.shape().compute_swept_aabb(&start, &end).loosened(reach);
                runs.iter()
                    .filter(|(_, run_box)| aabb.intersects(run_box))
                    .flat_map(|(run, _)| run.clone())
                    .filter(|p| !held[*p] && aabb.contains_local_point(to_rapier(&ropes.x[*p])))
                    .collect()
            })
            .collect()
    }
}

/// The bodies as the rope's [`Surroundings`] through one step.
struct Among<'a> {
    contacts: &'a mut RigidContacts,
    bodies: &'a RigidBodySet,
    colliders: &'a ColliderSet,
    dt_s: f64,
    substeps: usize,
    substep: usize,
    more: &'a mut dyn Surroundings,
    /// The particles that may touch each collider this step ([`RigidContacts::candidates`]).
    candidates: Vec<Vec<usize>>,
    /// The bodies' pushes on the rope in this substep's contacts, in the order made.
    pushed: Vec<Push>,
    /// The poses of the bodies asked for so far this step.
    poses: Vec<BodyPoses>,
    /// The grips found slipping in this substep ([`Surroundings::slipping`]), each with the
    /// sign of its pull along the rope (its [`Among::grip_run`]'s direction).
    slipping: Vec<(usize, f64)>,
    /// Each attachment of a slipping grip and how far the grip's friction moved its particle
    /// along the rope in this substep ([`Surroundings::start_slipping`]), m.
    slid_by_friction_m: Vec<(usize, Vector3<f64>)>,
}

/// How far a body the surroundings move ([`Surroundings::pose_of`]) may go from where its collider
/// was boxed in a substep, m: the box is not taken again for each contact.
const MOVED_HERE_REACH_M: f64 = 0.0005;

/// A body's poses through the step: where it starts and ends, and the last two asked for between
/// (each substep asks for its end, which is the next one's start).
struct BodyPoses {
    body: RigidBodyHandle,
    start: Pose,
    end: Pose,
    /// Fractions of the step and the poses there, the latest first.
    at: [(f64, Pose); 2],
}

impl Among<'_> {
    /// The pose of `body` a fraction `f` of the way through the step: where the surroundings that
    /// move it within the step have it now ([`Surroundings::pose_of`]), else between where Rapier
    /// has it and where it will have it.
    fn body_pose(&mut self, body: RigidBodyHandle, f: f64) -> Option<Pose> {
        if let Some(pose) = self.more.pose_of(body) {
            return Some(pose);
        }
        let k = match self.poses.iter().position(|p| p.body == body) {
            Some(k) => k,
            None => {
                let b = self.bodies.get(body)?;
                let (start, end) = (*b.position(), pose_after(b, self.dt_s));
                self.poses.push(BodyPoses { body, start, end, at: [(f64::NAN, start); 2] });
                self.poses.len() - 1
            }
        };
        let poses = &mut self.poses[k];
        if let Some((_, pose)) = poses.at.iter().find(|(g, _)| g.to_bits() == f.to_bits()) {
            return Some(*pose);
        }
        let pose = poses.start.lerp(&poses.end, f);
        poses.at = [(f, pose), poses.at[0]];
        Some(pose)
    }

    /// The grip's run of the rope at fraction `f` of the step: its attachments, the rope's way
    /// through it, its mass, and how far the attachments would move the run along the rope,
    /// mass-weighted (kg m: over a substep `h`, an impulse of that over `h`), from where the rope
    /// would have taken it ([`Ropes::unheld_m`]).
    fn grip_run(
        &mut self,
        ropes: &Ropes,
        grip: &Grip,
        f: f64,
    ) -> Option<(Vec<usize>, Vector3<f64>, f64, f64)> {
        let pose = self.body_pose(grip.body, f)?;
        let held: Vec<usize> = (0..self.contacts.attachments.len())
            .filter(|&k| {
                let a = &self.contacts.attachments[k];
                a.body == grip.body && ropes.w[a.particle] > 0.0
            })
            .collect();
        let particles = held.iter().map(|&k| self.contacts.attachments[k].particle);
        let (first, last) = (particles.clone().min()?, particles.max()?);
        let t = ropes.way_through(&(first..last + 1))?;
        let (mut along, mut mass) = (0.0, 0.0);
        for &k in &held {
            let a = self.contacts.attachments[k];
            let m = 1.0 / ropes.w[a.particle];
            let target = to_na(pose.transform_point(to_rapier(&a.local_m)));
            along += m * t.dot(&(target - ropes.unheld_m(a.particle)));
            mass += m;
        }
        (mass > 0.0).then_some((held, t, mass, along))
    }

    /// [`Self::grip_run`]'s pull along the rope, kg m.
    fn pull_along_grip(&mut self, ropes: &Ropes, grip: &Grip, f: f64) -> Option<f64> {
        self.grip_run(ropes, grip, f).map(|(_, _, _, along)| along)
    }

    /// Each grip's attachment points give way along the rope where holding them would pull it
    /// harder than the grip's limit over this substep of `h_s` (the body at fraction `f` of the step).
    fn give_way_in_grips(&mut self, ropes: &Ropes, h_s: f64, f: f64) {
        for g in 0..self.contacts.grips.len() {
            let grip = self.contacts.grips[g].clone();
            let Some(pose) = self.body_pose(grip.body, f) else { continue };
            let Some((held, t, mass, along)) = self.grip_run(ropes, &grip, f) else { continue };
            // A grip whose friction was solved with the rope ([`Surroundings::start_slipping`])
            // holds each particle of its run where that left it along the rope; any other gives
            // way with its run as one, until the rest of the pull is its limit.
            let slipped = self.slipping.iter().any(|(s, _)| *s == g);
            let most = if slipped { 0.0 } else { grip.limit_n * h_s * h_s };
            if along.abs() <= most {
                continue;
            }
            let give = t * ((along - along.signum() * most) / mass);
            for &k in &held {
                let a = self.contacts.attachments[k];
                let at = to_na(pose.transform_point(to_rapier(&a.local_m)));
                let to = if slipped { at - t * t.dot(&(at - ropes.unheld_m(a.particle))) } else { at - give };
                self.contacts.attachments[k].local_m = to_na(pose.inverse_transform_point(to_rapier(&to)));
            }
            let origin = to_na(pose.inverse_transform_point(to_rapier(&Vector3::zeros())));
            let given = to_na(pose.inverse_transform_point(to_rapier(&-give))) - origin;
            let grip = &mut self.contacts.grips[g];
            grip.slid_local_m += given;
            grip.sliding = true;
        }
    }

    fn push(&mut self, body: RigidBodyHandle, impulse: Vector3<f64>, at: Vector3<f64>, f: f64) {
        let com = self
            .bodies
            .get(body)
            .map(|b| to_na(b.center_of_mass() + b.linvel() * (self.dt_s * f)))
            .unwrap_or(at);
        let impulses = &mut self.contacts.impulses;
        let k = match impulses.iter().position(|(h, _, _)| *h == body) {
            Some(k) => k,
            None => {
                impulses.push((body, Vector3::zeros(), Vector3::zeros()));
                impulses.len() - 1
            }
        };
        impulses[k].1 += impulse;
        impulses[k].2 += (at - com).cross(&impulse);
        self.more.pushed(body, impulse, self.dt_s / self.substeps as f64);
    }

    /// A particle pushed by one body into another that pushes it back (a seam narrower than the
    /// thread between two bodies that go where they go) is pinched between them: put on the seam,
    /// midway through the last push, moved across the seam only, along it left where the rope
    /// carried it; the two bodies share the push. Pushed to and fro by the two every substep
    /// instead, the segments leaving the seam stood stretched (at 0.15 kg/m and 24 substeps by a
    /// fifth). Bodies that move with the rope's contacts (the wound's flaps on their slides) are
    /// left to their pushes, which move them apart.
    fn pinch(&mut self, ropes: &mut Ropes, h_s: f64, f1: f64) {
        let pushed = std::mem::take(&mut self.pushed);
        // Each particle's pushes in the order made, the particles in the order of their last push.
        let mut order: Vec<usize> = (0..pushed.len()).collect();
        order.sort_unstable_by_key(|&i| (pushed[i].particle, i));
        let mut groups: Vec<&[usize]> = order
            .chunk_by(|a, b| pushed[*a].particle == pushed[*b].particle)
            .filter(|g| g.len() > 1)
            .collect();
        groups.sort_unstable_by_key(|g| g[g.len() - 1]);
        for group in groups {
            let (before, last) = group.split_at(group.len() - 1);
            let last = pushed[last[0]];
            let p = last.particle;
            let Some(first) = before
                .iter()
                .map(|&i| pushed[i])
                .find(|q| q.body != last.body && q.normal.dot(&last.normal) < -0.5)
            else {
                continue;
            };
            // Bodies that move with the rope's contacts were pushed apart by them.
            if self.more.pose_of(first.body).is_some() || self.more.pose_of(last.body).is_some() {
                continue;
            }
            let start_m = pushed[group[0]].from_m;
            let middle_m = last.from_m + last.dx_m * 0.5;
            let target_m = start_m + last.normal * (middle_m - start_m).dot(&last.normal);
            ropes.x[p] = target_m;
            if ropes.w[p] > 0.0 {
                // Each push's impulse taken back, the particle's whole move shared by the two.
                for &i in group {
                    let q = pushed[i];
                    self.push(q.body, q.dx_m / (ropes.w[p] * h_s), q.from_m, f1);
                }
                let impulse = -(target_m - start_m) / (ropes.w[p] * h_s);
                self.push(first.body, impulse * 0.5, target_m, f1);
                self.push(last.body, impulse * 0.5, target_m, f1);
            }
        }
        self.pushed = pushed;
        self.pushed.clear();
    }
}

impl Surroundings for Among<'_> {
    fn hold(&mut self, ropes: &mut Ropes, held: &mut [bool], h_s: f64) {
        let f1 = (self.substep + 1) as f64 / self.substeps as f64;
        // Held exactly only where the rope can give: an inextensible rope drawn taut between two
        // such holds has no solution (its projection threw particles metres), so it is held
        // softly, its held particles solved with the rest and put on their bodies afterwards.
        if ropes.params.axial_stiffness_n.is_finite() {
            for k in 0..self.contacts.attachments.len() {
                let a = self.contacts.attachments[k];
                let Some(pose) = self.body_pose(a.body, f1) else { continue };
                if let (Some(x), Some(h)) = (ropes.x.get_mut(a.particle), held.get_mut(a.particle)) {
                    *x = to_na(pose.transform_point(to_rapier(&a.local_m)));
                    *h = true;
                }
            }
        }
        // The rope through its guides, before its lengths are solved (after them, the guides'
        // moves across it were left as stretch).
        for k in 0..self.contacts.guides.len() {
            let guide = self.contacts.guides[k];
            let Some(pose) = self.body_pose(guide.body, f1) else { continue };
            let target = to_na(pose.transform_point(to_rapier(&guide.local_m)));
            if let Some((dx_at, at)) = thread_through(ropes, guide.at, &target) {
                for (p, dx) in dx_at {
                    if ropes.w[p] > 0.0 {
                        self.push(guide.body, -dx / (ropes.w[p] * h_s), target, f1);
                    }
                }
                self.contacts.guides[k].at = at;
            }
        }
        self.more.hold(ropes, held, h_s);
    }

    fn slipping(&mut self, ropes: &Ropes, held: &mut [bool], h_s: f64) -> bool {
        let f1 = (self.substep + 1) as f64 / self.substeps as f64;
        let mut any = false;
        self.slipping.clear();
        self.slid_by_friction_m.clear();
        for g in 0..self.contacts.grips.len() {
            let grip = self.contacts.grips[g].clone();
            let Some(along) = self.pull_along_grip(ropes, &grip, f1) else { continue };
            if along.abs() > grip.limit_n * h_s * h_s {
                let mut let_go = false;
                for a in self.contacts.attachments.iter().filter(|a| a.body == grip.body) {
                    if let Some(h) = held.get_mut(a.particle) {
                        let_go |= *h;
                        *h = false;
                    }
                }
                if let_go {
                    self.slipping.push((g, along.signum()));
                }
                any |= let_go;
            }
        }
        any
    }

    fn start_slipping(&mut self, ropes: &mut Ropes, h_s: f64) {
        let f1 = (self.substep + 1) as f64 / self.substeps as f64;
        self.slid_by_friction_m.clear();
        for i in 0..self.slipping.len() {
            let (g, pull_sign) = self.slipping[i];
            let grip = self.contacts.grips[g].clone();
            let Some(pose) = self.body_pose(grip.body, f1) else { continue };
            let Some((held, t, mass, _)) = self.grip_run(ropes, &grip, f1) else { continue };
            // The grip's friction, at its limit, over the substep moves the run along the rope
            // by its force times h² over the run's mass, the way the jaws pull it: each particle
            // from where the rope's motion carries it, by that along the rope, onto the jaws
            // across it.
            let slid = t * (pull_sign * grip.limit_n * h_s * h_s / mass);
            for &k in &held {
                let a = self.contacts.attachments[k];
                let target = to_na(pose.transform_point(to_rapier(&a.local_m)));
                let carried = ropes.x_free[a.particle];
                let miss = target - carried;
                ropes.x[a.particle] = carried + (miss - t * miss.dot(&t)) + slid;
                self.slid_by_friction_m.push((k, slid));
            }
        }
    }

    fn pushed_the_rope(&self) -> bool {
        self.contacts.contacts_last > 0 || self.more.pushed_the_rope()
    }

    fn after(&mut self, ropes: &mut Ropes, x_prev: &[Vector3<f64>], h_s: f64) {
        let (f0, f1) =
            (self.substep as f64 / self.substeps as f64, (self.substep + 1) as f64 / self.substeps as f64);
        self.substep += 1;
        let r_metal = ropes.params.radius_at_metal_m();
        let friction = self.contacts.friction;
        let mut touching = 0;
        let colliders = std::mem::take(&mut self.contacts.colliders);
        for (k, (handle, exempt)) in colliders.iter().enumerate() {
            if self.candidates[k].is_empty() {
                continue;
            }
            let Some(collider) = self.colliders.get(*handle) else { continue };
            let Some(body) = collider.parent() else { continue };
            let r = if self.contacts.at_collision_radius.contains(handle) {
                ropes.params.radius_m
            } else {
                r_metal
            };
            let local = collider.position_wrt_parent().copied().unwrap_or_default();
            let (Some(body_then), Some(body_now)) = (self.body_pose(body, f0), self.body_pose(body, f1))
            else {
                continue;
            };
            let (then, now) = (body_then * local, body_now * local);
            let friction = CoefficientCombineRule::combine(
                friction,
                collider.friction(),
                CoefficientCombineRule::default(),
                collider.friction_combine_rule(),
            );
            let (mut then, mut now) = (then, now);
            let moved_here = self.more.pose_of(body).is_some();
            let reach_m = if moved_here { r + MOVED_HERE_REACH_M } else { r };
            let aabb = collider.shape().compute_aabb(&now).loosened(reach_m);
            let candidates = std::mem::take(&mut self.candidates[k]);
            for &p in &candidates {
                let x_before = x_prev[p];
                if ropes.w[p] == 0.0 || exempt.contains(&p) {
                    continue;
                }
                if moved_here && let Some(pose) = self.more.pose_of(body) {
                    // Where the last contact left it.
                    now = pose * local;
                    then = now;
                }
                let x = ropes.x[p];
                if !aabb.contains_local_point(to_rapier(&x)) {
                    continue;
                }
                let projection = collider.shape().project_point(&now, to_rapier(&x), false);
                let to_surface = to_na(projection.point) - x;
                let distance = to_surface.norm();
                let (normal, depth) = if projection.is_inside {
                    if distance < 1e-12 {
                        continue;
                    }
                    (to_surface / distance, distance + r)
                } else if distance < r && distance > 1e-12 {
                    (-to_surface / distance, r - distance)
                } else {
                    continue;
                };
                touching += 1;
                let mut dx = normal * depth;
                // The surface under the particle moved this much over the substep.
                let surface_moved =
                    to_na(now.transform_point(then.inverse_transform_point(to_rapier(&x)))) - x;
                let moved = (x + dx - x_before) - surface_moved;
                let tangential = moved - normal * moved.dot(&normal);
                let slip = tangential.norm();
                if slip > 0.0 {
                    dx -= tangential * (friction * depth / slip).min(1.0);
                }
                // A body that moves with the rope's contacts shares the move by the masses.
                let w_body = self.more.inverse_mass_along(body, &normal);
                dx *= ropes.w[p] / (ropes.w[p] + w_body);
                ropes.x[p] += dx;
                let impulse = -dx / (ropes.w[p] * h_s);
                self.push(body, impulse, x, f1);
                self.pushed.push(Push { particle: p, body, normal, from_m: x, dx_m: dx });
            }
            self.candidates[k] = candidates;
        }
        self.contacts.colliders = colliders;
        self.contacts.contacts_last = touching;
        self.pinch(ropes, h_s, f1);
        self.give_way_in_grips(ropes, h_s, f1);
        for k in 0..self.contacts.attachments.len() {
            let a = self.contacts.attachments[k];
            let Some(pose) = self.body_pose(a.body, f1) else { continue };
            let target = to_na(pose.transform_point(to_rapier(&a.local_m)));
            // The body's pull on its particle: from where the rope would have taken it (and, in
            // a slipping grip, its friction's move solved with the rope).
            let mut dx = target - ropes.unheld_m(a.particle);
            if let Some((_, slid)) = self.slid_by_friction_m.iter().find(|(j, _)| *j == k) {
                dx += slid;
            }
            ropes.x[a.particle] = target;
            if ropes.w[a.particle] > 0.0 {
                let impulse = -dx / (ropes.w[a.particle] * h_s);
                self.push(a.body, impulse, target, f1);
                if let Some(held) = self.contacts.attachment_impulses.get_mut(k) {
                    *held -= impulse;
                }
            }
        }
        self.more.after(ropes, x_prev, h_s);
    }
}

/// A body's push on a particle out of one of its colliders.
#[derive(Clone, Copy, Debug)]
struct Push {
    particle: usize,
    body: RigidBodyHandle,
    /// Out of the collider, world frame.
    normal: Vector3<f64>,
    /// Where the particle was before the push, m.
    from_m: Vector3<f64>,
    /// The push (with its friction), m.
    dx_m: Vector3<f64>,
}

/// Two particles and how far each was moved, m.
pub(super) type ParticleMoves = [(usize, Vector3<f64>); 2];

/// Moves the rope's point at `at` (a particle's index plus a fraction) onto `target` across the
/// rope, its two particles sharing the move by their masses; returns each particle's move and where
/// the rope now passes nearest `target` (searched two segments either way).
pub fn thread_through(ropes: &mut Ropes, at: f64, target: &Vector3<f64>) -> Option<(ParticleMoves, f64)> {
    thread_through_held(ropes, at, target, 0.0, 1.0)
}

/// As [`thread_through`], but the rope's point at `at` is also held along the rope by friction up
/// to `friction_n` (this substep `h_s` long): moved onto `target` along the rope as well while that
/// takes no more force, so that the rope does not slide and stays at `at`; past it, moved by as much
/// as that force does, and the rope slides (where it now passes is searched as in
/// [`thread_through`]).
pub(super) fn thread_through_held(
    ropes: &mut Ropes,
    at: f64,
    target: &Vector3<f64>,
    friction_n: f64,
    h_s: f64,
) -> Option<(ParticleMoves, f64)> {
    let last = ropes.x.len().checked_sub(1).filter(|l| *l >= 1)?;
    let sigma = at.clamp(0.0, (last - 1) as f64 + 0.999_999);
    let i = sigma.floor() as usize;
    let t = sigma - i as f64;
    let (a, b) = (i, i + 1);
    let along = (ropes.x[b] - ropes.x[a]).try_normalize(1e-15)?;
    let here = ropes.x[a] * (1.0 - t) + ropes.x[b] * t;
    let miss = target - here;
    let along_miss_m = miss.dot(&along);
    let across = miss - along * along_miss_m;
    let weights = [(a, 1.0 - t), (b, t)];
    let wsum: f64 = weights.iter().map(|(p, f)| ropes.w[*p] * f * f).sum();
    // The most the friction moves the point along the rope (its force times h² over the point's
    // inverse mass): it holds if that is enough.
    let grip_m = friction_n * wsum * h_s * h_s;
    let held = along_miss_m.abs() <= grip_m;
    let drag = along * along_miss_m.clamp(-grip_m, grip_m);
    let mut moves = [(a, Vector3::zeros()), (b, Vector3::zeros())];
    if wsum > 0.0 {
        for (k, (p, f)) in weights.into_iter().enumerate() {
            let dx = (across + drag) * (ropes.w[p] * f / wsum);
            ropes.x[p] += dx;
            moves[k] = (p, dx);
        }
    }
    let now_at = if held && friction_n > 0.0 { sigma } else { nearest_on_rope(ropes, target, i, last) };
    Some((moves, now_at))
}

/// The place on the rope (particle index plus fraction) nearest `target`, searched over the
/// segments within two of segment `near`.
pub fn nearest_on_rope(ropes: &Ropes, target: &Vector3<f64>, near: usize, last: usize) -> f64 {
    let mut best = (f64::INFINITY, near as f64);
    for i in near.saturating_sub(2)..(near + 3).min(last) {
        let (a, b) = (ropes.x[i], ropes.x[i + 1]);
        let d = b - a;
        let t = ((target - a).dot(&d) / d.norm_squared().max(1e-18)).clamp(0.0, 1.0);
        let distance = (a + d * t - target).norm();
        if distance < best.0 {
            best = (distance, i as f64 + t);
        }
    }
    best.1
}
