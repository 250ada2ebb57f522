//! The demonstrated path: exact arc-length sampling at equal steps, exact timing along the speed
//! profile, and refusal of bad paths with the field named.

use knotlab_learner::fluid::{ArcPath, FluidError, SpeedPath};
use nalgebra::{Isometry2, Vector2};

fn v(x: f64, y: f64) -> Vector2<f64> {
    Vector2::new(x, y)
}

/// Equal arc-length samples of an L with a zero-length segment lie exactly at multiples of the step
/// along it, and a step that does not divide the length ends on the path's end.
#[test]
fn equal_arc_length_samples_are_exactly_d_apart_along_the_path() {
    // An L with a zero-length segment in it: 0.3 m then 0.4 m.
    let path = SpeedPath::constant_speed(vec![v(0.0, 0.0), v(0.3, 0.0), v(0.3, 0.0), v(0.3, 0.4)], 0.1)
        .expect("path");
    let arc = ArcPath::new(&path);
    assert!((arc.length_m() - 0.7).abs() < 1e-15);
    let samples = arc.sample_equal(0.07);
    assert_eq!(samples.len(), 11);
    for (k, s) in samples.iter().enumerate() {
        let want_s = (k as f64 * 0.07).min(0.7);
        assert!((s.s_m - want_s).abs() < 1e-12, "sample {k}: s = {}", s.s_m);
        // The point at arc length s on the L, exactly.
        let want = if want_s <= 0.3 { v(want_s, 0.0) } else { v(0.3, want_s - 0.3) };
        assert!((s.point_m - want).norm() < 1e-12, "sample {k}: {:?} against {want:?}", s.point_m);
    }
    // A step that does not divide the length: the end comes last, closer.
    let samples = arc.sample_equal(0.3);
    let s: Vec<f64> = samples.iter().map(|s| s.s_m).collect();
    assert_eq!(s.len(), 4);
    assert!((s[3] - 0.7).abs() < 1e-15 && (s[2] - 0.6).abs() < 1e-12);
}

/// Equal arc-length samples of a dense 2000-segment circle stay the step apart along it and lie on the
/// circle within the polyline's sag.
#[test]
fn samples_of_a_dense_circle_lie_on_it() {
    let points: Vec<Vector2<f64>> = (0..=2000)
        .map(|k| (k as f64 / 2000.0) * std::f64::consts::TAU)
        .map(|a| v(a.cos(), a.sin()) * 0.02)
        .collect();
    let arc = ArcPath::new(&SpeedPath::constant_speed(points, 0.02).expect("circle"));
    let d = 0.0005;
    let samples = arc.sample_equal(d);
    for w in samples.windows(2) {
        assert!((w[1].s_m - w[0].s_m - d).abs() < 1e-12 || w[1].s_m == arc.length_m());
        // The chord falls short of the arc by about d^3 / (24 r^2) = 1.3e-8 m.
        let shortfall = (w[1].s_m - w[0].s_m) - (w[1].point_m - w[0].point_m).norm();
        assert!((0.0..3e-8).contains(&shortfall), "{shortfall:.3e}");
    }
    // On the circle within the polyline's sag, r (1 - cos(pi / 2000)) = 2.5e-8 m.
    assert!(samples.iter().all(|s| (s.point_m.norm() - 0.02).abs() < 3e-8));
}

