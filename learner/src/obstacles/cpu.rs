//! The CPU backend: cells in parallel with rayon, each cell's subcells together. A cell's subcells are
//! solved first (one unreachable subcell settles it), then posed; the boxes each moving box sweeps over
//! the cell bound which environment boxes it can reach at all, and only those are tested per subcell
//! (bounding spheres, then the separating-axis test), stopping at the first collision.
//!
//! The pruning is conservative, so the verdicts are exactly those of the plain per-subcell reference
//! ([`PreparedGrid::verdict_at`]), and each cell is computed alone, so the grid is the same whatever the
//! number of threads. Runs on rayon's current pool: `pool.install(|| compute_cpu(..))` picks the threads.

use nalgebra::{IsometryMatrix3, Vector3};
use rayon::prelude::*;

use knotlab_hw::kinematics::ArmJoints;

use super::check::{SubcellVerdict, spheres_meet};
use super::error::ObstacleError;
use super::grid::{CellVerdict, GridResult};
use super::obb::Obb;
use super::prepare::PreparedGrid;

/// Per-thread work space for one cell.
struct Scratch {
    joints: Vec<Option<ArmJoints>>,
    posed: Vec<Obb>,
    candidates: Vec<Vec<u32>>,
    verdicts: Vec<SubcellVerdict>,
    /// The last separating axis of each self pair, then of each (moving box, environment box) pair.
    hints: Vec<u8>,
}

impl Scratch {
    fn new(subcells: usize, moving: usize, pairs: usize) -> Self {
        let empty = Obb::new(&IsometryMatrix3::identity(), Vector3::zeros());
        Self {
            joints: vec![None; subcells],
            posed: vec![empty; subcells * moving],
            candidates: vec![Vec::new(); moving],
            verdicts: vec![SubcellVerdict::Free; subcells],
            hints: vec![u8::MAX; pairs],
        }
    }
}

/// Distance from a point to an axis-aligned box, squared.
fn distance_sq_to_aabb(p: &Vector3<f64>, lo: &Vector3<f64>, hi: &Vector3<f64>) -> f64 {
    (0..3).map(|k| (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0)).map(|d| d * d).sum()
}

