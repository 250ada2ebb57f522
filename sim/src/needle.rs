//! The half-circle needle swaged to the thread's first segment. It is rigid and light, so its capsules
//! are colliders of that segment's body: no joint to stretch between needle and thread.
//!
//! In the first segment's frame (x along the thread towards the tail) the needle's back end sits at the
//! segment's needle end and leaves it along -x; the arc of radius `arc / pi` bends towards +y and ends
//! at the point, which faces +x.

use nalgebra::Vector3;
use rapier3d::prelude::*;

use crate::convert::{to_na, to_rapier};
use crate::groups::{FLAP_GROUP, PAD_GROUP, THREAD_GROUP};
use crate::physics::Physics;
use crate::scene::NeedleParams;
use crate::thread::Thread;

/// Capsules approximating the arc.
const PIECES: usize = 8;

/// The needle's geometry in the first segment's frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Needle {
    /// Points along the arc from the swage (the thread's end) to the point, segment frame, m.
    pub arc_points_m: Vec<Vector3<f64>>,
    /// Wire radius, m.
    pub wire_radius_m: f64,
    /// The body carrying it: the chain's first segment, or the needle's own body beside the rope
    /// (none for geometry alone).
    pub body: Option<RigidBodyHandle>,
}

impl Needle {
    /// The arc of `params` starting at the first segment's needle end.
    pub fn geometry(params: &NeedleParams, segment_length_m: f64) -> Self {
        let radius = params.arc_length_m / std::f64::consts::PI;
        let start = -0.5 * segment_length_m;
        let arc_points_m = (0..=PIECES)
            .map(|k| {
                let theta = std::f64::consts::PI * k as f64 / PIECES as f64;
                Vector3::new(start - radius * theta.sin(), radius * (1.0 - theta.cos()), 0.0)
            })
            .collect();
        Self { arc_points_m, wire_radius_m: params.wire_radius_m, body: None }
    }

    /// Adds the needle's capsules to the thread's first segment.
    pub fn attach(params: &NeedleParams, physics: &mut Physics, thread: &Thread) -> Self {
        let needle = Self::geometry(params, thread.segment_length_m);
        let body = thread.segments[0];
        let piece_mass = params.mass_kg / PIECES as f64;
        for pair in needle.arc_points_m.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let capsule = ColliderBuilder::new(SharedShape::capsule(
                to_rapier(&a),
                to_rapier(&b),
                params.wire_radius_m,
            ))
            .mass(piece_mass)
            .friction(0.3)
            // The needle touches the thread and the tissue, not the instruments: a 16 mm arc swinging
            // with the holding jaws would otherwise snag every instrument it passes and tear the grasp.
            .collision_groups(InteractionGroups::new(
                THREAD_GROUP,
                THREAD_GROUP | FLAP_GROUP | PAD_GROUP,
                InteractionTestMode::And,
            ))
            .build();
            physics.colliders.insert_with_parent(capsule, body, &mut physics.bodies);
        }
        Self { body: Some(body), ..needle }
    }

    /// The arc's points in the world, swage first, m: on its own body, or else on `carrier` (the
    /// chain's first segment).
    pub fn world_points_m(&self, physics: &Physics, carrier: Option<RigidBodyHandle>) -> Vec<Vector3<f64>> {
        let Some(body) = self.body.or(carrier) else { return Vec::new() };
        let Some(body) = physics.bodies.get(body) else { return Vec::new() };
        let pose = body.position();
        self.arc_points_m.iter().map(|p| to_na(pose.transform_point(to_rapier(p)))).collect()
    }
}
