//! The stitch of the scene's rope, solved with the flaps in it: each flap's slide across the wound
//! (its spring back to the rest gap, its damping, its stops and any load pulling it open) is
//! integrated inside the rope's substeps, as the lab's wound trial (`knotlab_lab::wound`) integrates its flaps, and the thread
//! slides through the four stitch points the flaps carry; the rope's contacts with the flaps push
//! them along their slides, each move shared by the masses. Rapier only shows the flaps where the
//! slides put them (kinematic bodies). Exchanging impulses with dynamic flaps once a step was not
//! stable: the rope is inextensible and held at both ends, as heavy as the world to a flap, and at
//! an instrument's cinch the lag fed back until a flap flew off.

use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

use super::rigid::{nearest_on_rope, thread_through_held};
use super::{Ropes, Surroundings};
use crate::convert::to_rapier;
use crate::scene::TissueParams;
use crate::tissue::{FLAP_OUTWARD_TRAVEL_M, Flap, Tissue};

/// One flap on its slide.
#[derive(Clone, Debug)]
struct Slide {
    body: RigidBodyHandle,
    /// The flap's pose at rest.
    rest: Pose,
    /// Outward (away from the wound), world frame.
    outward: Vector3<f64>,
    /// Outward displacement from rest, m, and its rate, m/s.
    u_m: f64,
    v_m_s: f64,
}

impl Slide {
    /// The flap's pose where its slide has it.
    fn pose(&self) -> Pose {
        let mut pose = self.rest;
        pose.translation += to_rapier(&(self.outward * self.u_m));
        pose
    }
}

/// The two flaps and the four stitch points the rope passes.
#[derive(Clone, Debug)]
pub struct SlideStitch {
    tissue: TissueParams,
    /// [B, A].
    slides: [Slide; 2],
    /// Each flap pulled open with this force besides its spring, N ([B, A]).
    pub load_n: [f64; 2],
    /// The friction holding the thread in each flap, N (`stitch.slide_friction_n`), split between
    /// its two stitch points; 0 (as built): the thread slides through them freely.
    pub slide_friction_n: f64,
    /// The stitch points [exit, exit deep, entry deep, entry]: which flap, where in its rest frame
    /// (world frame at rest), and where the rope passes (a particle's index plus a fraction).
    points: [(usize, Vector3<f64>, f64); 4],
    /// The flaps' joints, disabled while the slides move the flaps.
    joints: [ImpulseJointHandle; 2],
    /// The thread's pull on each flap through its stitch points over the substep's solve, N ([B, A]).
    outward_n: [f64; 2],
    /// How far the rope's contacts moved each flap along its slide in the substep, m ([B, A]): each
    /// contact moves the flap as it moves the particle, by their masses, so that a thread caught in
    /// the seam holds the flaps apart, pressed with what closes them, as flesh closing on a suture
    /// does. (Shut to their stop on it regardless, the flaps pressed it with whatever pushed it out
    /// of their overlap each substep: 3 N at 6 substeps, 240 N at 24.)
    pushed_m: [f64; 2],
}

/// Enables or disables the joints.
fn enable_joints(physics: &mut crate::physics::Physics, joints: &[ImpulseJointHandle], enabled: bool) {
    for joint in joints {
        if let Some(j) = physics.impulse_joints.get_mut(*joint, true) {
            j.data.set_enabled(enabled);
        }
    }
}

impl SlideStitch {
    /// The stitch of `tissue` as `physics` holds it now, the rope `ropes` laid through its points;
    /// the flaps become kinematic.
    pub fn new(
        tissue: &Tissue,
        params: &TissueParams,
        physics: &mut crate::physics::Physics,
        ropes: &Ropes,
    ) -> Self {
        let slide = |flap: Flap, physics: &mut crate::physics::Physics| {
            let body = tissue.flap(flap);
            physics.bodies[body].set_body_type(RigidBodyType::KinematicPositionBased, true);
            let rest = *physics.bodies[body].position();
            let outward = tissue.world_from_tissue.rotation * Vector3::new(0.0, flap.side(), 0.0);
            Slide { body, rest, outward, u_m: 0.0, v_m_s: 0.0 }
        };
        let slides = [slide(Flap::B, physics), slide(Flap::A, physics)];
        // The slides take the place of the flaps' joints (which Rapier would otherwise go on
        // solving between the flaps and the tissue's base, neither dynamic, every step).
        enable_joints(physics, &tissue.joints, false);
        let last = ropes.x.len() - 1;
        let point = |flap: Flap, at: Vector3<f64>| {
            let nearest = (0..ropes.x.len())
                .min_by(|a, b| (ropes.x[*a] - at).norm().total_cmp(&(ropes.x[*b] - at).norm()))
                .unwrap_or(0);
            (flap.index(), at, nearest_on_rope(ropes, &at, nearest, last))
        };
        let points = tissue.stitch_points_m(physics).map(|(flap, at)| point(flap, at));
        Self {
            tissue: *params,
            slides,
            load_n: [0.0; 2],
            slide_friction_n: 0.0,
            points,
            joints: tissue.joints,
            outward_n: [0.0; 2],
            pushed_m: [0.0; 2],
        }
    }

