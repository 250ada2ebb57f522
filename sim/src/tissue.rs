//! The tissue: a pad on the patient's body wall carrying two flaps either side of a wound. Each flap
//! slides across the wound on a prismatic joint whose spring (the elastic load of the tissue) pulls it
//! back to the open rest gap; the suture, tied, pulls them together. The wound gap is measured between
//! the flaps' inner faces.
//!
//! Tissue frame: x along the wound, y across it, z up, origin at the wound's centre on the surface.
//! Flap A (the entry side, where the tail stays) lies at +y, flap B (the exit side, towards the
//! needle) at -y.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rapier3d::prelude::*;

use crate::convert::{to_na, to_pose, to_rapier};
use crate::groups::{FLAP_GROUP, PAD_GROUP, THREAD_GROUP};
use crate::physics::Physics;
use crate::scene::{StitchParams, TissueParams};

/// Half size of the square pad under the flaps, m: wide enough for the thread laid on it.
const PAD_HALF_M: f64 = 0.12;
/// Thickness of the pad, m.
const PAD_THICKNESS_M: f64 = 0.02;
/// How far a flap may be pulled outward from its rest position, m.
pub const FLAP_OUTWARD_TRAVEL_M: f64 = 0.02;

/// The two flaps, in the order the thread meets them from the needle end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flap {
    /// The exit side (-y), towards the needle.
    B,
    /// The entry side (+y), where the tail stays.
    A,
}

impl Flap {
    /// Both flaps, in the order the thread meets them from the needle end.
    pub const ALONG_THREAD: [Flap; 2] = [Flap::B, Flap::A];

    /// +1 for A (+y), -1 for B.
    pub fn side(self) -> f64 {
        match self {
            Flap::A => 1.0,
            Flap::B => -1.0,
        }
    }

    /// The flap's index in per-flap arrays ([B, A]).
    pub fn index(self) -> usize {
        match self {
            Flap::B => 0,
            Flap::A => 1,
        }
    }
}

/// The tissue in a [`Physics`] world.
pub struct Tissue {
    /// Pose of the tissue frame in the world.
    pub world_from_tissue: Isometry3<f64>,
    /// The fixed body the flaps slide on.
    pub base: RigidBodyHandle,
    /// The pad under the flaps.
    pub pad: RigidBodyHandle,
    /// Flap bodies, [B, A].
    pub flaps: [RigidBodyHandle; 2],
    /// Their colliders, [B, A].
    pub flap_colliders: [ColliderHandle; 2],
    /// The prismatic joints, [B, A].
    pub joints: [ImpulseJointHandle; 2],
    /// The flaps' size: along, across, thickness, m.
    pub flap_size_m: [f64; 3],
    /// Where the stitch's entry (A) and exit (B) points sit in each flap's frame, [B, A].
    pub flap_from_hole_m: [Vector3<f64>; 2],
    /// Where the stitch runs deepest in each flap, in its frame, [B, A]: the suture goes down from
    /// the exit point through flap B, under the wound at the stitch's depth and up through flap A to
    /// the entry point, so that nothing on the surface can reach round the part under the wound.
    pub flap_from_deep_m: [Vector3<f64>; 2],
}

/// The stitch's deep points lie this far in from each flap's inner face, m.
const DEEP_INSET_M: f64 = 0.001;