/// One cell: its verdict, how many subcells were collision-tested, and (with `keep`) every subcell's
/// verdict in `scratch.verdicts`, cell-local row-major.
fn evaluate_cell(
    grid: &PreparedGrid,
    scratch: &mut Scratch,
    i: usize,
    j: usize,
    keep: bool,
) -> (CellVerdict, usize) {
    let s = grid.request.plane.subcells;
    let m = grid.moving.len();
    let mut unreachable = false;
    for b in 0..s {
        for a in 0..s {
            let k = b * s + a;
            let joints = grid.solve(&grid.subcell_tip_m(i * s + a, j * s + b));
            unreachable |= joints.is_none();
            scratch.joints[k] = joints;
            scratch.verdicts[k] =
                if joints.is_some() { SubcellVerdict::Free } else { SubcellVerdict::Unreachable };
            if unreachable && !keep {
                return (CellVerdict::Unreachable, 0);
            }
        }
    }
    // Pose every reachable subcell, and bound each moving box's centre over the cell.
    let mut lo = [Vector3::repeat(f64::INFINITY); super::prepare::MAX_MOVING_BOXES];
    let mut hi = [Vector3::repeat(f64::NEG_INFINITY); super::prepare::MAX_MOVING_BOXES];
    for k in 0..s * s {
        if let Some(joints) = &scratch.joints[k] {
            let posed = &mut scratch.posed[k * m..(k + 1) * m];
            grid.pose_moving(joints, posed);
            for (b, obb) in posed.iter().enumerate() {
                lo[b] = lo[b].inf(&obb.centre_m);
                hi[b] = hi[b].sup(&obb.centre_m);
            }
        }
    }
    // Environment boxes each moving box can reach anywhere in the cell.
    for (b, mb) in grid.moving.iter().enumerate() {
        let list = &mut scratch.candidates[b];
        list.clear();
        if !mb.tests_environment || lo[b].x > hi[b].x {
            continue;
        }
        for (e, env) in grid.environment.iter().enumerate() {
            let reach = mb.radius_m + env.radius_m;
            if !(mb.inserted && env.patient)
                && distance_sq_to_aabb(&env.obb.centre_m, &lo[b], &hi[b]) <= reach * reach
            {
                list.push(e as u32);
            }
        }
    }
    let mut tested = 0;
    let mut collides = false;
    for k in 0..s * s {
        if scratch.joints[k].is_none() {
            continue;
        }
        tested += 1;
        let posed = &scratch.posed[k * m..(k + 1) * m];
        let (pairs, n_env) = (grid.self_pairs.len(), grid.environment.len());
        let (self_hints, env_hints) = scratch.hints.split_at_mut(pairs);
        let env_hit = grid.moving.iter().enumerate().any(|(b, mb)| {
            scratch.candidates[b].iter().any(|&e| {
                let env = &grid.environment[e as usize];
                spheres_meet(&posed[b].centre_m, mb.radius_m, &env.obb.centre_m, env.radius_m)
                    && posed[b].intersects_hinted(&env.obb, &mut env_hints[b * n_env + e as usize])
            })
        });
        let hit = env_hit
            || grid.self_pairs.iter().zip(self_hints.iter_mut()).any(|(&(a, b), hint)| {
                spheres_meet(
                    &posed[a].centre_m,
                    grid.moving[a].radius_m,
                    &posed[b].centre_m,
                    grid.moving[b].radius_m,
                ) && posed[a].intersects_hinted(&posed[b], hint)
            });
        if hit {
            scratch.verdicts[k] = SubcellVerdict::Collides;
            collides = true;
            if !keep {
                break;
            }
        }
    }
    let verdict = if unreachable {
        CellVerdict::Unreachable
    } else if collides {
        CellVerdict::Collides
    } else {
        CellVerdict::Free
    };
    (verdict, tested)
}

/// A thread pool of `threads` threads for [`compute_cpu`]: `thread_pool(2)?.install(|| compute_cpu(..))`.
pub fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, ObstacleError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build()
        .map_err(|e| ObstacleError::ThreadPool { threads, reason: e.to_string() })
}

/// Computes the grid on the CPU. With `keep_subcells`, every subcell is evaluated and its verdict kept
/// (slower: no cell is settled early).
pub fn compute_cpu(grid: &PreparedGrid, keep_subcells: bool) -> GridResult {
    let plane = grid.request.plane;
    let (n, s) = (plane.cells, plane.subcells);
    let per_cell: Vec<(CellVerdict, usize, Vec<SubcellVerdict>)> = (0..n * n)
        .into_par_iter()
        .map_init(
            || {
                let pairs = grid.self_pairs.len() + grid.moving.len() * grid.environment.len();
                Scratch::new(s * s, grid.moving.len(), pairs)
            },
            |scratch, c| {
                let (verdict, tested) = evaluate_cell(grid, scratch, c % n, c / n, keep_subcells);
                let kept = if keep_subcells { scratch.verdicts.clone() } else { Vec::new() };
                (verdict, tested, kept)
            },
        )
        .collect();
    let tested = per_cell.iter().map(|(_, t, _)| t).sum();
    let subcells = keep_subcells.then(|| {
        let side = plane.side();
        let mut fine = vec![SubcellVerdict::Free; side * side];
        for (c, (_, _, kept)) in per_cell.iter().enumerate() {
            let (i, j) = (c % n, c / n);
            for (k, v) in kept.iter().enumerate() {
                fine[(j * s + k / s) * side + i * s + k % s] = *v;
            }
        }
        fine
    });
    let cells = per_cell.into_iter().map(|(v, _, _)| v).collect();
    GridResult::new(plane, cells, subcells, tested)
}
