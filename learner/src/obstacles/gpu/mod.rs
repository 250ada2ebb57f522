//! The GPU backend (feature `gpu`): a wgpu compute shader in WGSL, one invocation per subcell, doing
//! the CPU backend's work in f32: the same closed-form trocar IK (ported from `hw`), forward kinematics
//! and oriented-box tests. Runs on whatever adapter wgpu finds, Mesa's software Vulkan (lavapipe)
//! included; with none, [`GpuContext::new`] says so and the CPU backend serves.
//!
//! Device setup ([`device`]) is apart from the kernel ([`kernel`]) so that tests can hand in their own
//! device; the buffers' layout is in [`buffers`].

pub mod buffers;
pub mod device;
pub mod kernel;

pub use super::error::GpuError;
pub use device::GpuContext;
pub use kernel::{GpuJob, GpuKernel, GpuReadback, GpuTimings, compute_gpu};
