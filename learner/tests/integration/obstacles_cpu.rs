//! The CPU backend: the same verdicts as the plain per-subcell reference on seeded random scenes,
//! the same grid whatever the thread count, the blocked region of an arm sweeping into another arm
//! where geometry puts it, and an empty scene blocking only what the arm cannot reach.

use super::obstacles_common;

use knotlab_hw::kinematics::{TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::*;
use nalgebra::Vector3;
use obstacles_common::*;

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool").install(f)
}

/// On seeded random scenes the CPU backend's subcell verdicts match the plain per-subcell reference, each
/// cell is its subcells' verdict, and settling cells early changes none.
#[test]
fn cpu_matches_the_plain_reference() {
    let rig = Rig::shipped().unwrap();
    let (mut collides, mut unreachable, mut free) = (0, 0, 0);
    for seed in 0..10 {
        let grid = random_prepared(&rig, seed, 8, 3);
        let full = compute_cpu(&grid, true);
        let quick = compute_cpu(&grid, false);
        let side = grid.request.plane.side();
        let subcells = full.subcells.as_ref().unwrap();
        for (k, verdict) in subcells.iter().enumerate() {
            let tip = grid.subcell_tip_m(k % side, k / side);
            assert_eq!(*verdict, grid.verdict_at(&tip), "seed {seed} subcell {k}");
        }
        let s = grid.request.plane.subcells;
        for (c, cell) in full.cells.iter().enumerate() {
            let (i, j) = (c % grid.request.plane.cells, c / grid.request.plane.cells);
            let own = (0..s * s).map(|k| subcells[(j * s + k / s) * side + i * s + k % s]);
            assert_eq!(*cell, CellVerdict::of_subcells(own), "seed {seed} cell {c}");
        }
        assert_eq!(quick.cells, full.cells, "seed {seed}: settling cells early changed them");
        assert!(quick.subcells.is_none());
        collides += full.count(CellVerdict::Collides);
        unreachable += full.count(CellVerdict::Unreachable);
        free += full.count(CellVerdict::Free);
    }
    println!("cells over 10 scenes: {free} free, {collides} colliding, {unreachable} unreachable");
    assert!(collides > 20 && unreachable > 20 && free > 20, "{free} {collides} {unreachable}");
}

/// The CPU backend gives the same grid on 1, 2, 3 or 4 threads, with subcells kept or not.
#[test]
fn same_grid_whatever_the_thread_count() {
    let rig = Rig::shipped().unwrap();
    for seed in [3, 11] {
        let grid = random_prepared(&rig, seed, 12, 3);
        let one = in_pool(1, || compute_cpu(&grid, true));
        for threads in [2, 3, 4] {
            assert_eq!(in_pool(threads, || compute_cpu(&grid, true)), one, "{threads} threads, seed {seed}");
            assert_eq!(in_pool(threads, || compute_cpu(&grid, false)).cells, one.cells);
        }
    }
}

/// Shortest distance between segments [p0, p1] and [q0, q1].
fn segment_distance(p0: Vector3<f64>, p1: Vector3<f64>, q0: Vector3<f64>, q1: Vector3<f64>) -> f64 {
    knotlab_hw::geometry::segment_distance(&p0, &p1, &q0, &q1)
}

/// The straight instrument's axis, jaw end to shaft base (box ends included), for a tip and trocar.
fn instrument_axis(tip: Vector3<f64>, trocar: Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let dir = (tip - trocar).normalize();
    // Jaw boxes reach 1.5 mm past the tip; the shaft box 4 mm behind the shaft base, which is
    // 0.4318 m behind the pitch axis, 19.1 mm behind the tip.
    (tip + dir * 0.0015, tip - dir * (0.0191 + 0.4318 + 0.004))
}

/// Cells within `radius` cells (Chebyshev) of a cell of `set`.
fn dilate(set: &[bool], n: usize, radius: usize) -> Vec<bool> {
    (0..n * n)
        .map(|c| {
            let (i, j) = (c % n, c / n);
            (j.saturating_sub(radius)..=(j + radius).min(n - 1))
                .any(|y| (i.saturating_sub(radius)..=(i + radius).min(n - 1)).any(|x| set[y * n + x]))
        })
        .collect()
}

