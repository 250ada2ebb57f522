//! The GPU backend against the CPU backend: identical grids on seeded scenes, except at subcells
//! within 1e-5 m of a collision or reachability boundary (f32 against f64), which are counted.
//!
//! Needs a wgpu adapter (CI installs Mesa's lavapipe). Without one these tests fail with a clear
//! message, unless `KNOTLAB_ALLOW_NO_GPU=1`, when they print that they skipped.
#![cfg(feature = "gpu")]

use super::obstacles_common;

use std::sync::OnceLock;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::gpu::{GpuContext, GpuError, GpuKernel, compute_gpu};
use knotlab_learner::obstacles::*;
use nalgebra::Vector3;
use obstacles_common::*;

/// Subcells whose verdicts may differ between f32 and f64: this close to a boundary, m.
const BOUNDARY_M: f64 = 1e-5;

/// One device and compiled kernel for the whole test binary (lavapipe compiles the kernel for seconds).
fn gpu(test: &str) -> Option<&'static (GpuContext, GpuKernel)> {
    static GPU: OnceLock<Result<(GpuContext, GpuKernel), String>> = OnceLock::new();
    let found = GPU.get_or_init(|| {
        let ctx = GpuContext::new().map_err(|e| e.to_string())?;
        let kernel = GpuKernel::new(&ctx).map_err(|e| e.to_string())?;
        eprintln!("GPU tests run on {}", ctx.describe());
        Ok((ctx, kernel))
    });
    match found {
        Ok(gpu) => Some(gpu),
        Err(reason) if std::env::var("KNOTLAB_ALLOW_NO_GPU").as_deref() == Ok("1") => {
            println!("SKIPPED {test}: no GPU ({reason}); KNOTLAB_ALLOW_NO_GPU=1 allows it");
            None
        }
        Err(reason) => panic!(
            "{test}: no GPU adapter: {reason}\n(install mesa-vulkan-drivers and libvulkan1, as scripts/test does, \
             or set KNOTLAB_ALLOW_NO_GPU=1 to skip the GPU tests)"
        ),
    }
}

/// Subcells of a grid within [`BOUNDARY_M`] of a boundary (where the backends may differ).
fn boundary_subcells(grid: &PreparedGrid) -> usize {
    let side = grid.request.plane.side();
    (0..side * side)
        .filter(|k| grid.near_boundary(&grid.subcell_tip_m(k % side, k / side), BOUNDARY_M))
        .count()
}

/// Compares the backends on one grid: (subcells, differing subcells); panics on a difference away
/// from a boundary.
fn compare(
    label: &str,
    grid: &PreparedGrid,
    ctx: &GpuContext,
    kernel: &GpuKernel,
) -> (usize, usize, GridResult) {
    let cpu = compute_cpu(grid, true);
    let (gpu, _) = compute_gpu(ctx, kernel, grid, true).expect("GPU grid");
    let (cs, gs) = (cpu.subcells.as_ref().expect("kept"), gpu.subcells.as_ref().expect("kept"));
    let side = grid.request.plane.side();
    let mut differing = 0;
    for (k, (c, g)) in cs.iter().zip(gs).enumerate() {
        if c != g {
            let tip = grid.subcell_tip_m(k % side, k / side);
            assert!(
                grid.near_boundary(&tip, BOUNDARY_M),
                "{label}: subcell {k} at {tip:?}: CPU {c:?}, GPU {g:?}, not within {BOUNDARY_M} m of a boundary"
            );
            differing += 1;
        }
    }
    // Cells differ only through differing subcells.
    let s = grid.request.plane.subcells;
    let n = grid.request.plane.cells;
    for (cell, (c, g)) in cpu.cells.iter().zip(&gpu.cells).enumerate() {
        if c != g {
            let (i, j) = (cell % n, cell / n);
            let explained = (0..s * s).any(|k| {
                let at = (j * s + k / s) * side + i * s + k % s;
                cs[at] != gs[at]
            });
            assert!(explained, "{label}: cell {cell} differs (CPU {c:?}, GPU {g:?}) with equal subcells");
        }
    }
    assert_eq!(
        gpu.subcells_collision_tested,
        cs.iter().filter(|v| **v != SubcellVerdict::Unreachable).count()
    );
    (cs.len(), differing, cpu)
}

