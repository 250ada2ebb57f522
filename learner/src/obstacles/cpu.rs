//! The CPU backend: cells in parallel with rayon, each cell's subcells together. A cell's subcells are
//! solved first (one unreachable subcell settles it), then their arm links are posed (the sines and
//! cosines of the joints from the first subcell's, [`SinCosNear`]). Where each moving box's centre goes
//! over the cell bounds which environment boxes and which of its own boxes it can reach at all
//! (bounding spheres); each box left is grown to hold itself in every subcell and tested once for the
//! whole cell; a pair of its own boxes is also tested with only the joints between them moving (an
//! instrument's wrist held straight leaves its jaws and shaft rigid over the cell). Only the pairs left
//! after that are tested per subcell (bounding spheres, then the separating-axis test), stopping at the
//! first collision, and only their boxes are posed.
//!
//! Tried and dropped: bounding each box's motion from the joints' spread alone (as the self pairs'
//! relative test does), so that a cell settled without posing its other 24 subcells. With the shaft
//! held through the trocar, the arm's joints move in opposition and their sum-of-levers bound came out
//! about 27 times the posed one for the instrument's boxes (36 mm against 1.3 mm at the plane's
//! centre): it settled no cell of the benchmark's grid and only added work.
//!
//! The pruning is conservative, so the verdicts are those of the plain per-subcell reference
//! ([`PreparedGrid::verdict_at`]) but for a pose computed 1e-16 apart deciding a box test exactly on
//! its tolerance, and each cell is computed alone, so the grid is the same whatever the number of
//! threads. Runs on rayon's current pool: `pool.install(|| compute_cpu(..))` picks the threads.

use nalgebra::{IsometryMatrix3, Vector3};
use rayon::prelude::*;

use knotlab_hw::kinematics::ArmJoints;

use super::check::{SubcellVerdict, spheres_meet};
use super::error::ObstacleError;
use super::frames::{ANCHORS, CHAIN_JOINTS, SinCosNear, chain_angles};
use super::grid::{CellVerdict, GridResult};
use super::obb::Obb;
use super::prepare::{MAX_MOVING_BOXES, PreparedGrid};

/// Per-thread work space for one cell.
struct Scratch {
    joints: Vec<Option<ArmJoints>>,
    /// Each subcell's anchor poses.
    anchors: Vec<[IsometryMatrix3<f64>; ANCHORS]>,
    /// One subcell's posed moving boxes (only those `needed`).
    posed: Vec<Obb>,
    candidates: Vec<Vec<u32>>,
    /// The self pairs whose boxes can meet anywhere in the cell (indices into `self_pairs`).
    self_candidates: Vec<u32>,
    verdicts: Vec<SubcellVerdict>,
    /// The last separating axis of each self pair, then of each (moving box, environment box) pair.
    hints: Vec<u8>,
}

impl Scratch {
    fn new(subcells: usize, moving: usize, pairs: usize) -> Self {
        let empty = Obb::new(&IsometryMatrix3::identity(), Vector3::zeros());
        Self {
            joints: vec![None; subcells],
            anchors: vec![[IsometryMatrix3::identity(); ANCHORS]; subcells],
            posed: vec![empty; moving],
            candidates: vec![Vec::new(); moving],
            self_candidates: Vec::new(),
            verdicts: vec![SubcellVerdict::Free; subcells],
            hints: vec![u8::MAX; pairs],
        }
    }
}

