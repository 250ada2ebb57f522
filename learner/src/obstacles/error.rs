//! Why a virtual-obstacle grid cannot be computed.

use knotlab_hw::rig::ArmName;

/// Why a grid request or a collision world is refused.
#[derive(Debug, thiserror::Error)]
pub enum ObstacleError {
    /// The grid's plane is malformed.
    #[error("grid plane: {field}: {reason}")]
    Plane {
        /// The offending field (`origin`, `axis_u`, `axis_v`, `size`, `cells`, `subcells`).
        field: &'static str,
        /// What is wrong with it.
        reason: String,
    },
    /// The tip orientation asked for cannot be used with this arm.
    #[error("tip orientation for the {arm} arm: {reason}")]
    Orientation {
        /// The arm.
        arm: ArmName,
        /// Why.
        reason: String,
    },
    /// The collision world has no such arm.
    #[error("the collision world has no {0} arm")]
    MissingArm(ArmName),
    /// A box of the collision world is malformed.
    #[error("collision world: {what}: {reason}")]
    World {
        /// Which box.
        what: String,
        /// Why.
        reason: String,
    },
    /// The CPU backend's thread pool could not be built.
    #[error("a pool of {threads} threads: {reason}")]
    ThreadPool {
        /// Threads asked for.
        threads: usize,
        /// What rayon said.
        reason: String,
    },
    /// The GPU backend failed (or none is available).
    #[cfg(feature = "gpu")]
    #[error(transparent)]
    Gpu(#[from] super::gpu::GpuError),
}
