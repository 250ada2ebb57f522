//! The kernel's buffers as `#[repr(C)]` structs, every field a 16-byte vector so the layout is the
//! same in Rust and WGSL (see `virtual_obstacles.wgsl`), and their packing from a [`PreparedGrid`]
//! (f64 to f32). All are storage buffers, the parameters included: lavapipe specialises a kernel on
//! uniform values that steer control flow and compiled a new variant, for seconds, for every grid.

use bytemuck::{Pod, Zeroable};
use nalgebra::{IsometryMatrix3, Vector3};

use knotlab_hw::kinematics::{TipOrientation, Tool};

use crate::obstacles::prepare::PreparedGrid;

/// The kernel's parameters (`Params` in the WGSL).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuParams {
    /// Corner of cell (0, 0) (xyz) and the subcell size (w), m.
    pub origin: [f32; 4],
    /// First in-plane axis.
    pub axis_u: [f32; 4],
    /// Second in-plane axis.
    pub axis_v: [f32; 4],
    /// Subcells per side (n s), subcells per cell side (s), cells per side (n), subcells in all.
    pub grid: [u32; 4],
    /// Moving boxes, environment boxes, padding, self pairs.
    pub counts: [u32; 4],
    /// Tool (0 instrument, 1 endoscope), orientation (0 along shaft, 1 jaw direction), padding.
    pub mode: [u32; 4],
    /// The moving arm's base in the world: rotation rows with the translation in w.
    pub world_from_base: [[f32; 4]; 3],
    /// Its inverse.
    pub base_from_world: [[f32; 4]; 3],
    /// The DH rows: d, theta offset, a, alpha.
    pub dh: [[f32; 4]; 6],
    /// (d1, a1, a2, a3), (d4, d6, forearm, gamma), (sin gamma, cos gamma, padding).
    pub geometry: [[f32; 4]; 3],
    /// (lower, upper, padding) of axes 1-6, roll, pitch, yaw.
    pub limits: [[f32; 4]; 9],
    /// (coupling, shaft, wrist, jaw), (max insertion, min trocar distance, padding), m.
    pub tool: [[f32; 4]; 2],
    /// The trocar, m.
    pub trocar: [f32; 4],
    /// Current joints: (q1, q2, q3, q4), (q5, q6, roll, pitch), (yaw, jaw, padding).
    pub current: [[f32; 4]; 3],
    /// The current tip's yaw axis (instruments).
    pub yaw_now: [f32; 4],
    /// The asked jaw direction.
    pub jaw_dir: [f32; 4],
}

/// A box: on its anchor (moving arm) or in the world (environment). `GpuBox` in the WGSL.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuBox {
    /// Rotation rows with the translation in w.
    pub rows: [[f32; 4]; 3],
    /// Half extents and the bounding-sphere radius, m.
    pub half: [f32; 4],
    /// Anchor index, flags (1: tests the environment, or is the patient; 2: inserted), padding.
    pub info: [u32; 4],
}

/// Everything the kernel reads, packed.
#[derive(Clone, Debug)]
pub struct PackedGrid {
    /// Uniform parameters.
    pub params: GpuParams,
    /// The moving arm's boxes (at least one element: a zero-size binding is not allowed).
    pub moving: Vec<GpuBox>,
    /// The environment's boxes (likewise).
    pub environment: Vec<GpuBox>,
    /// Self pairs (a, b, padding) (likewise).
    pub pairs: Vec<[u32; 4]>,
}

/// Most environment boxes the kernel takes (its per-workgroup candidate bits: 8 words per moving box).
pub const MAX_GPU_ENV_BOXES: usize = 256;

/// Added to every bounding-sphere radius on the GPU so that f32 rounding never culls a pair the f64
/// CPU would test: the spheres only cull, the separating-axis test decides, so this changes no verdict.
const SPHERE_SLACK_M: f64 = 1e-5;

fn v4(v: &Vector3<f64>, w: f64) -> [f32; 4] {
    [v.x as f32, v.y as f32, v.z as f32, w as f32]
}

fn rows(iso: &IsometryMatrix3<f64>) -> [[f32; 4]; 3] {
    let r = iso.rotation.matrix();
    let t = iso.translation.vector;
    std::array::from_fn(|i| [r[(i, 0)] as f32, r[(i, 1)] as f32, r[(i, 2)] as f32, t[i] as f32])
}

/// `v`, with one zero element if empty: a zero-size binding is not allowed.
fn non_empty<T: Zeroable>(mut v: Vec<T>) -> Vec<T> {
    if v.is_empty() {
        v.push(T::zeroed());
    }
    v
}

