//! What a virtual-obstacle grid is asked for: which arm's tip moves, over which grid, held how.

use nalgebra::Vector3;

use knotlab_hw::rig::ArmName;

use super::plane::GridPlane;

/// How the tip is held at every subcell (the inverse kinematics needs an orientation as well as a
/// position).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SubcellOrientation {
    /// Jaws along the line from the trocar to the tip: a straight wrist, the instrument's most
    /// retracted posture, and the endoscope's only one. The default: a 2D primitive moves the tip in
    /// the plane and its jaw direction is not part of it.
    AlongShaft,
    /// Jaws pointing this way (world frame, need not be unit length) at every subcell, the rotation
    /// about it chosen by the solver: for a primitive that keeps a fixed jaw direction while it moves.
    /// Instruments only.
    JawDirection(Vector3<f64>),
}

/// One grid to compute.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridRequest {
    /// The arm whose tip moves over the grid; every other arm stays at its current joints.
    pub arm: ArmName,
    /// The grid.
    pub plane: GridPlane,
    /// The tip's orientation at every subcell.
    pub orientation: SubcellOrientation,
}
