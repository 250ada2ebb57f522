//! The oriented-box test: the exact rule for boxes that share their axes, no point of one box inside
//! the other when it says they are apart, and the hinted test giving the plain test's verdicts.

use knotlab_learner::obstacles::obb::Obb;
use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_box(rng: &mut ChaCha8Rng, spread: f64) -> Obb {
    let rotation = Rotation3::from_euler_angles(
        rng.random_range(-3.2..3.2),
        rng.random_range(-1.6..1.6),
        rng.random_range(-3.2..3.2),
    );
    let centre = Vector3::new(
        rng.random_range(-spread..spread),
        rng.random_range(-spread..spread),
        rng.random_range(-spread..spread),
    );
    let half = Vector3::new(
        rng.random_range(0.005..0.3),
        rng.random_range(0.005..0.3),
        rng.random_range(0.005..0.3),
    );
    Obb::new(&IsometryMatrix3::from_parts(Translation3::from(centre), rotation), half)
}

fn inside(p: &Vector3<f64>, b: &Obb) -> bool {
    let local = b.rotation.transpose() * (p - b.centre_m);
    (0..3).all(|k| local[k].abs() <= b.half_extents_m[k])
}

/// Two boxes sharing their axes intersect exactly when their centres' offset is within the summed
/// half-extents on every axis.
#[test]
fn boxes_sharing_axes_follow_the_interval_rule() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for _ in 0..2000 {
        let rotation =
            Rotation3::from_euler_angles(rng.random_range(-3.0..3.0), rng.random_range(-1.5..1.5), 0.4);
        let pose = |c: Vector3<f64>| IsometryMatrix3::from_parts(Translation3::from(c), rotation);
        let ha = Vector3::new(0.1, 0.05, 0.2);
        let hb = Vector3::new(0.03, 0.2, 0.07);
        let offset = Vector3::new(
            rng.random_range(-0.4..0.4),
            rng.random_range(-0.4..0.4),
            rng.random_range(-0.4..0.4),
        );
        // Stay clear of touching, where the test's 1e-6 slack decides.
        let gaps = (offset.abs() - (ha + hb)).abs();
        if gaps.min() < 1e-4 {
            continue;
        }
        let a = Obb::new(&pose(Vector3::zeros()), ha);
        let b = Obb::new(&pose(rotation * offset), hb);
        let expected = (0..3).all(|k| offset[k].abs() <= ha[k] + hb[k]);
        assert_eq!(a.intersects(&b), expected, "offset {offset:?}");
    }
}

/// Where the box test finds a separating axis no point of one box lies inside the other, and from any hint
/// the hinted test gives the plain verdict, leaving the hint on a separating axis.
#[test]
fn apart_means_no_point_inside_and_hints_change_nothing() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let (mut apart, mut overlapping) = (0, 0);
    for _ in 0..3000 {
        let (a, b) = (random_box(&mut rng, 0.4), random_box(&mut rng, 0.4));
        let plain = a.intersects(&b);
        match a.separating_axis(&b) {
            Some(axis) => {
                assert!(!plain && a.separated_along(&b, axis));
                apart += 1;
                for k in 0..1000 {
                    let f = |i: u32| f64::from((k / 10_u32.pow(i)) % 10) / 4.5 - 1.0;
                    let p = a.centre_m
                        + a.rotation * a.half_extents_m.component_mul(&Vector3::new(f(0), f(1), f(2)));
                    assert!(!inside(&p, &b), "a point of A inside B though axis {axis} separates them");
                }
            }
            None => {
                assert!(plain);
                overlapping += 1;
                assert!((0..15).all(|axis| !a.separated_along(&b, axis)));
            }
        }
        for hint in 0..=15 {
            let mut h = hint;
            assert_eq!(a.intersects_hinted(&b, &mut h), plain, "hint {hint}");
            if !plain {
                assert!(a.separated_along(&b, h), "the hint is left on a separating axis");
            }
        }
    }
    assert!(apart > 300 && overlapping > 300, "{apart} apart, {overlapping} overlapping");
}