/// The left arm swept into the right's shaft blocks cells within a cell of where the shafts must touch
/// (8 mm apart) and none more than a cell from where they can (11.3 mm).
#[test]
fn an_arm_sweeping_into_another_is_blocked_where_geometry_says() {
    // The right instrument reaches 9 cm into the chest; the left one's tip moves in a plane 8 mm above
    // the right tip, through the right shaft: the left shaft and jaws sweep into the right shaft.
    // Only these two arms are in the world.
    let rig = Rig::shipped().unwrap();
    let mut states = nominal_states(&rig);
    let right_trocar = trocar(ArmName::Right);
    let reach = (Vector3::new(-0.02, -0.03, 0.95) - right_trocar).normalize() * 0.09;
    let target =
        TipTarget { world_position_m: right_trocar + reach, orientation: TipOrientation::AlongShaft };
    states[1].joints = rig
        .arm(ArmName::Right)
        .model
        .solve_tip(&target, &right_trocar, &ArmName::Right.ready_joints())
        .unwrap();
    let mut world = CollisionWorld::from_rig(&rig, &states).unwrap();
    world.arms.retain(|a| matches!(a.name, ArmName::Left | ArmName::Right));
    let right = world.arm(ArmName::Right).unwrap().clone();
    let right_tip = right.model.world_from_tip(&right.joints).translation.vector;
    let right_dir = (right_tip - right.trocar_m).normalize();
    let z = right_tip.z + 0.008;
    let crossing = right_tip + right_dir * ((z - right_tip.z) / right_dir.z);
    let (n, s) = (14, 5);
    let plane = square(crossing, 0.07, n, s);
    let request = GridRequest { arm: ArmName::Left, plane, orientation: SubcellOrientation::AlongShaft };
    let grid = PreparedGrid::new(&world, &request).unwrap();
    let result = compute_cpu(&grid, false);
    assert_eq!(result.count(CellVerdict::Unreachable), 0, "the whole plane is reachable");

    // Expected: a cell must be blocked when, at one of its subcells, the two instrument axes come
    // within 8 mm (the 8 mm shaft boxes touch face to face whatever their roll), and may be blocked
    // when they come within 11.3 mm (edge to edge, depending on the boxes' roll about the shafts).
    let left_trocar = world.arm(ArmName::Left).unwrap().trocar_m;
    let (q0, q1) = instrument_axis(right_tip, right.trocar_m);
    let side = plane.side();
    let mut must = vec![false; n * n];
    let mut may = vec![false; n * n];
    for y in 0..side {
        for x in 0..side {
            let (p0, p1) = instrument_axis(plane.subcell_centre_m(x, y), left_trocar);
            let d = segment_distance(p0, p1, q0, q1);
            if d <= 0.008 {
                must[(y / s) * n + x / s] = true;
            }
            if d <= 0.0113 {
                may[(y / s) * n + x / s] = true;
            }
        }
    }
    let blocked = &result.raw.blocked;
    let near_may = dilate(&may, n, 1);
    let near_blocked = dilate(blocked, n, 1);
    let (n_blocked, n_expected) =
        (blocked.iter().filter(|b| **b).count(), must.iter().filter(|b| **b).count());
    assert!(n_expected >= 10 && n_expected <= n * n / 2, "the sweep crosses the plane: {n_expected} cells");
    for c in 0..n * n {
        assert!(
            !blocked[c] || near_may[c],
            "cell {c} blocked, no cell within one cell where the shafts can touch"
        );
        assert!(!must[c] || near_blocked[c], "cell {c} must be blocked, no blocked cell within one cell");
    }
    println!(
        "sweep: {n_blocked} cells blocked, {n_expected} where the shafts must touch; within a cell of the geometric bounds"
    );
}

/// With nothing in the scene no cell collides, and exactly the cells with an unreachable subcell are blocked.
#[test]
fn an_empty_scene_blocks_only_unreachable_cells() {
    let rig = Rig::shipped().unwrap();
    let mut world = nominal_world(&rig);
    world.arms.retain(|a| a.name == ArmName::Left);
    world.fixed.clear();
    let plane = square(Vector3::new(0.0, 0.0, 0.93), 0.5, 20, 2);
    let request = GridRequest { arm: ArmName::Left, plane, orientation: SubcellOrientation::AlongShaft };
    let grid = PreparedGrid::new(&world, &request).unwrap();
    let result = compute_cpu(&grid, false);
    assert_eq!(result.count(CellVerdict::Collides), 0);
    let arm = world.arm(ArmName::Left).unwrap();
    let side = plane.side();
    for (c, cell) in result.cells.iter().enumerate() {
        let (i, j) = (c % 20, c / 20);
        let any_unreachable = (0..4).any(|k| {
            let tip = plane.subcell_centre_m(2 * i + k % 2, 2 * j + k / 2);
            let target = TipTarget { world_position_m: tip, orientation: TipOrientation::AlongShaft };
            arm.model.solve_tip(&target, &arm.trocar_m, &arm.joints).is_err()
        });
        assert_eq!(*cell == CellVerdict::Unreachable, any_unreachable, "cell {c}");
    }
    let unreachable = result.count(CellVerdict::Unreachable);
    assert!(unreachable > 20 && result.count(CellVerdict::Free) > 20, "{unreachable} unreachable of 400");
    assert_eq!(result.raw.count_blocked(), unreachable);
    assert_eq!(side, 40);
}
