//! The collision world as plain data: per arm its kinematic model, trocar, current joints and link
//! boxes (each hung on an [`Anchor`]); the fixed boxes of the rig (gantry, table, patient) and the
//! scene's obstacles. Built from a [`Rig`] or by hand.

use nalgebra::{IsometryMatrix3, Vector3};

use knotlab_hw::kinematics::{ArmJoints, ArmModel};
use knotlab_hw::rig::{ArmName, Rig};

use super::error::ObstacleError;
use super::frames::{Anchor, world_from_anchors};
use super::obb::{Obb, bounding_half_extents_m};

/// Boxes of the same arm fewer than this many moving joints apart are never tested against each other:
/// in the box model, neighbouring links, the links packed around the spherical wrist and the jaws
/// around their hinge touch by construction.
pub const MIN_SELF_JOINTS: u8 = 3;

/// One collision box of an arm, fixed on one of its anchors.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkBox {
    /// Where it comes from (URDF link and collision index), for messages.
    pub name: String,
    /// The rigid body it moves with.
    pub anchor: Anchor,
    /// The box's centre frame on its anchor.
    pub anchor_from_box: IsometryMatrix3<f64>,
    /// Half sizes, m.
    pub half_extents_m: Vector3<f64>,
    /// Moving joints between the arm's base and this box (base 0, link i i, shaft 7, wrist 8, clevis 9,
    /// jaws 10): self-collision is tested only between boxes at least [`MIN_SELF_JOINTS`] apart.
    pub depth: u8,
    /// Part of the tool that goes through the trocar into the patient (the shaft side of the shaft base:
    /// instrument shaft, wrist and jaws, the endoscope's tube). Never tested against the patient, whom it
    /// enters by design.
    pub inserted: bool,
}

/// One arm of the collision world.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmBoxes {
    /// Which arm.
    pub name: ArmName,
    /// Its closed-form kinematics.
    pub model: ArmModel,
    /// Its trocar point, world frame, m.
    pub trocar_m: Vector3<f64>,
    /// Its current joints: where it stands when another arm moves, and the IK's seed when it moves.
    pub joints: ArmJoints,
    /// Its collision boxes.
    pub boxes: Vec<LinkBox>,
}

impl ArmBoxes {
    /// Its boxes in the world at `joints`.
    pub fn world_boxes_at(&self, joints: &ArmJoints) -> Vec<Obb> {
        let anchors = world_from_anchors(&self.model, joints);
        self.boxes
            .iter()
            .map(|b| Obb::new(&(anchors[b.anchor.index()] * b.anchor_from_box), b.half_extents_m))
            .collect()
    }

    /// Pairs of its boxes tested for self-collision: at least [`MIN_SELF_JOINTS`] apart.
    pub fn self_pairs(&self) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for (i, a) in self.boxes.iter().enumerate() {
            for (j, b) in self.boxes.iter().enumerate().skip(i + 1) {
                if a.depth.abs_diff(b.depth) >= MIN_SELF_JOINTS {
                    pairs.push((i, j));
                }
            }
        }
        pairs
    }
}

/// What a fixed box stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FixedKind {
    /// The ceiling gantry.
    Gantry,
    /// The operating table.
    Table,
    /// The patient (torso and head): inserted tool parts are not tested against it.
    Patient,
    /// Another fixed part of the rig.
    Rig,
    /// An obstacle of the scene.
    Obstacle,
}

/// A box that never moves.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedBox {
    /// Where it comes from, for messages.
    pub name: String,
    /// What it stands for.
    pub kind: FixedKind,
    /// The box in the world.
    pub obb: Obb,
}

/// Everything an arm can hit.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionWorld {
    /// The arms, each at its current joints.
    pub arms: Vec<ArmBoxes>,
    /// Fixed boxes.
    pub fixed: Vec<FixedBox>,
}

/// An arm's state for [`CollisionWorld::from_rig`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmState {
    /// Which arm.
    pub name: ArmName,
    /// Its trocar point, world frame, m.
    pub trocar_m: Vector3<f64>,
    /// Its current joints.
    pub joints: ArmJoints,
}