/// Moving box `b` in the world, from its anchor's pose.
fn box_at(grid: &PreparedGrid, anchors: &[IsometryMatrix3<f64>; ANCHORS], b: usize) -> Obb {
    let mb = &grid.moving[b];
    Obb::new(&(anchors[mb.anchor] * mb.anchor_from_box), mb.half_extents_m)
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
    let Some(k0) = (0..s * s).find(|&k| scratch.joints[k].is_some()) else {
        return (verdict_of(unreachable, false), 0);
    };
    // Pose every reachable subcell's anchors (the others' sines and cosines from k0's), and bound how
    // far each anchor moves over the cell.
    let Some(joints_k0) = scratch.joints[k0] else {
        return (verdict_of(unreachable, false), 0);
    };
    let near = SinCosNear::new(&joints_k0);
    for k in 0..s * s {
        if let Some(joints) = &scratch.joints[k] {
            scratch.anchors[k] = if k == k0 {
                grid.kinematics.world_from_anchors(joints)
            } else {
                grid.kinematics.world_from_anchors_near(joints, &near)
            };
        }
    }
    let view = Posed { joints: &scratch.joints, anchors: &scratch.anchors };
    let motions = anchor_motions(view, k0);
    // Each box's centre at `k0` and how far the centre strays from it over the cell.
    let mut centre = [Vector3::zeros(); MAX_MOVING_BOXES];
    let mut stray_m = [0.0; MAX_MOVING_BOXES];
    for (b, mb) in grid.moving.iter().enumerate() {
        let on_anchor = mb.anchor_from_box.translation.vector;
        let pose = &view.anchors[k0][mb.anchor];
        centre[b] = pose.rotation * on_anchor + pose.translation.vector;
        let (dt, dr) = motions[mb.anchor];
        stray_m[b] = dt + dr * on_anchor.norm();
    }
    // Environment boxes each moving box can reach anywhere in the cell: the groups' spheres first.
    for (b, mb) in grid.moving.iter().enumerate() {
        let list = &mut scratch.candidates[b];
        list.clear();
        if !mb.tests_environment {
            continue;
        }
        let within = |other_m: &Vector3<f64>, other_radius_m: f64| {
            let reach = mb.radius_m + stray_m[b] + other_radius_m;
            (other_m - centre[b]).norm_squared() <= reach * reach
        };
        for g in grid.groups.iter().filter(|g| within(&g.centre_m, g.radius_m)) {
            for (e, env) in grid.environment[g.start..g.end].iter().enumerate() {
                if !(mb.inserted && env.patient) && within(&env.obb.centre_m, env.radius_m) {
                    list.push((g.start + e) as u32);
                }
            }
        }
    }
    // Self pairs whose bounding spheres can meet anywhere in the cell.
    scratch.self_candidates.clear();
    for (p, &(a, b)) in grid.self_pairs.iter().enumerate() {
        let reach = grid.moving[a].radius_m + stray_m[a] + grid.moving[b].radius_m + stray_m[b];
        if (centre[a] - centre[b]).norm_squared() <= reach * reach {
            scratch.self_candidates.push(p as u32);
        }
    }
    // Tighter: each box that still has a candidate, grown to hold itself in every subcell of the cell
    // (and `PRUNE_MARGIN_M` more), tested against it once for the whole cell.
    let mut grown = [None; MAX_MOVING_BOXES];
    let mut grow = |b: usize| -> Obb {
        *grown[b].get_or_insert_with(|| grown_box(grid, motions[grid.moving[b].anchor], b, &view.anchors[k0]))
    };
    for (b, list) in scratch.candidates.iter_mut().enumerate() {
        if !list.is_empty() {
            let big = grow(b);
            list.retain(|&e| big.intersects(&grid.environment[e as usize].obb));
        }
    }
    // A self pair moves together but for the joints between its two anchors (often none that move over
    // the cell, such as an instrument's wrist held straight): the box on the later anchor, grown by
    // how far those joints can move it relative to the earlier one, against the other as posed at k0.
    let spread = joint_spread_rad(&scratch.joints, k0);
    let axes = joint_axes(&view.anchors[k0]);
    let k0_anchors = &view.anchors[k0];
    scratch.self_candidates.retain(|&p| {
        let (a, b) = grid.self_pairs[p as usize];
        let (fixed, moving) = if grid.moving[a].anchor <= grid.moving[b].anchor { (a, b) } else { (b, a) };
        let joints = grid.moving[fixed].anchor..grid.moving[moving].anchor;
        let relative_m =
            relative_stray_m(&spread, &axes, joints, &centre[moving], grid.moving[moving].radius_m);
        let apart_relative = relative_m.is_finite() && {
            let m = box_at(grid, k0_anchors, moving);
            let grown = Obb { half_extents_m: m.half_extents_m.add_scalar(relative_m + RIGID_MARGIN_M), ..m };
            !box_at(grid, k0_anchors, fixed).intersects(&grown)
        };
        !apart_relative && grow(a).intersects(&grow(b))
    });
    // The boxes the remaining pairs need.
    let mut needed = [false; MAX_MOVING_BOXES];
    for (b, list) in scratch.candidates.iter().enumerate() {
        needed[b] |= !list.is_empty();
    }
    for &p in &scratch.self_candidates {
        let (a, b) = grid.self_pairs[p as usize];
        needed[a] = true;
        needed[b] = true;
    }
    if !needed[..m].iter().any(|&n| n) {
        let tested = scratch.joints.iter().filter(|j| j.is_some()).count();
        return (verdict_of(unreachable, false), tested);
    }
    let mut tested = 0;
    let mut collides = false;
    for k in 0..s * s {
        if scratch.joints[k].is_none() {
            continue;
        }
        tested += 1;
        for b in (0..m).filter(|&b| needed[b]) {
            scratch.posed[b] = box_at(grid, &scratch.anchors[k], b);
        }
        let posed = &scratch.posed;
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
            || scratch.self_candidates.iter().any(|&p| {
                let (a, b) = grid.self_pairs[p as usize];
                spheres_meet(
                    &posed[a].centre_m,
                    grid.moving[a].radius_m,
                    &posed[b].centre_m,
                    grid.moving[b].radius_m,
                ) && posed[a].intersects_hinted(&posed[b], &mut self_hints[p as usize])
            });
        if hit {
            scratch.verdicts[k] = SubcellVerdict::Collides;
            collides = true;
            if !keep {
                break;
            }
        }
    }
    (verdict_of(unreachable, collides), tested)
}

