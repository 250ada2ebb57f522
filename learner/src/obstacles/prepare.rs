//! A grid request turned into flat data both backends share: the moving arm's kinematics and boxes on
//! their anchors, its self-collision pairs, and the environment as world boxes in broad-phase groups.

use nalgebra::{IsometryMatrix3, Vector3};

use knotlab_hw::kinematics::{ArmJoints, ArmModel, TipOrientation, Tool};

use super::error::ObstacleError;
use super::frames::{ANCHORS, AnchorKinematics};
use super::obb::Obb;
use super::request::{GridRequest, SubcellOrientation};
use super::world::{CollisionWorld, FixedKind};

/// Most boxes the moving arm may have (the shipped rig's instruments have 15).
pub const MAX_MOVING_BOXES: usize = 32;

/// A box of the moving arm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MovingBox {
    /// Index of its anchor (see [`super::frames::Anchor::index`]).
    pub anchor: usize,
    /// Its centre frame on the anchor.
    pub anchor_from_box: IsometryMatrix3<f64>,
    /// Half sizes, m.
    pub half_extents_m: Vector3<f64>,
    /// Bounding-sphere radius, m.
    pub radius_m: f64,
    /// Whether it is tested against the environment (the base hangs fixed: it is only in self pairs).
    pub tests_environment: bool,
    /// Whether it goes into the patient (then not tested against the patient).
    pub inserted: bool,
}

/// A box of the environment, in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnvBox {
    /// The box.
    pub obb: Obb,
    /// Bounding-sphere radius, m.
    pub radius_m: f64,
    /// Whether it is the patient.
    pub patient: bool,
}

/// Environment boxes `start..end` and a sphere that holds them all: another arm, or one fixed box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxGroup {
    /// Sphere centre, world frame, m.
    pub centre_m: Vector3<f64>,
    /// Sphere radius, m.
    pub radius_m: f64,
    /// First box.
    pub start: usize,
    /// One past the last box.
    pub end: usize,
}

/// A request ready to evaluate.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedGrid {
    /// What was asked.
    pub request: GridRequest,
    /// The moving arm's kinematics.
    pub model: ArmModel,
    /// Its trocar, world frame, m.
    pub trocar_m: Vector3<f64>,
    /// Its current joints: every subcell's IK starts from them (nearest solution to them).
    pub current: ArmJoints,
    /// The tip orientation handed to the IK.
    pub orientation: TipOrientation,
    /// For an instrument held along its shaft: the current tip's yaw axis (world frame), from which
    /// each subcell's yaw axis is derived as `hw`'s solver does (see [`PreparedGrid::solve`]).
    pub current_yaw_axis: Option<Vector3<f64>>,
    /// The moving arm's forward kinematics to its anchors.
    pub kinematics: AnchorKinematics,
    /// The moving arm's boxes.
    pub moving: Vec<MovingBox>,
    /// Its self-collision pairs (indices into `moving`).
    pub self_pairs: Vec<(usize, usize)>,
    /// The environment: other arms at their current joints, fixed boxes, obstacles.
    pub environment: Vec<EnvBox>,
    /// Broad-phase groups over `environment`.
    pub groups: Vec<BoxGroup>,
}

fn group_of(boxes: &[EnvBox], start: usize) -> BoxGroup {
    let members = &boxes[start..];
    let centre_m = members.iter().map(|b| b.obb.centre_m).sum::<Vector3<f64>>() / members.len().max(1) as f64;
    let radius_m =
        members.iter().map(|b| (b.obb.centre_m - centre_m).norm() + b.radius_m).fold(0.0, f64::max);
    BoxGroup { centre_m, radius_m, start, end: boxes.len() }
}

impl PreparedGrid {
    /// Flattens `world` for `request`.
    pub fn new(world: &CollisionWorld, request: &GridRequest) -> Result<Self, ObstacleError> {
        let arm = world.arm(request.arm)?;
        let orientation = match request.orientation {
            SubcellOrientation::AlongShaft => TipOrientation::AlongShaft,
            SubcellOrientation::JawDirection(direction) => {
                if matches!(arm.model.tool, Tool::Endoscope { .. }) {
                    return Err(ObstacleError::Orientation {
                        arm: request.arm,
                        reason: "the endoscope looks along its shaft: only along-shaft is possible"
                            .to_owned(),
                    });
                }
                let n = direction.norm();
                if !(n.is_finite() && n > 1e-9) {
                    return Err(ObstacleError::Orientation {
                        arm: request.arm,
                        reason: format!("jaw direction must be finite and not zero, got {direction:?}"),
                    });
                }
                TipOrientation::JawDirection(direction / n)
            }
        };
        if arm.boxes.len() > MAX_MOVING_BOXES {
            return Err(ObstacleError::World {
                what: format!("arm {}", arm.name),
                reason: format!("{} boxes, more than the {MAX_MOVING_BOXES} supported", arm.boxes.len()),
            });
        }
        let current_yaw_axis = match (orientation, &arm.model.tool) {
            (TipOrientation::AlongShaft, Tool::Instrument { .. }) => {
                Some(arm.model.world_from_tip(&arm.joints).rotation * Vector3::y())
            }
            _ => None,
        };
        let moving = arm
            .boxes
            .iter()
            .map(|b| MovingBox {
                anchor: b.anchor.index().min(ANCHORS - 1),
                anchor_from_box: b.anchor_from_box,
                half_extents_m: b.half_extents_m,
                radius_m: b.half_extents_m.norm(),
                tests_environment: b.depth > 0,
                inserted: b.inserted,
            })
            .collect();
        let mut environment = Vec::new();
        let mut groups = Vec::new();
        for other in world.arms.iter().filter(|a| a.name != request.arm) {
            let start = environment.len();
            for obb in other.world_boxes_at(&other.joints) {
                environment.push(EnvBox { obb, radius_m: obb.bounding_radius_m(), patient: false });
            }
            if environment.len() > start {
                groups.push(group_of(&environment, start));
            }
        }
        for fixed in &world.fixed {
            let start = environment.len();
            environment.push(EnvBox {
                obb: fixed.obb,
                radius_m: fixed.obb.bounding_radius_m(),
                patient: fixed.kind == FixedKind::Patient,
            });
            groups.push(group_of(&environment, start));
        }
        Ok(Self {
            request: *request,
            model: arm.model,
            trocar_m: arm.trocar_m,
            current: arm.joints,
            orientation,
            current_yaw_axis,
            kinematics: AnchorKinematics::new(&arm.model),
            moving,
            self_pairs: arm.self_pairs(),
            environment,
            groups,
        })
    }
}
