//! Finding a GPU: the wgpu instance, adapter, device and queue the kernel runs on. Kept apart from the
//! kernel so that a test (or a program that already has a device) can hand in its own.

use std::fmt;

use crate::obstacles::error::GpuError;

/// A device to run kernels on.
pub struct GpuContext {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter is.
    pub adapter_info: wgpu::AdapterInfo,
    /// Whether the device can time passes with timestamp queries.
    pub timestamps: bool,
}

impl fmt::Debug for GpuContext {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GpuContext").field("adapter", &self.describe()).finish()
    }
}

impl GpuContext {
    /// The best adapter wgpu finds (high-performance preference: a discrete GPU before an integrated
    /// or software one), on any backend (`WGPU_BACKEND` may narrow them), with its full limits and
    /// timestamp queries when it has them.
    pub fn new() -> Result<Self, GpuError> {
        pollster::block_on(Self::request())
    }

    async fn request() -> Result<Self, GpuError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        };
        let adapter = instance
            .request_adapter(&options)
            .await
            .map_err(|e| GpuError::NoAdapter { reason: e.to_string() })?;
        let info = adapter.get_info();
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("knotlab virtual obstacles"),
            required_features: if timestamps {
                wgpu::Features::TIMESTAMP_QUERY
            } else {
                wgpu::Features::empty()
            },
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) = adapter
            .request_device(&descriptor)
            .await
            .map_err(|e| GpuError::RequestDevice { adapter: describe(&info), reason: e.to_string() })?;
        Ok(Self { device, queue, adapter_info: info, timestamps })
    }

    /// Wraps a device someone else opened (timestamps only if `device` has the feature).
    pub fn from_device(device: wgpu::Device, queue: wgpu::Queue, adapter_info: wgpu::AdapterInfo) -> Self {
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        Self { device, queue, adapter_info, timestamps }
    }

    /// "name (backend, device type)", e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu)`.
    pub fn describe(&self) -> String {
        describe(&self.adapter_info)
    }

    /// Whether the adapter is a CPU emulation (lavapipe, llvmpipe, WARP).
    pub fn is_software(&self) -> bool {
        self.adapter_info.device_type == wgpu::DeviceType::Cpu
    }
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
}
