//! What the scene looks like at one instant, as plain data for anyone who draws or logs it (the
//! snapshot pictures, the root package's Rerun recording): every solid collider with its owner, shape
//! and pose, the thread's centreline, the needle, the stitch holes and the wound gap. Read from the
//! colliders themselves, so what is drawn is what collides.

use nalgebra::{IsometryMatrix3, Vector3};
use rapier3d::prelude::*;

use crate::convert::{to_isometry, to_na};
use crate::groups::{ENVIRONMENT_GROUP, FLAP_GROUP, PAD_GROUP, THREAD_GROUP};
use crate::tissue::Flap;
use crate::world::SimWorld;

/// Who a solid belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Owner {
    /// A robot link, by its URDF name (`left_link3`, `right_jaw_a`, ...).
    Link(String),
    /// A tissue flap.
    Flap,
    /// The pad under the flaps.
    Pad,
    /// Anything else that collides (a collider without a link).
    Other,
}

/// A solid's shape in its own frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SolidShape {
    /// A box centred on the frame.
    Cuboid {
        /// Half sizes, m.
        half_extents_m: Vector3<f64>,
    },
    /// A capsule between two points of the frame.
    Capsule {
        /// One end of the axis, m.
        a_m: Vector3<f64>,
        /// The other end, m.
        b_m: Vector3<f64>,
        /// Radius, m.
        radius_m: f64,
    },
    /// A ball centred on the frame.
    Ball {
        /// Radius, m.
        radius_m: f64,
    },
}

/// One solid collider.
#[derive(Clone, Debug, PartialEq)]
pub struct Solid {
    /// Whose it is.
    pub owner: Owner,
    /// Its shape.
    pub shape: SolidShape,
    /// Its pose.
    pub world_from_solid: IsometryMatrix3<f64>,
}

/// The scene at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneShapes {
    /// Robot links, flaps and pad (not the thread, not the fixed environment).
    pub solids: Vec<Solid>,
    /// The thread's centreline, needle end first, m.
    pub thread_m: Vec<Vector3<f64>>,
    /// The thread's radius, m.
    pub thread_radius_m: f64,
    /// The needle's wire, from its tip, m.
    pub needle_m: Vec<Vector3<f64>>,
    /// The needle wire's radius, m.
    pub needle_radius_m: f64,
    /// The stitch holes, in the order the thread passes them, m.
    pub holes_m: Vec<Vector3<f64>>,
    /// The wound's gap, m.
    pub wound_gap_m: f64,
}

/// Reads the scene off `world`.
pub fn scene_shapes(world: &SimWorld) -> SceneShapes {
    let physics = &world.physics;
    let mut solids = Vec::new();
    for (_, collider) in physics.colliders.iter() {
        let groups = collider.collision_groups().memberships;
        if groups.contains(ENVIRONMENT_GROUP) || groups.contains(THREAD_GROUP) {
            continue;
        }
        let owner = if groups.contains(FLAP_GROUP) {
            Owner::Flap
        } else if groups.contains(PAD_GROUP) {
            Owner::Pad
        } else {
            collider
                .parent()
                .and_then(|body| world.link_bodies.iter().position(|l| *l == Some(body)))
                .map_or(Owner::Other, |i| Owner::Link(world.rig.tree.links[i].name.clone()))
        };
        let shape = collider.shape();
        let shape = if let Some(cuboid) = shape.as_cuboid() {
            SolidShape::Cuboid { half_extents_m: to_na(cuboid.half_extents) }
        } else if let Some(capsule) = shape.as_capsule() {
            SolidShape::Capsule {
                a_m: to_na(capsule.segment.a),
                b_m: to_na(capsule.segment.b),
                radius_m: capsule.radius,
            }
        } else if let Some(ball) = shape.as_ball() {
            SolidShape::Ball { radius_m: ball.radius }
        } else {
            continue;
        };
        solids.push(Solid { owner, shape, world_from_solid: to_isometry(collider.position()) });
    }
    SceneShapes {
        solids,
        thread_m: world.thread_centreline(),
        thread_radius_m: world.config.thread.radius_m,
        needle_m: world.suture().needle_points_m(physics),
        needle_radius_m: world.suture().needle().wire_radius_m,
        holes_m: Flap::ALONG_THREAD.iter().map(|&flap| world.tissue.hole_m(physics, flap)).collect(),
        wound_gap_m: world.wound_gap_m(),
    }
}

impl Solid {
    /// A point of the solid's frame in the world.
    pub fn world_point(&self, local_m: &Vector3<f64>) -> Vector3<f64> {
        self.world_from_solid.rotation * local_m + self.world_from_solid.translation.vector
    }
}
