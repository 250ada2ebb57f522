//! Real obstacles cutting the plane: boxes and capsules in the world turned into blocked cells, checked
//! against independent in-plane geometry and dense sampling.

use knotlab_learner::fluid::{GridRegion, ObstacleMask, PlaneFrame, Solid, block_solid};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector2, Vector3};

fn setup() -> (PlaneFrame, GridRegion) {
    let plane = PlaneFrame::new(
        Vector3::new(0.1, 0.2, 0.9),
        Vector3::new(1.0, 0.0, 0.3),
        Vector3::new(0.0, 1.0, 0.0),
    )
    .expect("plane");
    (plane, GridRegion::new(Vector2::new(-0.02, -0.02), 0.001, 40).expect("region"))
}

/// Distance in the plane from `p` to the square of cell `(i, j)`.
fn square_distance(region: &GridRegion, i: usize, j: usize, p: Vector2<f64>) -> f64 {
    let lo = region.origin_m + Vector2::new(i as f64, j as f64) * region.cell_m;
    let dx = (lo.x - p.x).max(p.x - lo.x - region.cell_m).max(0.0);
    let dy = (lo.y - p.y).max(p.y - lo.y - region.cell_m).max(0.0);
    dx.hypot(dy)
}

/// A shaft through the plane blocks exactly the cells whose squares come within its radius of where it
/// crosses, and reports that count.
#[test]
fn a_shaft_through_the_plane_blocks_the_cells_within_its_radius() {
    let (plane, region) = setup();
    let centre = Vector2::new(0.003, -0.004);
    let normal = plane.normal();
    let at = plane.to_world(&centre);
    let shaft = Solid::Capsule { a_m: at - normal * 0.05, b_m: at + normal * 0.05, radius_m: 0.0042 };
    let mut mask = ObstacleMask::free(40);
    let added = block_solid(&mut mask, &plane, &region, &shaft).expect("block");
    let mut expected = 0;
    for j in 0..40 {
        for i in 0..40 {
            let want = square_distance(&region, i, j, centre) <= 0.0042;
            expected += usize::from(want);
            assert_eq!(mask.get(i, j), want, "cell ({i}, {j})");
        }
    }
    assert_eq!(added, expected);
    assert!(expected > 40);
}

/// A capsule lying above the plane blocks only the cells within its cut where it dips in, and none when it
/// stays clear of the plane.
#[test]
fn a_capsule_lying_above_the_plane_blocks_only_where_it_dips_in() {
    let (plane, region) = setup();
    let normal = plane.normal();
    let (p, q) = (Vector2::new(-0.01, 0.0), Vector2::new(0.012, 0.008));
    for (height, radius) in [(0.005, 0.004), (0.002, 0.004)] {
        let capsule = Solid::Capsule {
            a_m: plane.to_world(&p) + normal * height,
            b_m: plane.to_world(&q) + normal * height,
            radius_m: radius,
        };
        let mut mask = ObstacleMask::free(40);
        block_solid(&mut mask, &plane, &region, &capsule).expect("block");
        // The cut is the set of points within sqrt(r^2 - height^2) of the segment, in the plane.
        let reach = (radius * radius - height * height).max(0.0).sqrt();
        let mut blocked = 0;
        for j in 0..40 {
            for i in 0..40 {
                // Distance from the segment to the square: sample the segment densely.
                let d = (0..=2000)
                    .map(|k| square_distance(&region, i, j, p + (q - p) * (k as f64 / 2000.0)))
                    .fold(f64::INFINITY, f64::min);
                let want = height < radius && d <= reach;
                if (d - reach).abs() > 2e-5 {
                    assert_eq!(
                        mask.get(i, j),
                        want,
                        "height {height}: cell ({i}, {j}), d {d:.6} reach {reach:.6}"
                    );
                }
                blocked += usize::from(mask.get(i, j));
            }
        }
        assert_eq!(blocked > 0, height < radius);
    }
}

/// A tilted box blocks every cell holding a point of it and no cell farther than a sampling step from it.
#[test]
fn a_tilted_box_blocks_exactly_the_cells_it_touches() {
    let (plane, region) = setup();
    let world_from_box = Isometry3::from_parts(
        Translation3::from(plane.to_world(&Vector2::new(0.002, 0.001))),
        UnitQuaternion::from_euler_angles(0.5, 0.3, 0.9),
    );
    let half = Vector3::new(0.008, 0.003, 0.004);
    let solid = Solid::Box { world_from_box, half_extents_m: half };
    let mut mask = ObstacleMask::free(40);
    block_solid(&mut mask, &plane, &region, &solid).expect("block");
    let inside = |w: Vector3<f64>, margin: f64| {
        let local = world_from_box.inverse_transform_point(&w.into()).coords;
        (0..3).all(|k| local[k].abs() <= half[k] + margin)
    };
    let samples = 24;
    let h = region.cell_m;
    for j in 0..40 {
        for i in 0..40 {
            let corner = region.origin_m + Vector2::new(i as f64, j as f64) * h;
            let points = (0..=samples).flat_map(|a| {
                (0..=samples).map(move |b| corner + Vector2::new(a as f64, b as f64) * (h / samples as f64))
            });
            let (mut hit, mut near) = (false, false);
            for p in points {
                let w = plane.to_world(&p);
                hit |= inside(w, 0.0);
                near |= inside(w, h / samples as f64);
            }
            if hit {
                assert!(mask.get(i, j), "cell ({i}, {j}) holds a point of the box but is free");
            }
            if mask.get(i, j) {
                assert!(near, "cell ({i}, {j}) is blocked but nowhere near the box");
            }
        }
    }
    assert!(mask.count_blocked() > 20);
}

/// A capsule with a negative radius, and a mask whose size does not match the grid, are refused.
#[test]
fn bad_solids_are_refused() {
    let (plane, region) = setup();
    let mut mask = ObstacleMask::free(40);
    let bad = Solid::Capsule { a_m: Vector3::zeros(), b_m: Vector3::zeros(), radius_m: -1.0 };
    assert!(block_solid(&mut mask, &plane, &region, &bad).is_err());
    let ok = Solid::Capsule { a_m: Vector3::zeros(), b_m: Vector3::zeros(), radius_m: 0.01 };
    assert!(block_solid(&mut ObstacleMask::free(30), &plane, &region, &ok).is_err(), "mask size");
}