/// Added all round in the relative test of a self pair, m: far beyond the round-off of posing the two
/// boxes at another subcell and beyond the separating-axis test's tolerance.
const RIGID_MARGIN_M: f64 = 1e-5;

/// The largest change of each chain joint from subcell k0 over the reachable subcells, rad.
fn joint_spread_rad(joints: &[Option<ArmJoints>], k0: usize) -> [f64; CHAIN_JOINTS] {
    let at_k0 = joints[k0].as_ref().map_or([0.0; CHAIN_JOINTS], chain_angles);
    let mut spread = [0.0f64; CHAIN_JOINTS];
    for q in joints.iter().flatten() {
        for (s, (a, b)) in spread.iter_mut().zip(chain_angles(q).iter().zip(&at_k0)) {
            *s = s.max((a - b).abs());
        }
    }
    spread
}

/// Each chain joint's axis at the given anchor poses: a point on it and its direction (world). Arm axis
/// `k` turns about z of the frame before it (`Rz(q)`, then the DH row's fixed part); the roll turns
/// about the shaft's z, the pitch about the wrist's x, the yaw about the clevis' y, each through the
/// origin of the frame it makes.
fn joint_axes(anchors: &[IsometryMatrix3<f64>; ANCHORS]) -> [(Vector3<f64>, Vector3<f64>); CHAIN_JOINTS] {
    let axis = |a: usize, column: usize| {
        (anchors[a].translation.vector, anchors[a].rotation.matrix().column(column).into_owned())
    };
    [
        axis(0, 2),
        axis(1, 2),
        axis(2, 2),
        axis(3, 2),
        axis(4, 2),
        axis(5, 2),
        axis(7, 2),
        axis(8, 0),
        axis(9, 1),
    ]
}

