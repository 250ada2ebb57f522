//! Building the simulated scene: the arms' servos and start joints, the rig's links as bodies
//! (kinematic, fixed, or fixed and posed after each step), the tissue and the suture.

use knotlab_hw::kinematics::{JointLimit, Tool};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rapier3d::prelude::*;

use super::arm::{JawState, SimArm};
use super::{SimWorld, WorldError, start_joints, trocar_of};
use crate::convert::matrix_to_pose;
use crate::groups::{ENVIRONMENT_GROUP, ROBOT_GROUP, THREAD_GROUP};
use crate::physics::Physics;
use crate::scene::SceneConfig;
use crate::servo::{ServoModel, ServoState};
use crate::suture::Suture;
use crate::tissue::Tissue;

impl SimWorld {
    /// Builds the scene with the thread laid along the path `layout` gives (world frame, needle end
    /// first, from the scene, its tissue and its physics as built), through the stitch where the path
    /// passes its points, and held by no instrument; the instruments stand as in [`Self::new`]. For
    /// trials of a thread placed by hand, such as a knot laid over the stitch (`knotlab_lab::laid_knot`).
    pub fn with_thread_laid(
        config: SceneConfig,
        rig: Rig,
        layout: impl FnOnce(&SceneConfig, &Tissue, &Physics) -> Vec<Vector3<f64>>,
    ) -> Result<Self, WorldError> {
        let mut physics = Physics::new(&config.solver);
        let arms: Vec<SimArm> = ArmName::ALL
            .iter()
            .map(|&name| {
                let arm = rig.arm(name);
                let offsets = match name {
                    ArmName::Left => config.servo.calibration_offset_rad.left,
                    ArmName::Right => config.servo.calibration_offset_rad.right,
                    ArmName::Assist => config.servo.calibration_offset_rad.assist,
                    ArmName::Camera => config.servo.calibration_offset_rad.camera,
                };
                let free = JointLimit::new(-1e3, 1e3, 10.0);
                let tool_limits = match &arm.model.tool {
                    Tool::Instrument { limits, .. } => [limits.roll, limits.pitch, limits.yaw, limits.jaw],
                    Tool::Endoscope { .. } => [free; 4],
                };
                let servos = (0..10)
                    .map(|i| ServoModel {
                        limit: if i < 6 { arm.model.limits[i] } else { tool_limits[i - 6] },
                        time_constant_s: if i < 6 {
                            config.servo.time_constant_s
                        } else {
                            config.servo.instrument_time_constant_s
                        },
                        max_acceleration_rad_s2: if i < 6 {
                            config.servo.max_acceleration_rad_s2
                        } else {
                            config.servo.instrument_max_acceleration_rad_s2
                        },
                        play_rad: if i < 6 { config.servo.play_rad } else { 0.0 },
                        calibration_offset_rad: if i < 6 { offsets[i] } else { 0.0 },
                    })
                    .collect();
                let trocar = trocar_of(&config, name);
                let ready = start_joints(&config, &rig, name, &trocar)?;
                let states = ready.to_array().iter().map(|q| ServoState::at(*q)).collect();
                Ok(SimArm {
                    name,
                    servos,
                    states,
                    command: ready,
                    jaws: JawState::Free,
                    force_n: Vector3::zeros(),
                    filtered_force_n: Vector3::zeros(),
                    instrument_bodies: Vec::new(),
                    jaw_colliders: Vec::new(),
                })
            })
            .collect::<Result<_, WorldError>>()?;

        // Links: kinematic when an arm moves them, fixed otherwise.
        let mut positions = vec![0.0; rig.tree.joints.len()];
        for arm in &arms {
            rig.arm(arm.name).write_tree_positions(&arm.actual(), &mut positions);
        }
        let poses = rig.tree.root_from_links(&positions);
        let mut link_bodies = vec![None; rig.tree.links.len()];
        let mut posed_links = Vec::new();
        let mut jaw_colliders: Vec<(String, ColliderHandle)> = Vec::new();
        // What a suture making its own link contacts touches of the robots: the instruments (the
        // arms' own links stay outside the body, above the trocars).
        let mut instrument_colliders: Vec<ColliderHandle> = Vec::new();
        let own_contacts = Suture::makes_own_link_contacts(&config);
        let flanges: Vec<usize> = arms.iter().map(|a| rig.arm(a.name).flange_link).collect();
        let on_instrument = |i: usize| flanges.iter().any(|&flange| on_flange(&rig, i, flange));
        for (i, link) in rig.tree.links.iter().enumerate() {
            if link.collisions.is_empty() {
                continue;
            }
            let moving = rig.tree.path_to(i).iter().any(|&j| rig.tree.joints[j].limit.is_some());
            // The jaws collide with the thread (it can be wound around them), except with what they
            // hold or close on: the contact filter leaves that to the grasp constraint.
            let jaw = ["_jaw_1", "_jaw_2", "_clevis", "_wrist"].iter().any(|s| link.name.ends_with(s));
            // With a suture whose contacts with the links are its own (the rope's), Rapier has
            // nothing to do with a moving link but carry the needle in jaws: the links' colliders
            // stay out of its broad phase, and the arms' own links (before the flange, which hold
            // nothing) are fixed bodies posed after each step, out of its solver.
            let posed = own_contacts && moving && !on_instrument(i);
            let (builder, group, filter) = if moving && !posed {
                (RigidBodyBuilder::kinematic_position_based(), ROBOT_GROUP, THREAD_GROUP)
            } else if moving {
                (RigidBodyBuilder::fixed(), ROBOT_GROUP, THREAD_GROUP)
            } else {
                (RigidBodyBuilder::fixed(), ENVIRONMENT_GROUP, Group::NONE)
            };
            let body = physics.bodies.insert(builder.pose(matrix_to_pose(&poses[i])).build());
            if posed {
                posed_links.push((i, body));
            }
            for c in &link.collisions {
                let collider = shape_collider(&c.shape)
                    .enabled(!(own_contacts && moving))
                    .position(matrix_to_pose(&c.link_from_shape))
                    .friction(0.8)
                    .active_hooks(if jaw { ActiveHooks::FILTER_CONTACT_PAIRS } else { ActiveHooks::empty() })
                    .collision_groups(InteractionGroups::new(group, filter, InteractionTestMode::And))
                    .build();
                let handle = physics.colliders.insert_with_parent(collider, body, &mut physics.bodies);
                if jaw && moving {
                    jaw_colliders.push((link.name.clone(), handle));
                }
                if moving && on_instrument(i) {
                    instrument_colliders.push(handle);
                }
            }
            link_bodies[i] = Some(body);
        }

        let mut arms = arms;
        for arm in &mut arms {
            let flange = rig.arm(arm.name).flange_link;
            arm.instrument_bodies = (0..rig.tree.links.len())
                .filter(|&i| on_flange(&rig, i, flange))
                .filter_map(|i| link_bodies[i])
                .collect();
            let prefix = format!("{}_", arm.name);
            arm.jaw_colliders =
                jaw_colliders.iter().filter(|(name, _)| name.starts_with(&prefix)).map(|(_, h)| *h).collect();
        }
        let mut tissue = Tissue::build(&mut physics, &config.tissue, &config.stitch);
        let layout = layout(&config, &tissue, &physics);
        let suture =
            Suture::build(&config, &layout, &mut physics, &mut tissue, &instrument_colliders, arms.len());
        let grip_force_n = config.sensor.grip_force_n;
        Ok(Self {
            physics,
            rig,
            arms,
            suture,
            tissue,
            link_bodies,
            posed_links,
            time_s: 0.0,
            events: Vec::new(),
            config,
            jaw_closed_rad: 0.05,
            grip_force_n,
            noise: ChaCha8Rng::seed_from_u64(0),
        })
    }
}

/// Whether link `i` of `rig` is the flange `flange` or hangs from it (the instrument an arm carries).
fn on_flange(rig: &Rig, i: usize, flange: usize) -> bool {
    i == flange || rig.tree.path_to(i).iter().any(|&j| rig.tree.joints[j].child == flange)
}

fn shape_collider(shape: &knotlab_hw::rig::Shape) -> ColliderBuilder {
    match *shape {
        knotlab_hw::rig::Shape::Box { half_extents_m: h } => ColliderBuilder::cuboid(h.x, h.y, h.z),
        knotlab_hw::rig::Shape::Capsule { radius_m, length_m } => {
            ColliderBuilder::capsule_z(0.5 * length_m, radius_m)
        }
        knotlab_hw::rig::Shape::Sphere { radius_m } => ColliderBuilder::ball(radius_m),
    }
}