/// On 24 seeded scenes the GPU grid equals the CPU grid except at subcells within 1e-5 m of a boundary,
/// with every verdict exercised.
#[test]
fn gpu_matches_cpu_on_seeded_scenes() {
    let Some((ctx, kernel)) = gpu("gpu_matches_cpu_on_seeded_scenes") else { return };
    let rig = Rig::shipped().unwrap();
    let (mut subcells, mut differing, mut boundary) = (0, 0, 0);
    let mut verdicts = [0usize; 3];
    let scenes = 24;
    for seed in 0..scenes {
        let grid = random_prepared(&rig, 1000 + seed, 16, 3);
        let (n, d, cpu) = compare(&format!("seed {}", 1000 + seed), &grid, ctx, kernel);
        subcells += n;
        differing += d;
        boundary += boundary_subcells(&grid);
        verdicts[0] += cpu.count(CellVerdict::Free);
        verdicts[1] += cpu.count(CellVerdict::Collides);
        verdicts[2] += cpu.count(CellVerdict::Unreachable);
    }
    println!(
        "parity over {scenes} seeded scenes: {subcells} subcells, {boundary} within {BOUNDARY_M} m of a boundary, \
         {differing} differ (each of them within {BOUNDARY_M} m of a boundary); cells {} free, {} colliding, {} unreachable",
        verdicts[0], verdicts[1], verdicts[2]
    );
    assert!(verdicts.iter().all(|v| *v > 100), "the scenes exercise every verdict: {verdicts:?}");
}

/// On a full-size 50-cell grid with a pad in it, along the shaft and with a jaw direction, the GPU grid
/// equals the CPU grid away from boundaries and the pad blocks cells.
#[test]
fn gpu_matches_cpu_on_a_full_size_grid() {
    let Some((ctx, kernel)) = gpu("gpu_matches_cpu_on_a_full_size_grid") else { return };
    let rig = Rig::shipped().unwrap();
    let mut world = nominal_world(&rig);
    world.add_obstacle("pad", Vector3::new(0.01, 0.0, 0.975), Vector3::new(0.01, 0.02, 0.01)).unwrap();
    for (arm, orientation) in [
        (ArmName::Left, SubcellOrientation::AlongShaft),
        (ArmName::Assist, SubcellOrientation::JawDirection(Vector3::new(0.2, -0.1, -1.0))),
    ] {
        let plane = square(Vector3::new(0.0, 0.0, 0.975), 0.12, 50, 5);
        let grid = PreparedGrid::new(&world, &GridRequest { arm, plane, orientation }).unwrap();
        let (n, d, cpu) = compare(&format!("{arm}"), &grid, ctx, kernel);
        println!(
            "{arm}: {n} subcells, {d} differ (boundary); {} cells colliding, {} unreachable",
            cpu.count(CellVerdict::Collides),
            cpu.count(CellVerdict::Unreachable)
        );
        assert_eq!(n, 62_500);
        assert!(cpu.count(CellVerdict::Collides) > 0, "{arm}: the pad blocks something");
    }
}

/// A scene with more environment boxes than the GPU kernel takes is a `TooLarge` error naming them, not a
/// panic.
#[test]
fn too_many_boxes_is_an_error_not_a_panic() {
    let Some((ctx, kernel)) = gpu("too_many_boxes_is_an_error_not_a_panic") else { return };
    let rig = Rig::shipped().unwrap();
    let mut world = nominal_world(&rig);
    for k in 0..300 {
        let at = Vector3::new(1.5 + 0.01 * f64::from(k), 0.0, 0.5);
        world.add_obstacle(&format!("crate {k}"), at, Vector3::repeat(0.004)).unwrap();
    }
    let plane = square(Vector3::new(0.0, 0.0, 0.975), 0.06, 4, 2);
    let request = GridRequest { arm: ArmName::Left, plane, orientation: SubcellOrientation::AlongShaft };
    let grid = PreparedGrid::new(&world, &request).unwrap();
    let err = compute_gpu(ctx, kernel, &grid, false).unwrap_err();
    assert!(matches!(err, GpuError::TooLarge(_)), "{err}");
    assert!(err.to_string().contains("environment boxes"), "{err}");
}
