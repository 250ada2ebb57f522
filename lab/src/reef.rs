//! The two-throw knot trial: does the simulated thread hold a square (reef) knot once its free
//! ends are let go? Two strands are laid as a loose knot, snugged by all four ends, then
//! loaded by their standing parts (one held, one pulled, as the wound's loop pulls a tied stitch)
//! with both free ends let go. Used by the `thread_reef` benchmark and a regression test: a first
//! throw alone cannot hold (`cinch::run_holding`), so whether the second throw can decides what the
//! expert must tie.
//!
//! The loose knot is two bights collaring each other: the red strand lies flat (z = 0) as a bight
//! opening towards -x (its standing part along y = +1, its free end along y = -1, the bend at x > 1,
//! in units of `spread_m`); the blue strand comes from +x under the bend, rises through the red
//! bight, goes once round both of red's legs and goes back down through the bight and out to +x:
//! a square knot, as [`knotlab_sim::knot::classify()`] confirms (test below).

use knotlab_hw::geometry::segment_distance;
use nalgebra::Vector3;
use rapier3d::prelude::*;

use crate::cinch::{step_strands, strand_along};
use knotlab_sim::knot::{KnotType, classify};
use knotlab_sim::physics::{HealthError, Physics, SolverParams};
use knotlab_sim::thread::{Thread, ThreadParams};

/// The loose knot's two strands, each from its standing part to its free end, m.
pub struct LooseKnot {
    /// Red: standing part first (along y = +1, towards -x), then the bend, then the free end.
    pub red: Vec<Vector3<f64>>,
    /// Blue: standing part first (from +x), then the collar round red's legs, then the free end.
    pub blue: Vec<Vector3<f64>>,
}

/// The loose knot with its features `spread_m` apart (the red legs are `2 spread_m` apart), the
/// strands crossing `lift_m` above and below each other, and `tail_m` of straight strand from the
/// knot to each end.
pub fn loose_knot(spread_m: f64, lift_m: f64, tail_m: f64) -> LooseKnot {
    let u = spread_m;
    let h = lift_m;
    let l = tail_m / u + 2.5;
    let p = |x: f64, y: f64, z: f64| Vector3::new(x * u, y * u, z);
    // Red: the standing part from -x along y = +1, the bend round (1, 0), back along y = -1.
    let mut red = vec![p(-l, 1.0, 0.0), p(1.0, 1.0, 0.0)];
    let n = 24;
    red.extend((1..n).map(|k| {
        let a = std::f64::consts::PI * (0.5 - k as f64 / n as f64);
        p(1.0 + a.cos(), a.sin(), 0.0)
    }));
    red.extend([p(1.0, -1.0, 0.0), p(-l, -1.0, 0.0)]);
    // Blue: in from +x under the bend at y = +0.4, up through the bight, round both red legs (over
    // the y = +1 leg, under both, over the y = -1 leg), down through the bight, out under the bend.
    let blue = vec![
        p(l, 0.4, -h),
        p(2.5, 0.4, -h),
        p(0.4, 0.4, -h),
        p(0.0, 0.4, h),
        p(-0.5, 0.4, h),
        p(-0.5, 1.7, h),
        p(-0.7, 1.7, -h),
        p(-0.7, -1.7, -h),
        p(-0.9, -1.7, h),
        p(-0.9, -0.4, h),
        p(0.0, -0.4, h),
        p(0.4, -0.4, -h),
        p(2.5, -0.4, -h),
        p(l, -0.4, -h),
    ];
    LooseKnot { red, blue }
}

impl LooseKnot {
    /// The two strands as one open thread ([`as_stitch`]).
    pub fn as_stitch(&self) -> Vec<Vector3<f64>> {
        as_stitch(&self.red, &self.blue)
    }
}

/// Two strands (each from its standing part to its free end, the red standing part towards -x, the
/// blue towards +x) as one open thread, as a stitch makes them: red's free end, red, its standing
/// part, a loop far below the knot (the stitch through the tissue), blue's standing part, blue,
/// blue's free end. Its knot type is the knot's.
pub fn as_stitch(red: &[Vector3<f64>], blue: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let (red_stand, blue_stand) = (red[0], blue[0]);
    let far = 4.0 * (red_stand - blue_stand).norm();
    let mut line: Vec<Vector3<f64>> = red.iter().rev().copied().collect();
    line.push(red_stand - Vector3::x() * 0.1 * far);
    line.push(Vector3::new(red_stand.x - 0.1 * far, 0.0, -far));
    line.push(Vector3::new(blue_stand.x + 0.1 * far, 0.0, -far));
    line.push(blue_stand + Vector3::x() * 0.1 * far);
    line.extend(blue.iter().copied());
    line
}

