//! The rope as the scene's suture (`thread.model = "rope"`): one strand laid along the start
//! layout, the needle a Rapier body of its own with the strand's first particle swaged to it, the
//! thread sliding through the stitch's four points in the flaps, the flaps' slides solved with the
//! rope ([`super::slides`]), and the rope touching the instruments, the flaps and the pad through
//! [`super::rigid`]'s contacts. Each scene step the rope steps first (the instruments at their next
//! poses), then what it did to the needle is applied, the flaps are posed where their slides went,
//! and Rapier steps. (The instruments and the needle do not push the flaps: only the thread and the
//! loads of the holding test move them.)

use nalgebra::Vector3;
use rapier3d::math::{Pose, Rotation, Vector};
use rapier3d::prelude::*;

use super::rigid::{Attachment, RigidContacts};
use super::slides::SlideStitch;
use super::{RopeParams, Ropes};
use crate::convert::{to_na, to_rapier};
use crate::groups::{FLAP_GROUP, PAD_GROUP, THREAD_GROUP};
use crate::needle::Needle;
use crate::physics::Physics;
use crate::scene::{NeedleParams, TissueParams};
use crate::thread::ThreadParams;
use crate::tissue::{Flap, Tissue};

/// The rope's particles lie about this many radii apart unless the scene says otherwise
/// (`thread.rope_spacing_radii`): as near it as whole segments fit the thread's length.
pub const SPACING_RADII: f64 = 1.5;

/// The suture as a rope in the scene.
pub struct SceneRope {
    /// The rope (one strand, needle end first).
    pub ropes: Ropes,
    /// What it touches, the stitch it runs through, what holds it.
    pub contacts: RigidContacts,
    /// Its particles' spacing, m.
    pub spacing_m: f64,
    /// The needle's body.
    pub needle_body: RigidBodyHandle,
    /// The colliders the thread in the stitch passes through (the flaps and the pad).
    tissue_colliders: Vec<ColliderHandle>,
    /// The stitch, with the flaps' slides solved in the rope's substeps (`None` once the thread is
    /// taken out of it: [`Self::unstitch`]).
    pub stitch: Option<SlideStitch>,
    /// Whether the needle rides on the rope (no jaws hold it): then it is kinematic, posed on the
    /// rope's first segment after each of the rope's steps, its weight on the first particle.
    /// (Dynamic and pulled by the rope's reaction alone, the 1 g needle and the rope's tension fed
    /// each other step after step: released, it flew off at 100 m/s.)
    pub needle_free: bool,
    /// The needle's weight, N.
    needle_weight_n: f64,
}

/// Segment pairs within this many of the rope's radii beyond touching are watched for contact
/// ([`RopeParams::contact_margin_m`]): 1 mm at the nominal 0.4 mm radius, and as many particle
/// spacings at any other radius (a fixed millimetre round a 0.11 mm rope watched three times the
/// pairs, and a trial took 16 times as long).
pub const CONTACT_MARGIN_RADII: f64 = 2.5;

/// How far beyond the rope's radius a collider still counts as touching it, m.
const TOUCH_SLOP_M: f64 = 1e-4;

/// The rope's material from the scene's thread: its radius and friction on itself (kinetic 0.8 of
/// the static), its bending stiffness the chain's per joint times a segment's length (the nominal
/// scene's 2e-5 N m/rad over 2.5 mm: 5.0e-8 N m²), its damping the chain's, two contact passes a
/// substep, its substeps the scene's `thread.rope_substeps` (20 if left out), its inertial mass the
/// scene's `thread.rope_inertial_mass_kg_per_m` (0.67 kg/m if left out), its bending solved a
/// strand at once if `thread.rope_direct_bending`, its lengths and joints passed over
/// `thread.rope_constraint_passes` times a substep (once if left out), its contacts solved from
/// either end in turn if `thread.rope_contacts_both_ways`, its contact margin [`CONTACT_MARGIN_RADII`] radii.
pub fn rope_params(thread: &ThreadParams) -> RopeParams {
    let friction = thread.friction_on_itself.unwrap_or(thread.friction);
    RopeParams {
        radius_m: thread.radius_m,
        metal_radius_m: thread.rope_radius_at_metal_m,
        static_friction: friction,
        kinetic_friction: 0.8 * friction,
        bending_stiffness_n_m2: thread.bend_stiffness_n_m_per_rad * thread.segment_length_m(),
        damping_per_s: thread.linear_damping_per_s,
        contact_passes: 2,
        substeps: thread.rope_substeps.unwrap_or(RopeParams::default().substeps),
        axial_stiffness_n: thread.axial_stiffness_n.unwrap_or(f64::INFINITY),
        mass_per_m_kg: thread.rope_inertial_mass_kg_per_m.unwrap_or(RopeParams::default().mass_per_m_kg),
        contact_margin_m: CONTACT_MARGIN_RADII * thread.radius_m,
        direct_bending: thread.rope_direct_bending,
        constraint_passes: thread.rope_constraint_passes.unwrap_or(1),
        contacts_both_ways: thread.rope_contacts_both_ways,
        ..RopeParams::default()
    }
}