fn count(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Packs a prepared grid for the kernel.
pub fn pack(grid: &PreparedGrid) -> PackedGrid {
    let plane = &grid.request.plane;
    let model = &grid.model;
    let g = &model.geometry;
    let l3 = g.forearm_m();
    let (tool, endoscope) = match &model.tool {
        Tool::Instrument { geometry, .. } => (
            [
                [geometry.coupling_m, geometry.shaft_m, geometry.wrist_m, geometry.jaw_m],
                [geometry.max_insertion_m, knotlab_hw::kinematics::tool::MIN_TROCAR_DISTANCE_M, 0.0, 0.0],
            ],
            false,
        ),
        Tool::Endoscope { geometry } => (
            [
                [geometry.coupling_m, geometry.shaft_m, 0.0, 0.0],
                [geometry.max_insertion_m, knotlab_hw::kinematics::tool::MIN_TROCAR_DISTANCE_M, 0.0, 0.0],
            ],
            true,
        ),
    };
    let mut limits = [[0.0_f32; 4]; 9];
    for (k, l) in model.limits.iter().enumerate() {
        limits[k] = [l.lower_rad as f32, l.upper_rad as f32, 0.0, 0.0];
    }
    if let Tool::Instrument { limits: tl, .. } = &model.tool {
        for (k, l) in [tl.roll, tl.pitch, tl.yaw].iter().enumerate() {
            limits[6 + k] = [l.lower_rad as f32, l.upper_rad as f32, 0.0, 0.0];
        }
    }
    let (orientation, jaw_dir) = match grid.orientation {
        TipOrientation::JawDirection(d) => (1, v4(&d, 0.0)),
        _ => (0, [0.0; 4]),
    };
    let yaw_now = match &model.tool {
        Tool::Instrument { .. } => model.world_from_tip(&grid.current).rotation * Vector3::y(),
        Tool::Endoscope { .. } => Vector3::zeros(),
    };
    let c = grid.current.to_array().map(|q| q as f32);
    let params = GpuParams {
        origin: v4(&plane.origin_m, plane.subcell_size_m()),
        axis_u: v4(&plane.axis_u, 0.0),
        axis_v: v4(&plane.axis_v, 0.0),
        grid: [count(plane.side()), count(plane.subcells), count(plane.cells), count(plane.subcell_count())],
        counts: [count(grid.moving.len()), count(grid.environment.len()), 0, count(grid.self_pairs.len())],
        mode: [u32::from(endoscope), orientation, 0, 0],
        world_from_base: rows(&model.world_from_base),
        base_from_world: rows(&model.base_from_world),
        dh: g.rows().map(|r| [r.d_m as f32, r.theta_offset_rad as f32, r.a_m as f32, r.alpha_rad as f32]),
        geometry: [
            [g.d1_m as f32, g.a1_m as f32, g.a2_m as f32, g.a3_m as f32],
            [g.d4_m as f32, g.d6_m as f32, l3 as f32, g.a3_m.atan2(g.d4_m) as f32],
            [(g.a3_m / l3) as f32, (g.d4_m / l3) as f32, 0.0, 0.0],
        ],
        limits,
        tool: tool.map(|row| row.map(|x| x as f32)),
        trocar: v4(&grid.trocar_m, 0.0),
        current: [[c[0], c[1], c[2], c[3]], [c[4], c[5], c[6], c[7]], [c[8], c[9], 0.0, 0.0]],
        yaw_now: v4(&yaw_now, 0.0),
        jaw_dir,
    };
    let moving = grid
        .moving
        .iter()
        .map(|m| GpuBox {
            rows: rows(&m.anchor_from_box),
            half: v4(&m.half_extents_m, m.radius_m + SPHERE_SLACK_M),
            info: [count(m.anchor), u32::from(m.tests_environment) | (u32::from(m.inserted) << 1), 0, 0],
        })
        .collect();
    let environment = grid
        .environment
        .iter()
        .map(|e| {
            let pose = IsometryMatrix3::from_parts(
                e.obb.centre_m.into(),
                nalgebra::Rotation3::from_matrix_unchecked(e.obb.rotation),
            );
            GpuBox {
                rows: rows(&pose),
                half: v4(&e.obb.half_extents_m, e.radius_m + SPHERE_SLACK_M),
                info: [0, u32::from(e.patient), 0, 0],
            }
        })
        .collect();
    let pairs = grid.self_pairs.iter().map(|&(a, b)| [count(a), count(b), 0, 0]).collect();
    PackedGrid {
        params,
        moving: non_empty(moving),
        environment: non_empty(environment),
        pairs: non_empty(pairs),
    }
}
