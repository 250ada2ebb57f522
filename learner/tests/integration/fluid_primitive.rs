//! Instantiating a 2D primitive: the regenerated path keeps the moved demonstration's shape and speed in
//! free space (within a cell, Hausdorff), a double wrap stays a double wrap, an obstacle across the path
//! is passed with at least half a cell of clearance, and over 1000 seeded random obstacle layouts no
//! particle position is ever inside an obstacle cell.

use knotlab_learner::fluid::{
    FluidError, GridRegion, InstantiateSettings, Instantiation, ObstacleMask, PlanarDemonstration,
    PlaneFrame, SpeedPath, instantiate,
};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The knot's double wrap, 2.4 cm across at 2 cm/s, in a tilted plane.
fn double_wrap() -> PlanarDemonstration {
    let plane = PlaneFrame::new(
        Vector3::new(0.05, -0.02, 0.95),
        Vector3::new(1.0, 0.0, 0.2),
        Vector3::new(0.0, 1.0, 0.0),
    )
    .expect("plane");
    let path = SpeedPath::double_loop(Vector2::new(0.0, 0.0), 0.012, 0.02).expect("path");
    PlanarDemonstration { plane, path }
}

fn site() -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(0.08, 0.03, -0.05),
        UnitQuaternion::from_euler_angles(0.1, -0.2, 0.7),
    )
}