/// How the trial goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReefParams {
    /// How far apart the loose knot's features lie (red's legs are twice this apart), m.
    pub spread_m: f64,
    /// How far above and below each other the strands cross in the loose knot, m.
    pub lift_m: f64,
    /// Straight strand from the knot to each end, m.
    pub tail_m: f64,
    /// All four ends pulled out with this tension first, N ...
    pub snug_n: f64,
    /// ... for this long, s, ...
    pub snug_s: f64,
    /// ... every segment's velocity damped at this rate meanwhile, 1/s (the slack drawn in slowly,
    /// so that no strand passes through another on the way).
    pub snug_damping_per_s: f64,
    /// Then, if not zero, red's two ends are pulled apart with `snug_n` for this long, s (its free end
    /// to +x, in line with its standing part, blue's ends slack, the damping kept): red is drawn
    /// straight and blue's collar lies wound round it. The knot capsizes, as a surgeon's capsizes when
    /// one end is pulled in line with its own leg; its type does not change.
    pub capsize_s: f64,
    /// Then red's standing part is held where it is and blue's pulled with this tension, N ...
    pub load_n: f64,
    /// ... for this long, s.
    pub hold_s: f64,
    /// The free ends let go for the load (else held where the snug left them).
    pub release_free: bool,
}

impl ReefParams {
    /// The trial as the bench and the tests run it: the loose knot's features `spread_m` apart, 2 mm
    /// lift, 30 mm tails; snugged at 1 N for 2 s under 200/s damping; then `load_n` for 2 s.
    pub fn snug_then_load(spread_m: f64, load_n: f64, release_free: bool) -> Self {
        Self {
            spread_m,
            lift_m: 0.002,
            tail_m: 0.03,
            snug_n: 1.0,
            snug_s: 2.0,
            snug_damping_per_s: 200.0,
            capsize_s: 0.0,
            load_n,
            hold_s: 2.0,
            release_free,
        }
    }
}

/// What the trial measured.
#[derive(Clone, Debug, PartialEq)]
pub struct ReefOutcome {
    /// The smallest gap between two capsules of the strands as laid (not neighbours), m; negative:
    /// they overlap and the knot is no test.
    pub clearance_m: f64,
    /// The knot as laid, ...
    pub knot_laid: KnotType,
    /// ... after the snug (and the capsize, if any), ...
    pub knot_snug: KnotType,
    /// How far red's two ends lie apart along red, as a fraction of red's length, as the load
    /// begins: about 1 once red is drawn straight (capsized), well under 1 while it is a bight.
    pub red_straightness: f64,
    /// ... and after the load.
    pub knot_end: KnotType,
    /// How far blue's standing part moved along its pull while loaded, m ...
    pub slip_m: f64,
    /// ... in the last half of that time, m.
    pub late_slip_m: f64,
    /// Steps taken.
    pub steps: usize,
}

/// The knot type of the two strands as they lie (`Unknown` if the centreline is unusable).
fn knot_of(physics: &Physics, red: &Thread, blue: &Thread) -> KnotType {
    classify(&as_stitch(&red.centreline(physics), &blue.centreline(physics)))
        .map(|c| c.knot)
        .unwrap_or(KnotType::Unknown)
}

/// The smallest gap between the capsules of `strands` that are not neighbours on one strand, m.
fn gap_m(physics: &Physics, strands: &[&Thread], radius_m: f64) -> f64 {
    let capsules: Vec<(usize, usize, _)> = strands
        .iter()
        .enumerate()
        .flat_map(|(s, t)| t.capsules(physics, radius_m).into_iter().enumerate().map(move |(i, c)| (s, i, c)))
        .collect();
    let mut gap = f64::INFINITY;
    for (k, (s, i, p)) in capsules.iter().enumerate() {
        for (t, j, q) in &capsules[k + 1..] {
            if s == t && j - i < 2 {
                continue;
            }
            gap = gap.min(segment_distance(&p.a_m, &p.b_m, &q.a_m, &q.b_m) - 2.0 * radius_m);
        }
    }
    gap
}

/// Holds `body` where it is, as jaws hold it.
fn clamp(physics: &mut Physics, body: RigidBodyHandle) {
    let pose = *physics.bodies[body].position();
    let anchor = physics.bodies.insert(RigidBodyBuilder::fixed().pose(pose));
    physics.impulse_joints.insert(anchor, body, FixedJointBuilder::new(), true);
}

