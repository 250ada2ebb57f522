//! Why an inverse-kinematics request has no solution. `Copy` and allocation-free, like the solver.

use super::limits::JointId;

/// Why a target cannot be reached.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum IkError {
    /// A coordinate of the target, jaw direction or trocar is NaN or infinite.
    #[error("the target, jaw direction or trocar is not finite")]
    NonFiniteTarget,
    /// The jaw direction is zero or not perpendicular-able (zero length).
    #[error("the jaw direction has zero length")]
    ZeroJawDirection,
    /// The point that fixes the shaft (tip, or wrist pitch axis) is too close to the trocar.
    #[error("{what} is {distance_m:.6} m from the trocar, closer than the {min_m} m allowed")]
    TooCloseToTrocar {
        /// Which point: "tip" or "wrist pitch axis".
        what: &'static str,
        /// Its distance from the trocar, m.
        distance_m: f64,
        /// The smallest allowed distance, m.
        min_m: f64,
    },
    /// The shaft would have to go deeper through the trocar than the tool allows.
    #[error("insertion depth {depth_m:.4} m beyond the tool's maximum {max_m} m")]
    InsertionTooDeep {
        /// Needed insertion, m.
        depth_m: f64,
        /// The tool's maximum, m.
        max_m: f64,
    },
    /// The wrist cannot be oriented: the yaw axis points at the trocar.
    #[error("jaw orientation impossible: the wrist yaw axis points through the trocar")]
    WristAxisThroughTrocar,
    /// The endoscope has no wrist: only its tip position can be commanded.
    #[error("the endoscope's orientation follows its shaft; a jaw direction cannot be commanded")]
    OrientationNotControllable,
    /// The arm's wrist centre lies beyond the arm's reach.
    #[error(
        "the arm's wrist centre is {distance_m:.4} m from the shoulder; reachable {min_m:.4}..{max_m:.4} m"
    )]
    OutOfReach {
        /// Shoulder-to-wrist-centre distance needed, m.
        distance_m: f64,
        /// Shortest reachable distance, m.
        min_m: f64,
        /// Longest reachable distance, m.
        max_m: f64,
    },
    /// No arm branch was found and no more specific reason recorded (a safety net: every path the
    /// solver knows records a reason first).
    #[error("no arm configuration reaches the flange pose")]
    NoBranch,
    /// Geometric solutions exist, but each puts some joint outside its limits; this is the least bad.
    #[error("{joint} would be at {value_rad:.4} rad, outside its limits {lower_rad:.4}..{upper_rad:.4} rad")]
    JointLimit {
        /// The joint.
        joint: JointId,
        /// The angle it would need, rad.
        value_rad: f64,
        /// Its lower limit, rad.
        lower_rad: f64,
        /// Its upper limit, rad.
        upper_rad: f64,
    },
}