impl CollisionWorld {
    /// The rig's collision geometry as boxes (capsules and spheres become their bounding boxes), every
    /// arm of the rig at the joints `states` gives it. Fixed links are classified by name: `gantry`,
    /// `table`, `patient*`; other fixed links are [`FixedKind::Rig`].
    pub fn from_rig(rig: &Rig, states: &[ArmState]) -> Result<Self, ObstacleError> {
        let tree = &rig.tree;
        let mut arms = Vec::new();
        let mut arm_links = vec![false; tree.links.len()];
        for arm in &rig.arms {
            let state =
                states.iter().find(|s| s.name == arm.name).ok_or(ObstacleError::MissingArm(arm.name))?;
            let finite = state.trocar_m.iter().chain(state.joints.to_array().iter()).all(|x| x.is_finite());
            if !finite {
                return Err(ObstacleError::World {
                    what: format!("arm {}", arm.name),
                    reason: "trocar or joints not finite".to_owned(),
                });
            }
            let base = tree.link(&format!("{}_base", arm.name)).ok_or_else(|| ObstacleError::World {
                what: format!("arm {}", arm.name),
                reason: format!("the rig has no link {}_base", arm.name),
            })?;
            let base_joint = tree.links[base].parent_joint;
            let flange_joint = tree.links[arm.flange_link].parent_joint;
            let link_poses = rig.link_poses(arm.name, &state.joints);
            let anchors = world_from_anchors(&arm.model, &state.joints);
            let flange_from_world = link_poses[arm.flange_link].inverse();
            let mut boxes = Vec::new();
            for (l, link) in tree.links.iter().enumerate() {
                let path = tree.path_to(l);
                let under_base = l == base || base_joint.is_some_and(|j| path.contains(&j));
                if !under_base {
                    continue;
                }
                arm_links[l] = true;
                let is_tool = l == arm.flange_link || flange_joint.is_some_and(|j| path.contains(&j));
                // The last of the arm's moving joints on the way to this link decides its anchor.
                let last = path.iter().rev().find_map(|j| arm.tree_joints.iter().position(|t| t == j));
                let (anchor, depth) = match last {
                    None => (Anchor::Base, 0),
                    Some(k @ 0..=5) => (Anchor::Link(k as u8 + 1), k as u8 + 1),
                    Some(6) => (Anchor::Shaft, 7),
                    Some(7) => (Anchor::Wrist, 8),
                    Some(8) => (Anchor::Clevis, 9),
                    Some(_) => (Anchor::Clevis, 10),
                };
                let world_from_anchor = anchors[anchor.index()];
                for (c, shape) in link.collisions.iter().enumerate() {
                    let world_from_box = link_poses[l] * shape.link_from_shape;
                    let inserted = is_tool
                        && (flange_from_world * world_from_box).translation.z > arm.model.tool.coupling_m();
                    boxes.push(LinkBox {
                        name: format!("{} collision {c}", link.name),
                        anchor,
                        anchor_from_box: world_from_anchor.inverse() * world_from_box,
                        half_extents_m: bounding_half_extents_m(&shape.shape),
                        depth,
                        inserted,
                    });
                }
            }
            arms.push(ArmBoxes {
                name: arm.name,
                model: arm.model,
                trocar_m: state.trocar_m,
                joints: state.joints,
                boxes,
            });
        }
        let poses = tree.root_from_links(&vec![0.0; tree.joints.len()]);
        let mut fixed = Vec::new();
        for (l, link) in tree.links.iter().enumerate() {
            if arm_links[l] {
                continue;
            }
            let moving = tree.path_to(l).iter().any(|&j| tree.joints[j].limit.is_some());
            if moving {
                return Err(ObstacleError::World {
                    what: format!("link {}", link.name),
                    reason: "moves but belongs to no arm".to_owned(),
                });
            }
            let kind = match link.name.as_str() {
                "gantry" => FixedKind::Gantry,
                "table" => FixedKind::Table,
                n if n.starts_with("patient") => FixedKind::Patient,
                _ => FixedKind::Rig,
            };
            for (c, shape) in link.collisions.iter().enumerate() {
                fixed.push(FixedBox {
                    name: format!("{} collision {c}", link.name),
                    kind,
                    obb: Obb::new(&(poses[l] * shape.link_from_shape), bounding_half_extents_m(&shape.shape)),
                });
            }
        }
        Ok(Self { arms, fixed })
    }

    /// Adds an obstacle: a box along the world axes.
    pub fn add_obstacle(
        &mut self,
        name: &str,
        centre_m: Vector3<f64>,
        half_extents_m: Vector3<f64>,
    ) -> Result<(), ObstacleError> {
        let finite = centre_m.iter().chain(half_extents_m.iter()).all(|x| x.is_finite());
        if !finite || half_extents_m.iter().any(|h| *h <= 0.0) {
            return Err(ObstacleError::World {
                what: name.to_owned(),
                reason: format!(
                    "centre must be finite and half extents positive, got {centre_m:?} and {half_extents_m:?}"
                ),
            });
        }
        let pose = IsometryMatrix3::translation(centre_m.x, centre_m.y, centre_m.z);
        self.fixed.push(FixedBox {
            name: name.to_owned(),
            kind: FixedKind::Obstacle,
            obb: Obb::new(&pose, half_extents_m),
        });
        Ok(())
    }

    /// One arm.
    pub fn arm(&self, name: ArmName) -> Result<&ArmBoxes, ObstacleError> {
        self.arms.iter().find(|a| a.name == name).ok_or(ObstacleError::MissingArm(name))
    }
}