impl SceneRope {
    /// Lays the rope along `layout` (needle end first; thread left over runs on straight beyond
    /// its last point), swages it to a new needle body, threads it through the stitch's points of
    /// `tissue` (sliding freely: set its `slide_friction_n`) and lets it touch `touched` (the
    /// instruments' colliders) and the tissue. Returns the rope and the needle's geometry in its
    /// body's frame.
    pub fn build(
        thread: &ThreadParams,
        needle: &NeedleParams,
        layout: &[Vector3<f64>],
        physics: &mut Physics,
        tissue: &Tissue,
        tissue_params: &TissueParams,
        touched: &[ColliderHandle],
    ) -> (Self, Needle) {
        let params = rope_params(thread);
        // The thread's whole length in segments as near the spacing asked for as fit it (at 1.2 mm,
        // cut to whole segments, 0.2 m lost 0.8 mm).
        let asked_m = thread.rope_spacing_radii.unwrap_or(SPACING_RADII) * thread.radius_m;
        let segments = ((thread.length_m / asked_m).round() as usize).max(1);
        let spacing_m = thread.length_m / segments as f64;
        let count = segments + 1;
        let mut ropes = Ropes::new(params);
        let strand = ropes.add_strand(&crate::chords::chord_points(layout, spacing_m, count));
        // The suture's own weight (the rope's mass is inflated for its solver).
        let weight_per_particle_n = thread.mass_kg / thread.length_m * spacing_m * 9.81;
        for f in &mut ropes.force_n {
            *f = -Vector3::z() * weight_per_particle_n;
        }
        let (geometry, needle_body) = Self::needle(needle, physics, &ropes, thread.linear_damping_per_s);
        let stitch = SlideStitch::new(tissue, tissue_params, physics, &ropes);
        let mut tissue_colliders: Vec<ColliderHandle> = tissue.flap_colliders.to_vec();
        tissue_colliders.extend(physics.bodies[tissue.pad].colliders().iter().copied());
        let colliders = touched.iter().chain(&tissue_colliders).map(|c| (*c, 0..0)).collect();
        let at_collision_radius = tissue_colliders.clone();
        let contacts = RigidContacts {
            colliders,
            at_collision_radius,
            friction: thread.friction,
            attachments: vec![Attachment {
                particle: strand.start,
                body: needle_body,
                local_m: Vector3::zeros(),
            }],
            ..Default::default()
        };
        let needle_weight_n = needle.mass_kg * 9.81;
        let rope = Self {
            ropes,
            contacts,
            spacing_m,
            needle_body,
            tissue_colliders,
            stitch: Some(stitch),
            needle_free: false,
            needle_weight_n,
        };
        (rope, geometry)
    }

    /// The needle's body at the rope's first particle, its x along the rope's first segment (as the
    /// chain's first segment lies), the arc's capsules its colliders.
    fn needle(
        params: &NeedleParams,
        physics: &mut Physics,
        ropes: &Ropes,
        damping_per_s: f64,
    ) -> (Needle, RigidBodyHandle) {
        let geometry = Needle::geometry(params, 0.0);
        let (a, b) = (ropes.x[0], ropes.x[1]);
        let rotation = Rotation::from_rotation_arc(Vector::X, to_rapier(&(b - a).normalize()));
        let body = physics.bodies.insert(
            RigidBodyBuilder::dynamic()
                .pose(Pose::from_parts(to_rapier(&a), rotation))
                .linear_damping(damping_per_s)
                .can_sleep(false)
                .build(),
        );
        let piece_mass = params.mass_kg / (geometry.arc_points_m.len() - 1) as f64;
        for pair in geometry.arc_points_m.windows(2) {
            let capsule = ColliderBuilder::new(SharedShape::capsule(
                to_rapier(&pair[0]),
                to_rapier(&pair[1]),
                params.wire_radius_m,
            ))
            .mass(piece_mass)
            .friction(0.3)
            .collision_groups(InteractionGroups::new(
                THREAD_GROUP,
                FLAP_GROUP | PAD_GROUP,
                InteractionTestMode::And,
            ))
            .build();
            physics.colliders.insert_with_parent(capsule, body, &mut physics.bodies);
        }
        (Needle { body: Some(body), ..geometry }, body)
    }

    /// Steps the rope by `dt_s` among the bodies as they stand before Rapier's step, then applies
    /// what it did to them.
    pub fn step(&mut self, physics: &mut Physics, dt_s: f64) {
        // The thread in the stitch, and where it enters and leaves the flaps' surfaces.
        let margin = (4.0 * self.ropes.params.radius_m / self.spacing_m).ceil() as usize + 1;
        let between = self.stitch.as_ref().map_or(0..0, SlideStitch::between);
        let inside = between.start.saturating_sub(margin)..(between.end + margin).min(self.ropes.x.len());
        for (collider, exempt) in &mut self.contacts.colliders {
            if self.tissue_colliders.contains(collider) {
                *exempt = inside.clone();
            }
        }
        self.contacts.step_with(&mut self.ropes, dt_s, &physics.bodies, &physics.colliders, &mut self.stitch);
        self.contacts.apply_impulses(&mut physics.bodies);
        if let Some(stitch) = &self.stitch {
            stitch.pose_flaps(physics);
        }
        if self.needle_free {
            self.carry_needle(physics);
        }
    }