/// Distance from `p` to the polyline `line`.
fn distance_to_polyline(p: &Vector3<f64>, line: &[Vector3<f64>]) -> f64 {
    line.windows(2)
        .map(|w| {
            let ab = w[1] - w[0];
            let t = if ab.norm_squared() > 0.0 {
                ((p - w[0]).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (w[0] + ab * t - p).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Symmetric Hausdorff distance between two polylines (vertices against segments), m.
fn hausdorff(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    let one = |x: &[Vector3<f64>], y: &[Vector3<f64>]| {
        x.iter().map(|p| distance_to_polyline(p, y)).fold(0.0, f64::max)
    };
    one(a, b).max(one(b, a))
}

/// Turns of a plane path around `centre`.
fn winding(points: &[Vector2<f64>], centre: Vector2<f64>) -> f64 {
    let mut angle = 0.0;
    for w in points.windows(2) {
        let (a, b) = (w[0] - centre, w[1] - centre);
        angle += a.perp(&b).atan2(a.dot(&b));
    }
    angle / std::f64::consts::TAU
}

/// Checks that no traced or output position lies in a blocked cell of the simulated mask.
fn assert_outside_obstacles(inst: &Instantiation, label: &str) -> usize {
    let region = inst.region;
    let mut checked = 0;
    let positions = inst.trace.iter().map(|(_, p)| *p).chain(inst.points.iter().map(|p| p.plane_m));
    for p in positions {
        let (i, j) = region.cell_of(&p).unwrap_or_else(|| panic!("{label}: {p:?} outside the grid"));
        assert!(!inst.mask.get(i, j), "{label}: a position in obstacle cell ({i}, {j})");
        checked += 1;
    }
    checked
}

/// In free space the regenerated path stays within a cell (Hausdorff) of the moved demonstration and
/// keeps its duration and 2 cm/s speed, in points at most 10 ms apart, with divergence within tolerance.
#[test]
fn free_space_keeps_the_moved_demonstration_within_a_cell() {
    let demo = double_wrap();
    let region = GridRegion::around(&demo.path.points_m, 50, 0.006).expect("region");
    let inst = instantiate(&demo, &site(), &region, &ObstacleMask::free(50), &InstantiateSettings::default())
        .expect("instantiate");
    let moved_plane = demo.plane.moved(&site());
    let moved_demo: Vec<Vector3<f64>> = demo.path.points_m.iter().map(|p| moved_plane.to_world(p)).collect();
    // The world points are the moved demonstration's plane mapping of the plane points.
    for p in &inst.points {
        assert!((p.world_m - moved_plane.to_world(&p.plane_m)).norm() < 1e-12);
        let moved = site().transform_point(&demo.plane.to_world(&p.plane_m).into());
        assert!((moved.coords - p.world_m).norm() < 1e-12);
    }
    let world: Vec<Vector3<f64>> = inst.points.iter().map(|p| p.world_m).collect();
    let distance = hausdorff(&world, &moved_demo);
    println!(
        "free space: Hausdorff {:.3e} m = {:.3} cells, {:?}",
        distance,
        distance / region.cell_m,
        inst.report
    );
    assert!(distance <= region.cell_m, "Hausdorff {distance:.3e} m > one cell {:.3e} m", region.cell_m);
    // The speed is the demonstration's: same duration, resampled every 10 ms.
    let demo_duration = knotlab_learner::fluid::ArcPath::new(&demo.path).duration_s();
    // (The stirring runs through the equal arc-length samples, whose chords cut the polyline's corners.)
    assert!((inst.report.duration_s - demo_duration).abs() < 1e-4 * demo_duration);
    assert_eq!(inst.points[inst.points.len() - 1].t_s, inst.report.duration_s);
    assert!(inst.points.windows(2).all(|w| w[1].t_s - w[0].t_s <= 0.01 + 1e-12 && w[1].t_s > w[0].t_s));
    let speeds: Vec<f64> = inst
        .points
        .windows(2)
        .map(|w| (w[1].world_m - w[0].world_m).norm() / (w[1].t_s - w[0].t_s))
        .collect();
    let mid = &speeds[speeds.len() / 4..3 * speeds.len() / 4];
    assert!(mid.iter().all(|s| (s - 0.02).abs() < 0.002), "speeds in the loops stay near 2 cm/s");
    assert!(inst.report.max_divergence_per_s <= inst.report.divergence_tol_per_s);
}

/// A demonstrated double wrap regenerates as two turns about its centre, within 0.05 turn of the
/// demonstration's winding.
#[test]
fn a_double_wrap_stays_a_double_wrap() {
    let demo = double_wrap();
    let region = GridRegion::around(&demo.path.points_m, 50, 0.006).expect("region");
    let inst = instantiate(
        &demo,
        &Isometry3::identity(),
        &region,
        &ObstacleMask::free(50),
        &InstantiateSettings::default(),
    )
    .expect("instantiate");
    let plane: Vec<Vector2<f64>> = inst.points.iter().map(|p| p.plane_m).collect();
    let demo_turns = winding(&demo.path.points_m, Vector2::zeros());
    let turns = winding(&plane, Vector2::zeros());
    println!("winding: demonstration {demo_turns:.3} turns, regenerated {turns:.3}");
    assert_eq!(turns.round(), 2.0);
    assert!((turns - demo_turns).abs() < 0.05);
}

/// A block across both loops is passed with at least half a cell of clearance and never unblocked, and the
/// path still winds twice and ends within two cells of the demonstration's end.
#[test]
fn an_obstacle_across_the_path_is_passed_with_half_a_cell_of_clearance() {
    let demo = double_wrap();
    let region = GridRegion::around(&demo.path.points_m, 50, 0.006).expect("region");
    // A 6 mm wide block rising from the bottom edge through both loops' lowest stretches.
    let mut mask = ObstacleMask::free(50);
    let added = region.block_box(&mut mask, Vector2::new(-0.003, -0.03), Vector2::new(0.003, -0.008));
    assert!(added > 50);
    let blocked_before = mask.clone();
    let inst =
        instantiate(&demo, &site(), &region, &mask, &InstantiateSettings::default()).expect("instantiate");
    let h = region.cell_m;
    // Clearance from every blocked cell, measured here from the positions.
    let mut clearance = f64::INFINITY;
    for (_, p) in &inst.trace {
        for j in 0..50 {
            for i in 0..50 {
                if inst.mask.get(i, j) {
                    let lo = region.origin_m + Vector2::new(i as f64, j as f64) * h;
                    let d = Vector2::new(
                        (lo.x - p.x).max(p.x - lo.x - h).max(0.0),
                        (lo.y - p.y).max(p.y - lo.y - h).max(0.0),
                    );
                    clearance = clearance.min(d.norm());
                }
            }
        }
    }
    println!("obstacle: clearance {:.3} cells, {:?}", clearance / h, inst.report);
    assert!(clearance >= 0.5 * h, "clearance {:.3} cells", clearance / h);
    assert!(blocked_before.blocked.iter().zip(&inst.mask.blocked).all(|(a, b)| !a || *b));
    // It went around: the demonstration crosses the block, the regenerated path does not, and it
    // still reaches the end of the stirring with the same winding.
    assert!(inst.report.detours >= 2 && inst.report.moved_samples > 0);
    assert!(inst.report.end_gap_m < h, "end gap {:.3e}", inst.report.end_gap_m);
    let plane: Vec<Vector2<f64>> = inst.points.iter().map(|p| p.plane_m).collect();
    assert_eq!(winding(&plane, Vector2::zeros()).round(), 2.0);
    let end = inst.points[inst.points.len() - 1].plane_m;
    let demo_end = demo.path.points_m[demo.path.points_m.len() - 1];
    assert!(
        (end - demo_end).norm() < 2.0 * h,
        "ends {:.3e} m from the demonstration's end",
        (end - demo_end).norm()
    );
}

/// Over 1000 seeded random obstacle layouts no traced or output position lies in a blocked cell, at least
/// 950 layouts are stirred, and at least 300 of them force a detour.
#[test]
fn a_thousand_random_obstacle_layouts_never_put_the_particle_inside_one() {
    // A 2 cm arc at 2 cm/s through a 50 x 50 grid of 1 mm cells, with 1 to 4 random boxes and up to 30
    // random single cells (like virtual obstacles) around it; the start's neighbourhood stays free.
    let points: Vec<Vector2<f64>> = (0..=60)
        .map(|k| {
            let a = std::f64::consts::PI * (0.9 - 0.8 * k as f64 / 60.0);
            Vector2::new(0.025 + 0.012 * a.cos(), 0.015 + 0.012 * a.sin())
        })
        .collect();
    let demo = PlanarDemonstration {
        plane: PlaneFrame::horizontal(0.9),
        path: SpeedPath::constant_speed(points.clone(), 0.02).expect("arc"),
    };
    let region = GridRegion::new(Vector2::zeros(), 0.001, 50).expect("region");
    let start = region.cell_of(&points[0]).expect("start inside");
    let mut rng = ChaCha8Rng::seed_from_u64(8_2026);
    let (mut runs, mut no_room, mut positions, mut detoured, mut split) = (0, 0, 0, 0, 0);
    for layout in 0..1000 {
        let mut mask = ObstacleMask::free(50);
        for _ in 0..rng.random_range(1..=4) {
            let (w, h) = (rng.random_range(1..=10), rng.random_range(1..=10));
            let (i0, j0) = (rng.random_range(0..50 - w), rng.random_range(0..50 - h));
            for j in j0..j0 + h {
                for i in i0..i0 + w {
                    mask.set(i, j, true);
                }
            }
        }
        for _ in 0..rng.random_range(0..=30) {
            mask.set(rng.random_range(0..50), rng.random_range(0..50), true);
        }
        for j in start.1.saturating_sub(3)..=start.1 + 3 {
            for i in start.0.saturating_sub(3)..=start.0 + 3 {
                mask.set(i, j, false);
            }
        }
        match instantiate(&demo, &Isometry3::identity(), &region, &mask, &InstantiateSettings::default()) {
            Ok(inst) => {
                runs += 1;
                positions += assert_outside_obstacles(&inst, &format!("layout {layout}"));
                detoured += usize::from(inst.report.detours > 0);
                split += usize::from(inst.report.particle_splits > 0);
            }
            Err(FluidError::NoRoom(_)) => no_room += 1,
            Err(other) => panic!("layout {layout}: {other}"),
        }
    }
    println!(
        "{runs} layouts run ({detoured} with detours, {split} with split particle steps), {no_room} without room; {positions} positions checked"
    );
    assert!(runs >= 950, "only {runs} layouts could be stirred");
    assert!(detoured >= 300, "the layouts must get in the way: only {detoured} detours");
}

/// A mask of the wrong size, a zero or vanishing output step and a negative speed are refused naming the
/// field, and a fully blocked grid is refused too.
#[test]
fn bad_input_is_refused_with_the_field_named() {
    let demo = double_wrap();
    let region = GridRegion::around(&demo.path.points_m, 50, 0.006).expect("region");
    let err = instantiate(&demo, &site(), &region, &ObstacleMask::free(40), &InstantiateSettings::default())
        .expect_err("mask size");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "obstacles"), "{err}");
    let settings = InstantiateSettings { output_dt_s: 0.0, ..InstantiateSettings::default() };
    let err =
        instantiate(&demo, &site(), &region, &ObstacleMask::free(50), &settings).expect_err("output_dt_s");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "output_dt_s"), "{err}");
    let settings = InstantiateSettings { output_dt_s: 1e-9, ..InstantiateSettings::default() };
    let err =
        instantiate(&demo, &site(), &region, &ObstacleMask::free(50), &settings).expect_err("10^10 points");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "output_dt_s"), "{err}");
    let mut bad = demo.clone();
    bad.path.speed_mps[5] = -1.0;
    let err = instantiate(&bad, &site(), &region, &ObstacleMask::free(50), &InstantiateSettings::default())
        .expect_err("negative speed");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "path.speed_mps[5]"), "{err}");
    // Everything blocked: no room to stir.
    let full = ObstacleMask { n: 50, blocked: vec![true; 2500] };
    assert!(instantiate(&demo, &site(), &region, &full, &InstantiateSettings::default()).is_err());
}

