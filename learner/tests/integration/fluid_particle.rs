//! Particle tracing: fourth order in time on the staggered grid's bilinear velocities, linear between a
//! step's two fields, and never inside an obstacle cell even when the velocity points straight into one.

use knotlab_learner::fluid::ObstacleMask;
use knotlab_learner::fluid::flags::Flags;
use knotlab_learner::fluid::particle::{FlowInterval, Particle};
use nalgebra::Vector2;

const N: usize = 40;
const H: f64 = 0.001;

/// `u` and `v` arrays (ghosts included) sampled from a velocity function at the face positions.
fn field(velocity: impl Fn(Vector2<f64>) -> Vector2<f64>) -> (Vec<f64>, Vec<f64>) {
    let stride = N + 2;
    let mut u = vec![0.0; stride * stride];
    let mut v = vec![0.0; stride * stride];
    for j in 0..stride {
        for i in 0..stride {
            let k = j * stride + i;
            u[k] = velocity(Vector2::new(i as f64 * H, (j as f64 - 0.5) * H)).x;
            v[k] = velocity(Vector2::new((i as f64 - 0.5) * H, j as f64 * H)).y;
        }
    }
    (u, v)
}

/// Traces a particle in a steady field for `duration` in steps of `dt`.
fn trace(
    flags: &Flags,
    u: &[f64],
    v: &[f64],
    start: Vector2<f64>,
    duration: f64,
    dt: f64,
    max_speed: f64,
) -> Particle {
    let mut particle = Particle::new(start, 0.0);
    let steps = (duration / dt).round() as usize;
    for k in 0..steps {
        let flow = FlowInterval {
            start: (u, v),
            end: (u, v),
            t0_s: k as f64 * dt,
            t1_s: (k + 1) as f64 * dt,
            max_speed_mps: max_speed,
        };
        particle.advance(flags, &flow);
    }
    particle
}

/// A particle in solid-body rotation closes its circle within 1e-5 m in 40 steps, and the tracer's
/// observed order in time stays above 3.5.
#[test]
fn solid_body_rotation_closes_its_circle_at_fourth_order() {
    // u = -w (y - c), v = w (x - c): linear, so bilinear interpolation is exact and only the time
    // integration errs.
    let flags = Flags::new(&ObstacleMask::free(N), H).expect("flags");
    let c = 0.5 * N as f64 * H;
    let w = 1.0;
    let (u, v) = field(|p| Vector2::new(-w * (p.y - c), w * (p.x - c)));
    let start = Vector2::new(c + 0.012, c);
    let period = std::f64::consts::TAU / w;
    // max_speed tiny: one substep per step, so the step is what we choose.
    let error = |steps: usize| {
        let p = trace(&flags, &u, &v, start, period, period / steps as f64, 1e-12);
        (p.position_m() - start).norm()
    };
    let (coarse, fine) = (error(40), error(80));
    assert!(coarse < 1e-5, "{coarse}");
    let order = (coarse / fine).log2();
    assert!(order > 3.5, "observed order {order:.2} (errors {coarse:.3e}, {fine:.3e})");
}

/// Across a step whose velocity goes from 1 to 3 mm/s the particle travels at the mean, and its recorded
/// substeps are at most a quarter cell long.
#[test]
fn velocities_are_interpolated_between_the_two_time_levels() {
    // u = 1 m/s at the start of the step, 3 m/s at its end: the particle travels the mean, 2 m/s.
    let flags = Flags::new(&ObstacleMask::free(N), H).expect("flags");
    let (u0, v0) = field(|_| Vector2::new(0.001, 0.0));
    let (u1, v1) = field(|_| Vector2::new(0.003, 0.0));
    let mut particle = Particle::new(Vector2::new(0.005, 0.02), 0.0);
    let flow =
        FlowInterval { start: (&u0, &v0), end: (&u1, &v1), t0_s: 0.0, t1_s: 2.0, max_speed_mps: 0.003 };
    particle.advance(&flags, &flow);
    assert!((particle.position_m().x - (0.005 + 0.004)).abs() < 1e-15);
    // Substeps of at most a quarter cell were recorded.
    assert!(particle.trace.len() > 24);
    assert!(particle.trace.windows(2).all(|w| (w[1].1 - w[0].1).norm() <= 0.25 * H + 1e-15));
}

/// A uniform flow straight into a block never puts a traced position inside it nor a step across it;
/// the particle reaches the block and is held there or slides past.
#[test]
fn a_flow_straight_into_an_obstacle_never_carries_the_particle_inside() {
    // A uniform stream toward a block: no no-slip layer here, the velocity does not vanish at the
    // block, so only the enforcement keeps the particle out.
    let mut mask = ObstacleMask::free(N);
    for j in 10..30 {
        for i in 20..24 {
            mask.set(i, j, true);
        }
    }
    let flags = Flags::new(&mask, H).expect("flags");
    let (u, v) = field(|_| Vector2::new(0.01, 0.002));
    for (k, y) in [0.012, 0.015, 0.02, 0.025, 0.026].iter().enumerate() {
        let p = trace(&flags, &u, &v, Vector2::new(0.005, *y), 3.0, 0.05, 0.0102);
        for (t, q) in &p.trace {
            let (i, j) = ((q.x / H).floor() as usize, (q.y / H).floor() as usize);
            assert!(!mask.get(i, j), "start {k}: inside ({i}, {j}) at t = {t}");
        }
        for w in p.trace.windows(2) {
            assert!(
                knotlab_learner::fluid::particle::segment_free(&flags, w[0].1, w[1].1),
                "start {k}: a step crosses an obstacle"
            );
        }
        // It did press against the block and was held there, or slid past it over the top.
        assert!(p.splits > 0, "start {k}: never reached the block");
    }
}

/// A particle carried towards the grid's walls stays inside the grid, held at the wall once it gets there.
#[test]
fn the_particle_never_leaves_the_grid() {
    let flags = Flags::new(&ObstacleMask::free(N), H).expect("flags");
    let (u, v) = field(|_| Vector2::new(-0.004, -0.01));
    let p = trace(&flags, &u, &v, Vector2::new(0.02, 0.02), 10.0, 0.1, 0.011);
    let size = N as f64 * H;
    assert!(p.trace.iter().all(|(_, q)| q.x >= 0.0 && q.y >= 0.0 && q.x < size && q.y < size));
    assert!(p.holds > 0, "it reached the wall and stayed");
}