    /// Where the rope passes the exit (B) or the entry (A): a particle's index plus a fraction.
    pub fn at(&self, flap: Flap) -> f64 {
        match flap {
            Flap::B => self.points[0].2,
            Flap::A => self.points[3].2,
        }
    }

    /// The particles between the exit and the entry.
    pub fn between(&self) -> std::ops::Range<usize> {
        (self.points[0].2.floor() as usize)..(self.points[3].2.ceil() as usize + 1)
    }

    /// Shows the flaps where their slides are, for Rapier's coming step.
    pub fn pose_flaps(&self, physics: &mut crate::physics::Physics) {
        for slide in &self.slides {
            physics.bodies[slide.body].set_next_kinematic_position(slide.pose());
        }
    }

    /// Takes the thread out: the flaps become Rapier's dynamic bodies again, at rest where they are,
    /// on their joints.
    pub fn release(self, physics: &mut crate::physics::Physics) {
        for slide in &self.slides {
            let body = &mut physics.bodies[slide.body];
            body.set_body_type(RigidBodyType::Dynamic, true);
            body.set_linvel(Vector::ZERO, true);
        }
        enable_joints(physics, &self.joints, true);
    }
}

impl Surroundings for SlideStitch {
    /// The thread put through the stitch points before the rope's lengths are solved (after them, the
    /// points' moves across the thread stretched it, by some 8 % next to them under a cinch's pull).
    fn hold(&mut self, ropes: &mut Ropes, _held: &mut [bool], h_s: f64) {
        self.thread_through_points(ropes, h_s);
    }

    /// A flap stands where its slide has it, through the rope's substeps.
    fn pose_of(&self, body: RigidBodyHandle) -> Option<Pose> {
        self.slides.iter().find(|s| s.body == body).map(Slide::pose)
    }

    /// A flap is as heavy as it is, along its slide only.
    fn inverse_mass_along(&self, body: RigidBodyHandle, direction: &Vector3<f64>) -> f64 {
        self.slides
            .iter()
            .find(|s| s.body == body)
            .map_or(0.0, |s| s.outward.dot(direction).powi(2) / self.tissue.flap_mass_kg)
    }

    /// The flap takes the impulse at once: its speed, and where it stands for the next contact.
    fn pushed(&mut self, body: RigidBodyHandle, impulse_n_s: Vector3<f64>, h_s: f64) {
        if let Some(flap) = self.slides.iter().position(|s| s.body == body) {
            let slide = &mut self.slides[flap];
            let dv = slide.outward.dot(&impulse_n_s) / self.tissue.flap_mass_kg;
            slide.v_m_s += dv;
            slide.u_m += dv * h_s;
            self.pushed_m[flap] += dv * h_s;
        }
    }

    /// The flaps moved on their slides by the thread's pull through the points and its contacts,
    /// and their springs.
    fn after(&mut self, _ropes: &mut Ropes, _x_prev: &[Vector3<f64>], h_s: f64) {
        self.move_flaps(h_s);
    }
}

impl SlideStitch {
    /// The thread put through the stitch points (moved across itself onto each, held along itself
    /// by the flap's friction), the pull on each flap summed.
    fn thread_through_points(&mut self, ropes: &mut Ropes, h_s: f64) {
        let mut outward_n = [0.0; 2];
        for k in 0..4 {
            let (flap, rest_at, at) = self.points[k];
            let slide = &self.slides[flap];
            let target = rest_at + slide.outward * slide.u_m;
            let friction_n = 0.5 * self.slide_friction_n;
            let Some((moves, now_at)) = thread_through_held(ropes, at, &target, friction_n, h_s) else {
                continue;
            };
            for (p, dx) in moves {
                if ropes.w[p] > 0.0 {
                    outward_n[flap] -= slide.outward.dot(&dx) / (ropes.w[p] * h_s * h_s);
                }
            }
            self.points[k].2 = now_at;
        }
        self.outward_n = outward_n;
    }

    /// The flaps moved on their slides by the thread's pull and their springs.
    fn move_flaps(&mut self, h_s: f64) {
        let outward_n = std::mem::take(&mut self.outward_n);
        let pushed_m = std::mem::take(&mut self.pushed_m);
        let closed = -0.5 * self.tissue.rest_gap_m;
        for (flap, slide) in self.slides.iter_mut().enumerate() {
            let spring_n = -self.tissue.opening_stiffness_n_per_m * slide.u_m
                - self.tissue.opening_damping_n_s_per_m * slide.v_m_s;
            let a = (outward_n[flap] + spring_n + self.load_n[flap]) / self.tissue.flap_mass_kg;
            slide.v_m_s += a * h_s;
            // The contacts' impulses are in the speed, and their moves already made.
            slide.u_m += slide.v_m_s * h_s - pushed_m[flap];
            if slide.u_m < closed {
                slide.u_m = closed;
                slide.v_m_s = slide.v_m_s.max(0.0);
            } else if slide.u_m > FLAP_OUTWARD_TRAVEL_M {
                slide.u_m = FLAP_OUTWARD_TRAVEL_M;
                slide.v_m_s = slide.v_m_s.min(0.0);
            }
        }
    }
}