/// Time along a path follows its speed profile exactly: t = s / v at constant speed, and the closed form
/// for a speed linear in arc length.
#[test]
fn timing_follows_the_speed_profile_exactly() {
    // Constant speed: t = s / v.
    let path = SpeedPath::constant_speed(vec![v(0.0, 0.0), v(0.1, 0.0)], 0.02).expect("path");
    let arc = ArcPath::new(&path);
    assert!((arc.duration_s() - 5.0).abs() < 1e-12);
    assert!((arc.at_time(2.5).point_m.x - 0.05).abs() < 1e-12);
    // Speed linear in arc length, v = v0 + a s: t(s) = ln(v(s) / v0) / a, s(t) = v0 (e^(a t) - 1) / a.
    let (v0, v1, len) = (0.01, 0.03, 0.1);
    let path = SpeedPath::new(vec![v(0.0, 0.0), v(len, 0.0)], vec![v0, v1]).expect("path");
    let arc = ArcPath::new(&path);
    let a = (v1 - v0) / len;
    assert!((arc.duration_s() - (v1 / v0).ln() / a).abs() < 1e-12);
    for t in [0.0, 0.7, 2.0, 4.5, arc.duration_s()] {
        let s = v0 * (a * t).exp_m1() / a;
        let sample = arc.at_time(t);
        assert!((sample.s_m - s).abs() < 1e-12, "t = {t}: s = {} against {s}", sample.s_m);
        assert!((sample.speed_mps - (v0 + a * s)).abs() < 1e-12);
    }
}

/// The built-in double loop winds twice round its centre, peaks at its given speed, is 2 to 4 cm across,
/// and keeps its length when moved in its plane.
#[test]
fn the_double_loop_is_a_double_wrap_at_its_speed() {
    let centre = v(0.01, -0.02);
    let path = SpeedPath::double_loop(centre, 0.012, 0.02).expect("double loop");
    let mut angle = 0.0;
    for w in path.points_m.windows(2) {
        let (a, b) = (w[0] - centre, w[1] - centre);
        angle += a.perp(&b).atan2(a.dot(&b));
    }
    assert_eq!((angle / std::f64::consts::TAU).round(), 2.0);
    let top = path.speed_mps.iter().fold(0.0f64, |m, s| m.max(*s));
    assert!((top - 0.02).abs() < 1e-12);
    // About 2.5 cm across.
    let xs: Vec<f64> = path.points_m.iter().map(|p| p.x).collect();
    let width = xs.iter().fold(f64::MIN, |m, x| m.max(*x)) - xs.iter().fold(f64::MAX, |m, x| m.min(*x));
    assert!((0.02..0.04).contains(&width), "{width}");
    // Moving it in its plane moves every point.
    let moved = path.transformed(&Isometry2::new(v(0.1, 0.0), 0.5));
    assert!((moved.length_m() - path.length_m()).abs() < 1e-12);
}

/// A path of one point, a zero speed or a NaN point is refused naming the field, and one of no length or
/// with a speed count that does not match is refused too.
#[test]
fn bad_paths_name_the_field() {
    let err = SpeedPath::new(vec![v(0.0, 0.0)], vec![0.1]).expect_err("one point");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "path.points_m"), "{err}");
    let err = SpeedPath::new(vec![v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0)], vec![0.1, 0.0, 0.1])
        .expect_err("zero speed");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "path.speed_mps[1]"), "{err}");
    let err = SpeedPath::new(vec![v(0.0, 0.0), v(f64::NAN, 0.0)], vec![0.1, 0.1]).expect_err("NaN");
    assert!(matches!(&err, FluidError::Invalid { field, .. } if field == "path.points_m[1]"), "{err}");
    assert!(SpeedPath::new(vec![v(0.0, 0.0), v(0.0, 0.0)], vec![0.1, 0.1]).is_err());
    assert!(SpeedPath::new(vec![v(0.0, 0.0), v(1.0, 0.0)], vec![0.1]).is_err());
}

/// A zero, negative, NaN or vanishingly small sampling step gives a bounded number of samples ending at
/// the path's end instead of exhausting memory.
#[test]
fn a_degenerate_step_does_not_exhaust_memory() {
    let path = SpeedPath::constant_speed(vec![v(0.0, 0.0), v(0.1, 0.0)], 0.02).expect("path");
    let arc = ArcPath::new(&path);
    for d in [0.0, -1.0, f64::NAN, 1e-30] {
        let samples = arc.sample_equal(d);
        assert!(samples.len() <= 10_000_002, "d = {d}: {} samples", samples.len());
        assert_eq!(samples[samples.len() - 1].s_m, 0.1);
    }
}