/// How far any point of a box (centre `centre_m` at subcell k0, within `radius_m` of it) can move
/// relative to the anchor of chain joint `joints.start` when only the chain joints `joints` change, each
/// by at most `spread`, m. Along the straight joint-space path a point moves at `sum_j |dq_j|
/// dist(point, axis_j)`, and its distance to each axis grows by at most how far it has moved, which the
/// same bound holds: with `D = sum |dq_j|` and `d_j` the distances at k0, within `sum_j |dq_j| (d_j + r)
/// / (1 - D)`. Zero when the anchors are the same; infinite when `D` is not small.
fn relative_stray_m(
    spread: &[f64; CHAIN_JOINTS],
    axes: &[(Vector3<f64>, Vector3<f64>); CHAIN_JOINTS],
    joints: std::ops::Range<usize>,
    centre_m: &Vector3<f64>,
    radius_m: f64,
) -> f64 {
    let joints = joints.start.min(CHAIN_JOINTS)..joints.end.min(CHAIN_JOINTS);
    let total: f64 = spread[joints.clone()].iter().sum();
    if total >= 0.5 {
        return f64::INFINITY;
    }
    let moved: f64 = joints
        .map(|j| {
            let (point, dir) = &axes[j];
            spread[j] * ((centre_m - point).cross(dir).norm() + radius_m)
        })
        .sum();
    moved / (1.0 - total)
}

/// What [`grown_box`] reads of the scratch space.
#[derive(Clone, Copy)]
struct Posed<'a> {
    joints: &'a [Option<ArmJoints>],
    anchors: &'a [[IsometryMatrix3<f64>; ANCHORS]],
}

fn verdict_of(unreachable: bool, collides: bool) -> CellVerdict {
    if unreachable {
        CellVerdict::Unreachable
    } else if collides {
        CellVerdict::Collides
    } else {
        CellVerdict::Free
    }
}

/// Added to a grown box all round, m: a pair whose grown boxes are apart is at least this far apart in
/// every subcell, far beyond the separating-axis test's tolerance, so the plain per-subcell test finds
/// it apart too.
const PRUNE_MARGIN_M: f64 = 1e-3;

/// How far each anchor moves over the cell from subcell `k0`: the largest `|t_k - t_0|` and the
/// largest `|R_k - R_0|_F` over the reachable subcells (one pass over the subcells).
fn anchor_motions(view: Posed<'_>, k0: usize) -> [(f64, f64); ANCHORS] {
    let at_k0 = &view.anchors[k0];
    let mut sq = [(0.0f64, 0.0f64); ANCHORS];
    for (anchors, j) in view.anchors.iter().zip(view.joints) {
        if j.is_none() {
            continue;
        }
        for ((dt, dr), (pose, pose0)) in sq.iter_mut().zip(anchors.iter().zip(at_k0)) {
            *dt = dt.max((pose.translation.vector - pose0.translation.vector).norm_squared());
            *dr = dr.max((pose.rotation.matrix() - pose0.rotation.matrix()).norm_squared());
        }
    }
    sq.map(|(dt, dr)| (dt.sqrt(), dr.sqrt()))
}

/// Moving box `b` as posed at subcell `k0`, grown to hold the box as posed at every reachable subcell.
/// A point of the box sits at `t + R (p + u)` on its anchor (`p` the box centre on the anchor, `|u_i| <=
/// h_i`), so it lies within `|t_k - t_0| + |R_k - R_0|_F (|p| + |h|)` of where it is at `k0`: growing
/// every half extent by the anchor's largest such distance (and the margin) holds them all.
fn grown_box(
    grid: &PreparedGrid,
    motion: (f64, f64),
    b: usize,
    k0_anchors: &[IsometryMatrix3<f64>; ANCHORS],
) -> Obb {
    let base = box_at(grid, k0_anchors, b);
    let mb = &grid.moving[b];
    let lever_m = mb.anchor_from_box.translation.vector.norm() + mb.half_extents_m.norm();
    let grow_m = motion.0 + motion.1 * lever_m;
    Obb { half_extents_m: base.half_extents_m.add_scalar(grow_m + PRUNE_MARGIN_M), ..base }
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
