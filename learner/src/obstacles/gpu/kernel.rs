//! The compute kernel (`virtual_obstacles.wgsl`, one invocation per subcell) and running it: upload a
//! packed grid, dispatch, read the verdicts back, each step timed.

use std::sync::mpsc;
use std::time::Instant;

use wgpu::util::DeviceExt;

use crate::obstacles::check::SubcellVerdict;
use crate::obstacles::grid::{CellVerdict, GridResult};
use crate::obstacles::plane::GridPlane;
use crate::obstacles::prepare::PreparedGrid;

use super::buffers::{MAX_GPU_ENV_BOXES, pack};
use super::device::GpuContext;
use crate::obstacles::error::GpuError;

/// The WGSL source.
pub const SHADER: &str = include_str!("virtual_obstacles.wgsl");

/// Invocations per workgroup (`@workgroup_size` in the WGSL).
const WORKGROUP: u32 = 64;

/// Cell bits the kernel sets: a subcell collides, a subcell is unreachable.
const CELL_COLLIDES: u32 = 1;
const CELL_UNREACHABLE: u32 = 2;

/// The compiled kernel on one device.
pub struct GpuKernel {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// How long a GPU grid took, ms.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuTimings {
    /// Packing the grid and uploading it (buffers created, data written and flushed).
    pub upload_ms: f64,
    /// Dispatch to completion, as the host sees it (submit, run, wait).
    pub kernel_ms: f64,
    /// The compute pass alone, by GPU timestamps, when the device has them.
    pub kernel_gpu_ms: Option<f64>,
    /// Copying the results back and decoding them.
    pub readback_ms: f64,
}

impl GpuTimings {
    /// Upload, kernel and readback together.
    pub fn total_ms(&self) -> f64 {
        self.upload_ms + self.kernel_ms + self.readback_ms
    }
}

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

fn wait(ctx: &GpuContext) -> Result<(), GpuError> {
    ctx.device.poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).map_err(|e| GpuError::Run(e.to_string()))
}

/// Reads a `MAP_READ` buffer whole.
fn read_buffer(ctx: &GpuContext, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let (tx, rx) = mpsc::channel();
    buffer.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ignored = tx.send(r);
    });
    wait(ctx)?;
    rx.recv()
        .map_err(|e| GpuError::Run(e.to_string()))?
        .map_err(|e| GpuError::Run(format!("mapping the results: {e}")))?;
    let bytes = buffer.get_mapped_range(..).map_err(|e| GpuError::Run(e.to_string()))?.to_vec();
    buffer.unmap();
    Ok(bytes)
}

fn words(bytes: &[u8]) -> Vec<u32> {
    bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect()
}

impl GpuKernel {
    /// Compiles the kernel on `ctx`'s device.
    pub fn new(ctx: &GpuContext) -> Result<Self, GpuError> {
        let device = &ctx.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("virtual_obstacles.wgsl"),
            source: wgpu::ShaderSource::Wgsl(SHADER.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("virtual obstacles"),
            layout: None,
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Kernel { adapter: ctx.describe(), reason: error.to_string() });
        }
        let layout = pipeline.get_bind_group_layout(0);
        Ok(Self { pipeline, layout })
    }

    /// Packs and uploads a grid: a job ready to dispatch.
    pub fn upload(&self, ctx: &GpuContext, grid: &PreparedGrid) -> Result<GpuJob, GpuError> {
        let start = Instant::now();
        let plane = grid.request.plane;
        let subcells = plane.subcell_count();
        let n_cells = plane.cells * plane.cells;
        let groups = subcells.div_ceil(WORKGROUP as usize);
        let limits = ctx.device.limits();
        if groups > limits.max_compute_workgroups_per_dimension as usize {
            return Err(GpuError::TooLarge(format!(
                "{subcells} subcells need {groups} workgroups, the device allows {}",
                limits.max_compute_workgroups_per_dimension
            )));
        }
        let subcell_bytes = 4 * subcells as u64;
        if subcell_bytes > limits.max_storage_buffer_binding_size {
            return Err(GpuError::TooLarge(format!(
                "{subcell_bytes} bytes of subcell verdicts, the device binds at most {}",
                limits.max_storage_buffer_binding_size
            )));
        }
        if grid.environment.len() > MAX_GPU_ENV_BOXES {
            return Err(GpuError::TooLarge(format!(
                "{} environment boxes, the kernel takes at most {MAX_GPU_ENV_BOXES}",
                grid.environment.len()
            )));
        }
        let packed = pack(grid);
        let device = &ctx.device;
        // Validation errors become a GpuError instead of wgpu's default panic.
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let init = |label: &str, contents: &[u8], usage: wgpu::BufferUsages| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let params = init("params", bytemuck::bytes_of(&packed.params), storage);
        let moving = init("moving boxes", bytemuck::cast_slice(&packed.moving), storage);
        let environment = init("environment boxes", bytemuck::cast_slice(&packed.environment), storage);
        let pairs = init("self pairs", bytemuck::cast_slice(&packed.pairs), storage);
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let out = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST;
        let read = wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST;
        // One word per cell, then the count of reachable subcells.
        let cell_bytes = 4 * (n_cells as u64 + 1);
        let subcell_out = buffer("subcell verdicts", subcell_bytes, out);
        let cell_out = buffer("cell verdicts", cell_bytes, out);
        let subcell_read = buffer("subcell readback", subcell_bytes, read);
        let cell_read = buffer("cell readback", cell_bytes, read);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("virtual obstacles"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry { binding: 0, resource: params.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: moving.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 2, resource: environment.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 3, resource: pairs.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 4, resource: subcell_out.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 5, resource: cell_out.as_entire_binding() },
            ],
        });
        let timestamps = ctx.timestamps.then(|| {
            let set = device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("kernel timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve =
                buffer("timestamps", 16, wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
            let read = buffer("timestamp readback", 16, read);
            (set, resolve, read)
        });
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Run(format!("uploading the grid: {error}")));
        }
        // Flush the uploads so that the dispatch times the kernel alone.
        ctx.queue.submit([]);
        wait(ctx)?;
        Ok(GpuJob {
            plane,
            workgroups: groups as u32,
            bind_group,
            subcell_out,
            cell_out,
            subcell_read,
            cell_read,
            timestamps,
            upload_ms: ms(start),
            _inputs: [params, moving, environment, pairs],
        })
    }
}