/// Instantiating the same primitive twice around the same obstacle gives the same points bit for bit.
#[test]
fn instantiation_is_deterministic_to_the_bit() {
    let demo = double_wrap();
    let region = GridRegion::around(&demo.path.points_m, 50, 0.006).expect("region");
    let mut mask = ObstacleMask::free(50);
    region.block_box(&mut mask, Vector2::new(0.004, 0.0), Vector2::new(0.02, 0.003));
    let run =
        || instantiate(&demo, &site(), &region, &mask, &InstantiateSettings::default()).expect("instantiate");
    let (a, b) = (run(), run());
    assert_eq!(a.points.len(), b.points.len());
    for (p, q) in a.points.iter().zip(&b.points) {
        assert_eq!(p.world_m.map(f64::to_bits), q.world_m.map(f64::to_bits));
    }
}

/// On a 128-cell grid as on a 50-cell one the regenerated path stays within a cell of the moved
/// demonstration.
#[test]
fn a_finer_grid_regenerates_the_same_path() {
    let demo = double_wrap();
    let moved_plane = demo.plane.moved(&site());
    let moved_demo: Vec<Vector3<f64>> = demo.path.points_m.iter().map(|p| moved_plane.to_world(p)).collect();
    for n in [50, 128] {
        let region = GridRegion::around(&demo.path.points_m, n, 0.006).expect("region");
        let inst =
            instantiate(&demo, &site(), &region, &ObstacleMask::free(n), &InstantiateSettings::default())
                .expect("instantiate");
        let world: Vec<Vector3<f64>> = inst.points.iter().map(|p| p.world_m).collect();
        let distance = hausdorff(&world, &moved_demo);
        println!("n {n}: Hausdorff {:.3} cells, {} steps", distance / region.cell_m, inst.report.steps);
        assert!(distance <= region.cell_m, "n {n}: {:.3} cells", distance / region.cell_m);
    }
}
