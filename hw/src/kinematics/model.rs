//! One arm as the kinematics sees it: where it hangs, its RV-6SL geometry and limits, and its tool.

use nalgebra::{IsometryMatrix3, Vector3};

use super::joints::ArmJoints;
use super::limits::JointLimit;
use super::rv6sl::Rv6slGeometry;
use super::tool::Tool;

/// The kinematic model of one arm and its tool. Cheap to copy; holds no heap memory.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmModel {
    /// The arm's base frame in the world (upside down: its z points at the floor).
    pub world_from_base: IsometryMatrix3<f64>,
    /// The inverse of `world_from_base`, kept to spare the solver an inversion.
    pub base_from_world: IsometryMatrix3<f64>,
    /// Link lengths.
    pub geometry: Rv6slGeometry,
    /// Limits of axes 1..=6.
    pub limits: [JointLimit; 6],
    /// The tool on the flange.
    pub tool: Tool,
}

/// The shaft's axis: the line the trocar must lie on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShaftAxis {
    /// The shaft base, world frame, m.
    pub origin_m: Vector3<f64>,
    /// Unit direction from the shaft base towards the tip.
    pub direction: Vector3<f64>,
}

impl ShaftAxis {
    /// Distance of a point from the (infinite) axis, m.
    pub fn distance_m(&self, point_m: &Vector3<f64>) -> f64 {
        (point_m - self.origin_m).cross(&self.direction).norm()
    }
}

impl ArmModel {
    /// A model from its parts.
    pub fn new(
        world_from_base: IsometryMatrix3<f64>,
        geometry: Rv6slGeometry,
        limits: [JointLimit; 6],
        tool: Tool,
    ) -> Self {
        Self { world_from_base, base_from_world: world_from_base.inverse(), geometry, limits, tool }
    }

    /// The flange in the world.
    pub fn world_from_flange(&self, joints: &ArmJoints) -> IsometryMatrix3<f64> {
        self.world_from_base * self.geometry.base_from_flange(&joints.arm_rad)
    }

    /// The tool tip in the world (closed form).
    pub fn world_from_tip(&self, joints: &ArmJoints) -> IsometryMatrix3<f64> {
        self.world_from_flange(joints) * self.tool.flange_from_tip(&joints.tool)
    }

    /// The shaft axis in the world.
    pub fn shaft_axis(&self, joints: &ArmJoints) -> ShaftAxis {
        let flange = self.world_from_flange(joints);
        let direction = flange.rotation * Vector3::z();
        ShaftAxis { origin_m: flange.translation.vector + direction * self.tool.coupling_m(), direction }
    }
}