impl Tissue {
    /// The tissue frame of a scene: at its centre, turned by its yaw about the world's z and then
    /// tilted about the wound (the turned x).
    pub fn frame(params: &TissueParams) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(Vector3::from(params.centre_m)),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), params.yaw_rad)
                * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), params.tilt_rad),
        )
    }

    /// Builds the pad, the flaps at their rest gap with their springs, and the stitch's points.
    pub fn build(physics: &mut Physics, params: &TissueParams, stitch: &StitchParams) -> Self {
        let world_from_tissue = Self::frame(params);
        let [along, across, thickness] = params.flap_size_m;
        let base = physics.bodies.insert(RigidBodyBuilder::fixed().pose(to_pose(&world_from_tissue)));
        let pad_centre =
            world_from_tissue * nalgebra::Point3::new(0.0, 0.0, -thickness - 0.5 * PAD_THICKNESS_M);
        let pad = physics.bodies.insert(
            RigidBodyBuilder::fixed()
                .pose(Pose::from_parts(to_rapier(&pad_centre.coords), to_pose(&world_from_tissue).rotation)),
        );
        physics.colliders.insert_with_parent(
            ColliderBuilder::cuboid(PAD_HALF_M, PAD_HALF_M, 0.5 * PAD_THICKNESS_M)
                .friction(0.8)
                .collision_groups(InteractionGroups::new(PAD_GROUP, THREAD_GROUP, InteractionTestMode::And))
                .build(),
            pad,
            &mut physics.bodies,
        );
        let mut flaps = Vec::with_capacity(2);
        let mut flap_colliders = Vec::with_capacity(2);
        let mut joints = Vec::with_capacity(2);
        let mut holes = Vec::with_capacity(2);
        let mut deep = Vec::with_capacity(2);
        for flap in Flap::ALONG_THREAD {
            let s = flap.side();
            let tissue_from_flap =
                Vector3::new(0.0, s * 0.5 * (params.rest_gap_m + across), -0.5 * thickness);
            let world_centre = world_from_tissue * nalgebra::Point3::from(tissue_from_flap);
            let body = physics.bodies.insert(
                RigidBodyBuilder::dynamic()
                    .pose(Pose::from_parts(
                        to_rapier(&world_centre.coords),
                        to_pose(&world_from_tissue).rotation,
                    ))
                    .can_sleep(false)
                    .build(),
            );
            let collider = physics.colliders.insert_with_parent(
                ColliderBuilder::cuboid(0.5 * along, 0.5 * across, 0.5 * thickness)
                    .mass(params.flap_mass_kg)
                    .friction(0.8)
                    .active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS)
                    .collision_groups(InteractionGroups::new(
                        FLAP_GROUP,
                        THREAD_GROUP | FLAP_GROUP,
                        InteractionTestMode::And,
                    ))
                    .build(),
                body,
                &mut physics.bodies,
            );
            // Outward is +y for A and -y for B; the joint's coordinate is the outward displacement.
            // On a tilted tissue the body beneath carries the flap's weight along the slope, not the
            // wound's load: the load's rest is set off by that weight, so the wound rests at its gap.
            let outward = world_from_tissue.rotation * Vector3::new(0.0, s, 0.0);
            let weight_outward_n = params.flap_mass_kg * to_na(physics.gravity).dot(&outward);
            let rest_m = if params.opening_stiffness_n_per_m > 0.0 {
                -weight_outward_n / params.opening_stiffness_n_per_m
            } else {
                0.0
            };
            let joint = PrismaticJointBuilder::new(Vector::new(0.0, s, 0.0))
                .local_anchor1(to_rapier(&tissue_from_flap))
                .local_anchor2(Vector::ZERO)
                .limits([-0.5 * params.rest_gap_m, FLAP_OUTWARD_TRAVEL_M])
                .motor_position(rest_m, params.opening_stiffness_n_per_m, params.opening_damping_n_s_per_m)
                .motor_model(MotorModel::ForceBased)
                .contacts_enabled(false);
            joints.push(physics.impulse_joints.insert(base, body, joint, true));
            // The entry/exit point on the surface, bite away from the wound's centre line.
            let tissue_hole = Vector3::new(stitch.along_m, s * stitch.bite_m, 0.0);
            holes.push(tissue_hole - tissue_from_flap);
            // Under the surface at the stitch's depth, just in from the inner face (never beyond the
            // entry or exit point).
            let inset = (0.5 * params.rest_gap_m + DEEP_INSET_M).min(stitch.bite_m);
            deep.push(Vector3::new(stitch.along_m, s * inset, -stitch.depth_m) - tissue_from_flap);
            flaps.push(body);
            flap_colliders.push(collider);
        }
        Self {
            world_from_tissue,
            base,
            pad,
            flaps: [flaps[0], flaps[1]],
            flap_colliders: [flap_colliders[0], flap_colliders[1]],
            joints: [joints[0], joints[1]],
            flap_size_m: params.flap_size_m,
            flap_from_hole_m: [holes[0], holes[1]],
            flap_from_deep_m: [deep[0], deep[1]],
        }
    }

    /// The flap's body.
    pub fn flap(&self, flap: Flap) -> RigidBodyHandle {
        self.flaps[flap.index()]
    }

    /// The stitch's four points as the thread meets them from the needle end, each with the flap
    /// that carries it: the exit (B's hole), B's deep point, A's deep point, the entry (A's hole);
    /// world frame, m.
    pub fn stitch_points_m(&self, physics: &Physics) -> [(Flap, Vector3<f64>); 4] {
        [
            (Flap::B, self.hole_m(physics, Flap::B)),
            (Flap::B, self.deep_m(physics, Flap::B)),
            (Flap::A, self.deep_m(physics, Flap::A)),
            (Flap::A, self.hole_m(physics, Flap::A)),
        ]
    }

    /// Where the stitch passes through `flap`, world frame, m.
    pub fn hole_m(&self, physics: &Physics, flap: Flap) -> Vector3<f64> {
        let local = self.flap_from_hole_m[flap.index()];
        to_na(physics.bodies[self.flap(flap)].position().transform_point(to_rapier(&local)))
    }

    /// Where the stitch runs deepest in `flap`, world frame, m.
    pub fn deep_m(&self, physics: &Physics, flap: Flap) -> Vector3<f64> {
        let local = self.flap_from_deep_m[flap.index()];
        to_na(physics.bodies[self.flap(flap)].position().transform_point(to_rapier(&local)))
    }

    /// The stitch point of `flap` in that flap's frame, m.
    pub fn flap_from_hole_m(&self, flap: Flap) -> Vector3<f64> {
        self.flap_from_hole_m[flap.index()]
    }

    /// The wound gap: distance between the flaps' inner faces across the wound, m.
    pub fn gap_m(&self, physics: &Physics) -> f64 {
        let tissue_from_world = self.world_from_tissue.inverse();
        let y = |flap: Flap| {
            let t = physics.bodies[self.flap(flap)].translation();
            (tissue_from_world * nalgebra::Point3::new(t.x, t.y, t.z)).y
        };
        y(Flap::A) - y(Flap::B) - self.flap_size_m[1]
    }

    /// The surface's outward normal, world frame.
    pub fn normal(&self) -> Vector3<f64> {
        self.world_from_tissue.rotation * Vector3::z()
    }
}