    /// Hands the needle to jaws (`held`: dynamic, the rope swaged to it) or to the rope (kinematic,
    /// carried on the rope's end).
    pub fn set_needle_held(&mut self, physics: &mut Physics, held: bool) {
        if held != self.needle_free {
            return;
        }
        let weight = Vector3::z() * self.needle_weight_n;
        if held {
            physics.bodies[self.needle_body].set_body_type(RigidBodyType::Dynamic, true);
            self.contacts
                .attachments
                .insert(0, Attachment { particle: 0, body: self.needle_body, local_m: Vector3::zeros() });
            self.contacts.attachment_impulses.insert(0, Vector3::zeros());
            self.ropes.force_n[0] += weight;
        } else {
            physics.bodies[self.needle_body].set_body_type(RigidBodyType::KinematicPositionBased, true);
            let needle = self.needle_body;
            self.contacts.detach(|a| a.body == needle);
            self.ropes.force_n[0] -= weight;
        }
        self.needle_free = !held;
    }

    /// A free needle's next pose: its swage on the rope's first particle, its x along the first
    /// segment, turned from where it lies by the smallest turn.
    fn carry_needle(&self, physics: &mut Physics) {
        let body = &mut physics.bodies[self.needle_body];
        let now = *body.position();
        let (a, b) = (self.ropes.x[0], self.ropes.x[1]);
        let Some(along) = (b - a).try_normalize(1e-12) else { return };
        let x_now = now.rotation * Vector::X;
        let rotation = (Rotation::from_rotation_arc(x_now, to_rapier(&along)) * now.rotation).normalize();
        body.set_next_kinematic_position(Pose::from_parts(to_rapier(&a), rotation));
    }

    /// Takes the thread out of the stitch: it no longer slides through the flaps, which are Rapier's
    /// own dynamic bodies again.
    pub fn unstitch(&mut self, physics: &mut Physics) {
        if let Some(stitch) = self.stitch.take() {
            stitch.release(physics);
        }
    }

    /// The particles touching `body`'s colliders now (the rope's radius there and 0.1 mm from
    /// them, or in them), sorted.
    pub fn particles_touching(&self, physics: &Physics, body: RigidBodyHandle) -> Vec<usize> {
        let mut found = Vec::new();
        let colliders = physics.bodies.get(body).map_or(&[][..], |b| b.colliders());
        for (handle, collider) in colliders.iter().filter_map(|c| Some((*c, physics.colliders.get(*c)?))) {
            let aabb = collider.compute_aabb().loosened(self.ropes.params.radius_m + TOUCH_SLOP_M);
            found.extend((0..self.ropes.x.len()).filter(|p| {
                aabb.contains_local_point(to_rapier(&self.ropes.x[*p])) && self.touches(handle, collider, *p)
            }));
        }
        found.sort_unstable();
        found.dedup();
        found
    }

    /// Whether particle `p` touches `collider` (is in it, or within 0.1 mm of where the collider
    /// pushes it: the rope's radius, at metal [`crate::rope::RopeParams::radius_at_metal_m`]).
    pub fn touches(&self, handle: ColliderHandle, collider: &Collider, p: usize) -> bool {
        let x = self.ropes.x[p];
        let projection = collider.shape().project_point(collider.position(), to_rapier(&x), true);
        projection.is_inside
            || (to_na(projection.point) - x).norm() <= self.pushed_at_m(handle) + TOUCH_SLOP_M
    }

    /// How far from collider `handle` the rope's axis is pushed: its collision radius at the
    /// tissue, its radius at metal elsewhere, m.
    fn pushed_at_m(&self, handle: ColliderHandle) -> f64 {
        if self.contacts.at_collision_radius.contains(&handle) {
            self.ropes.params.radius_m
        } else {
            self.ropes.params.radius_at_metal_m()
        }
    }

    /// The rope's centreline, needle end first, m.
    pub fn centreline(&self) -> Vec<Vector3<f64>> {
        self.ropes.polyline(0)
    }

    /// Where `flap`'s stitch point sits on the rope: the arc length from the needle end, m.
    pub fn arc_at_m(&self, flap: Flap) -> Option<f64> {
        Some(self.stitch.as_ref()?.at(flap) * self.spacing_m)
    }

    /// The particles in the tissue, from the exit's to the entry's.
    pub fn inside(&self) -> Option<std::ops::RangeInclusive<usize>> {
        let range = self.stitch.as_ref()?.between();
        (!range.is_empty()).then(|| range.start..=range.end - 1)
    }
}
