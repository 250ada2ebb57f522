//! Why a virtual-obstacle grid cannot be computed, on the CPU or the GPU.

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
    Gpu(#[from] GpuError),
}

#[cfg(feature = "gpu")]
/// Why the GPU backend cannot run.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// wgpu found no adapter at all (no Vulkan, Metal, DX12 or GL driver, not even a software one).
    #[error(
        "no GPU adapter found ({reason}); on Linux install Mesa's software Vulkan driver \
         (apt-get install mesa-vulkan-drivers libvulkan1) or use the CPU backend"
    )]
    NoAdapter {
        /// What wgpu said.
        reason: String,
    },
    /// The adapter refused to give a device.
    #[error("GPU adapter {adapter}: cannot open a device: {reason}")]
    RequestDevice {
        /// The adapter.
        adapter: String,
        /// What wgpu said.
        reason: String,
    },
    /// The kernel did not compile or validate on this device.
    #[error("GPU kernel rejected by {adapter}: {reason}")]
    Kernel {
        /// The adapter.
        adapter: String,
        /// What wgpu said.
        reason: String,
    },
    /// Running the kernel or reading its results failed.
    #[error("GPU run failed: {0}")]
    Run(String),
    /// The grid does not fit the device's limits.
    #[error("grid too large for the GPU: {0}")]
    TooLarge(String),
}