/// What a run read back.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuReadback {
    /// Each cell's verdict, row-major.
    pub cells: Vec<CellVerdict>,
    /// Every subcell's verdict, fine-grid row-major, when asked for.
    pub subcells: Option<Vec<SubcellVerdict>>,
    /// Subcells the IK reached (and the boxes were tested at).
    pub reachable: usize,
}

/// A grid uploaded to the device: dispatch it (again and again, for timing), then read it.
pub struct GpuJob {
    plane: GridPlane,
    workgroups: u32,
    bind_group: wgpu::BindGroup,
    subcell_out: wgpu::Buffer,
    cell_out: wgpu::Buffer,
    subcell_read: wgpu::Buffer,
    cell_read: wgpu::Buffer,
    timestamps: Option<(wgpu::QuerySet, wgpu::Buffer, wgpu::Buffer)>,
    /// Packing and uploading took this long, ms.
    pub upload_ms: f64,
    _inputs: [wgpu::Buffer; 4],
}

impl GpuJob {
    /// Clears the cells, runs the kernel and waits for it: (host-side ms, GPU-timestamp ms if any).
    pub fn dispatch(&self, ctx: &GpuContext, kernel: &GpuKernel) -> Result<(f64, Option<f64>), GpuError> {
        let start = Instant::now();
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        encoder.clear_buffer(&self.cell_out, 0, None);
        {
            let timestamp_writes =
                self.timestamps.as_ref().map(|(set, _, _)| wgpu::ComputePassTimestampWrites {
                    query_set: set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                });
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("virtual obstacles"),
                timestamp_writes,
            });
            pass.set_pipeline(&kernel.pipeline);
            pass.set_bind_group(0, &self.bind_group, &[]);
            pass.dispatch_workgroups(self.workgroups, 1, 1);
        }
        if let Some((set, resolve, read)) = &self.timestamps {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, read, 0, 16);
        }
        ctx.queue.submit([encoder.finish()]);
        wait(ctx)?;
        let host_ms = ms(start);
        let gpu_ms = match &self.timestamps {
            Some((_, _, read)) => {
                let ticks = words(&read_buffer(ctx, read)?);
                let t = |i: usize| u64::from(ticks[2 * i]) | (u64::from(ticks[2 * i + 1]) << 32);
                let period_ns = f64::from(ctx.queue.get_timestamp_period());
                Some(t(1).saturating_sub(t(0)) as f64 * period_ns * 1e-6)
            }
            None => None,
        };
        Ok((host_ms, gpu_ms))
    }

    /// Copies the verdicts back: each cell's, every subcell's when `keep_subcells`, and the number of
    /// reachable subcells.
    pub fn read(&self, ctx: &GpuContext, keep_subcells: bool) -> Result<GpuReadback, GpuError> {
        let mut encoder = ctx.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        encoder.copy_buffer_to_buffer(&self.cell_out, 0, &self.cell_read, 0, None);
        if keep_subcells {
            encoder.copy_buffer_to_buffer(&self.subcell_out, 0, &self.subcell_read, 0, None);
        }
        ctx.queue.submit([encoder.finish()]);
        let cell_words = words(&read_buffer(ctx, &self.cell_read)?);
        let n_cells = self.plane.cells * self.plane.cells;
        let reachable = cell_words.get(n_cells).copied().unwrap_or(0) as usize;
        let cells = cell_words[..n_cells.min(cell_words.len())]
            .iter()
            .map(|bits| {
                if bits & CELL_UNREACHABLE != 0 {
                    CellVerdict::Unreachable
                } else if bits & CELL_COLLIDES != 0 {
                    CellVerdict::Collides
                } else {
                    CellVerdict::Free
                }
            })
            .collect();
        let subcells = if keep_subcells {
            let codes = words(&read_buffer(ctx, &self.subcell_read)?);
            Some(codes.into_iter().map(SubcellVerdict::from_code).collect())
        } else {
            None
        };
        Ok(GpuReadback { cells, subcells, reachable })
    }
}

/// Computes a grid on the GPU: upload, dispatch, read back; the result and how long each step took.
pub fn compute_gpu(
    ctx: &GpuContext,
    kernel: &GpuKernel,
    grid: &PreparedGrid,
    keep_subcells: bool,
) -> Result<(GridResult, GpuTimings), GpuError> {
    let job = kernel.upload(ctx, grid)?;
    let (kernel_ms, kernel_gpu_ms) = job.dispatch(ctx, kernel)?;
    let start = Instant::now();
    let back = job.read(ctx, keep_subcells)?;
    let readback_ms = ms(start);
    let result = GridResult::new(grid.request.plane, back.cells, back.subcells, back.reachable);
    Ok((result, GpuTimings { upload_ms: job.upload_ms, kernel_ms, kernel_gpu_ms, readback_ms }))
}