/// Lays the loose knot with `thread`'s material and segment length (no gravity), snugs it by all four
/// ends, then loads it by its standing parts with its free ends let go or held, as `params` says.
pub fn run_reef(
    solver: &SolverParams,
    thread: &ThreadParams,
    params: &ReefParams,
) -> Result<ReefOutcome, HealthError> {
    let mut physics = Physics::new(solver);
    physics.gravity = Vector::ZERO;
    let knot = loose_knot(params.spread_m, params.lift_m, params.tail_m);
    let red = strand_along(&mut physics, thread, &knot.red);
    let blue = strand_along(&mut physics, thread, &knot.blue);
    let clearance_m = gap_m(&physics, &[&red, &blue], thread.radius_m);
    let knot_laid = knot_of(&physics, &red, &blue);
    let last = |t: &Thread| t.segments[t.segments.len() - 1];
    // (body, pull direction along x): red's ends go to -x, blue's to +x.
    let (red_stand, red_free, blue_stand, blue_free) =
        (red.segments[0], last(&red), blue.segments[0], last(&blue));
    for h in [red_stand, red_free, blue_stand, blue_free] {
        physics.bodies[h].lock_rotations(true, true);
    }
    let segments: Vec<RigidBodyHandle> = red.segments.iter().chain(&blue.segments).copied().collect();
    let damp = |physics: &mut Physics, per_s: f64| {
        for h in &segments {
            physics.bodies[*h].set_linear_damping(per_s);
        }
    };
    damp(&mut physics, params.snug_damping_per_s);
    let capsize_steps = (params.capsize_s / physics.dt_s()).round() as usize;
    let snug_steps = (params.snug_s / physics.dt_s()).round() as usize + capsize_steps;
    let hold_steps = (params.hold_s / physics.dt_s()).round() as usize;
    let along = |physics: &Physics| physics.bodies[blue_stand].translation().x;
    let red_length_m = red.segment_length_m * red.segments.len() as f64;
    let (mut at_start, mut at_half, mut knot_snug, mut red_straightness) = (0.0, 0.0, KnotType::Unknown, 0.0);
    for step in 0..snug_steps + hold_steps {
        if step == snug_steps {
            at_start = along(&physics);
            knot_snug = knot_of(&physics, &red, &blue);
            let ends = physics.bodies[red_free].translation() - physics.bodies[red_stand].translation();
            red_straightness = ends.length() / red_length_m;
            damp(&mut physics, thread.linear_damping_per_s);
            clamp(&mut physics, red_stand);
            for h in [red_free, blue_free] {
                if params.release_free {
                    physics.bodies[h].lock_rotations(false, true);
                } else {
                    clamp(&mut physics, h);
                }
            }
        }
        if step == snug_steps + hold_steps / 2 {
            at_half = along(&physics);
        }
        let ramp = (2.0 * step as f64 / (snug_steps - capsize_steps) as f64).min(1.0);
        let forces: [(RigidBodyHandle, f64); 4] = if step >= snug_steps - capsize_steps && step < snug_steps {
            let f = params.snug_n;
            [(red_stand, -f), (red_free, f), (blue_stand, 0.0), (blue_free, 0.0)]
        } else if step < snug_steps {
            let f = params.snug_n * ramp;
            [(red_stand, -f), (red_free, -f), (blue_stand, f), (blue_free, f)]
        } else {
            [(red_stand, 0.0), (red_free, 0.0), (blue_stand, params.load_n), (blue_free, 0.0)]
        };
        for (h, force_n) in forces {
            let body = &mut physics.bodies[h];
            body.reset_forces(true);
            body.add_force(Vector::new(force_n, 0.0, 0.0), true);
        }
        step_strands(&mut physics, thread)?;
    }
    let at_end = along(&physics);
    Ok(ReefOutcome {
        clearance_m,
        knot_laid,
        knot_snug,
        red_straightness,
        knot_end: knot_of(&physics, &red, &blue),
        slip_m: at_end - at_start,
        late_slip_m: at_end - at_half,
        steps: snug_steps + hold_steps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The laid loose knot classifies as a square knot, and with blue's free end led out over the bend
    /// instead it classifies as a single throw (a trefoil).
    #[test]
    fn the_loose_knot_is_a_square_knot() {
        let knot = loose_knot(0.003, 0.0015, 0.03);
        let found = classify(&knot.as_stitch()).unwrap();
        assert_eq!(found.knot, KnotType::Square, "{found:?}");
        // Blue's free end led out over red's bend instead of back down through the bight: a single
        // throw.
        let mut single = loose_knot(0.003, 0.0015, 0.03);
        let n = single.blue.len();
        for p in &mut single.blue[n - 3..] {
            p.z = -p.z;
        }
        assert_eq!(classify(&single.as_stitch()).unwrap().knot, KnotType::Trefoil);
    }
}
