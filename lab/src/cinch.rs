//! The thread's contact strength under a cinch: a strand (`B`) wound twice round another (`A`, both
//! ends held), as in a surgeon's throw, its two ends pulled apart with a tension rising linearly (no
//! gravity). A knot is made of strands that block each other; pulled harder than its contacts hold,
//! one strand passes through the other and the throw comes undone. Used by the `thread_cinch`
//! benchmark (which sweeps the solver's settings) and by a regression test; the capstan trial (one
//! end pulled harder than the other) by `thread_capstan`; the holding trial (the throw's free ends let
//! go, the loop pulling) by `thread_holding`.

use std::f64::consts::TAU;

use knotlab_hw::geometry::segment_distance;
use nalgebra::Vector3;
use rapier3d::prelude::*;

use knotlab_sim::convert::to_na;
use knotlab_sim::hooks::ThreadOnItself;
use knotlab_sim::physics::{HealthError, Physics, SolverParams};
use knotlab_sim::thread::{Thread, ThreadParams};
use knotlab_sim::tunnelling::{Capsule, TunnellingMonitor};

/// The helix B is laid on before the pull tightens it: radius and advance per turn, m.
const HELIX_RADIUS_M: f64 = 0.0025;
const HELIX_PITCH_M: f64 = 0.0025;
/// Straight thread before and after the turns, m.
const TAIL_M: f64 = 0.02;
/// Length of the held strand A, m.
const HELD_LENGTH_M: f64 = 0.06;
/// Turns of B round A.
const TURNS: f64 = 2.0;

/// How the pull goes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CinchParams {
    /// The tension the pull rises to, N.
    pub top_tension_n: f64,
    /// How long it takes to get there, s.
    pub ramp_s: f64,
    /// Continuous collision detection on every segment.
    pub ccd: bool,
}

/// What a cinch measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CinchOutcome {
    /// The tension when a strand first passed through another, N (`None`: the turns held).
    pub first_pass_tension_n: Option<f64>,
    /// The tension when B's winding round A had fallen by half a turn or more, N (`None`: it never
    /// did). Catches a turn lost however it went, the tunnelling monitor's misses included.
    pub turn_lost_tension_n: Option<f64>,
    /// Passes counted (a strand passing exactly at a joint counts twice).
    pub passes: usize,
    /// The deepest overlap of two segments' axes before the first pass, as a fraction of the touching
    /// distance (twice the radius).
    pub deepest_overlap: f64,
    /// B's winding round A at the start, turns (two turns and nearly a quarter turn for each tail).
    pub turns_start: f64,
    /// ... and at the end.
    pub turns_end: f64,
    /// How tight the turns lie round A at the end: the median distance of B's joints within 3 mm of
    /// A's axis from it, m (the touching distance is twice the radius; `None`: no joint that close).
    pub wrap_radius_m: Option<f64>,
    /// The length of B within 3 mm of A's axis at the end, m (two tight turns: about 4 pi times the
    /// touching distance).
    pub wrap_length_m: f64,
    /// Steps taken.
    pub steps: usize,
}

/// How many times `b` winds round `a` (a polyline roughly along x): the angle of each point of `b`
/// about its nearest point on `a`, in the y-z plane, summed along `b`, in turns.
pub fn winding_turns(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    let angle = |p: &Vector3<f64>| {
        let nearest = a
            .windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                let t = ((p - w[0]).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                w[0] + d * t
            })
            .min_by(|x, y| (p - x).norm().total_cmp(&(p - y).norm()))
            .unwrap_or(*p);
        let o = p - nearest;
        o.z.atan2(o.y)
    };
    let angles: Vec<f64> = b.iter().map(angle).collect();
    let total: f64 = angles
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            d - TAU * (d / TAU).round()
        })
        .sum();
    total / TAU
}

/// How close to A a joint of B must be to count as part of the turns, m.
const WRAP_ZONE_M: f64 = 0.003;

/// The median distance from `a` of `b`'s points within `zone_m` of it, and the length of `b` between
/// such points.
fn wrap_tightness(a: &[Vector3<f64>], b: &[Vector3<f64>], zone_m: f64) -> (Option<f64>, f64) {
    let distance = |p: &Vector3<f64>| {
        a.windows(2).map(|w| segment_distance(&w[0], &w[1], p, p)).fold(f64::INFINITY, f64::min)
    };
    let d: Vec<f64> = b.iter().map(distance).collect();
    let length_m = b
        .windows(2)
        .zip(d.windows(2))
        .filter(|(_, dd)| dd[0] < zone_m && dd[1] < zone_m)
        .map(|(w, _)| (w[1] - w[0]).norm())
        .sum();
    let mut near: Vec<f64> = d.into_iter().filter(|&x| x < zone_m).collect();
    near.sort_by(f64::total_cmp);
    (near.get(near.len() / 2).copied(), length_m)
}

/// B's path: a tail along -z into two turns round the x axis, a tail along +z out of them.
fn wound_path() -> Vec<Vector3<f64>> {
    let advance = HELIX_PITCH_M * TURNS;
    let start = Vector3::new(-0.5 * advance, HELIX_RADIUS_M, 0.0);
    let mut points = vec![start - Vector3::z() * TAIL_M, start];
    let n = 200;
    for k in 1..=n {
        let f = k as f64 / n as f64;
        let theta = TAU * TURNS * f;
        points.push(Vector3::new(
            -0.5 * advance + advance * f,
            HELIX_RADIUS_M * theta.cos(),
            HELIX_RADIUS_M * theta.sin(),
        ));
    }
    let end = points[points.len() - 1];
    points.push(end + Vector3::z() * TAIL_M);
    points
}

/// Pins one end of `thread` where it lies: free to turn, or (`clamped`) held as jaws hold it.
fn hold_end(physics: &mut Physics, thread: &Thread, first: bool, clamped: bool) -> ImpulseJointHandle {
    let half = 0.5 * thread.segment_length_m;
    let (segment, local_x) =
        if first { (thread.segments[0], -half) } else { (thread.segments[thread.segments.len() - 1], half) };
    let pose = *physics.bodies[segment].position();
    let at = pose.transform_point(Vector::new(local_x, 0.0, 0.0));
    let anchor = physics.bodies.insert(RigidBodyBuilder::fixed().translation(at));
    let joint: GenericJoint = if clamped {
        FixedJointBuilder::new()
            .local_frame1(Pose::from_parts(Vector::ZERO, pose.rotation))
            .local_anchor2(Vector::new(local_x, 0.0, 0.0))
            .into()
    } else {
        SphericalJointBuilder::new().local_anchor2(Vector::new(local_x, 0.0, 0.0)).into()
    };
    physics.impulse_joints.insert(anchor, segment, joint, true)
}

/// A strand of `thread`'s material and segment length laid along `path` (as many whole segments as
/// the path holds), at rest.
pub(crate) fn strand_along(physics: &mut Physics, thread: &ThreadParams, path: &[Vector3<f64>]) -> Thread {
    let path_m: f64 = path.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
    let segment_m = thread.segment_length_m();
    let segments = ((path_m / segment_m).floor() as usize).max(2);
    let params = ThreadParams { length_m: segments as f64 * segment_m, segments, ..*thread };
    let strand = Thread::build(physics, &params, &path[0], &Vector3::x());
    strand.lay_along(physics, path);
    strand
}

/// The two phases of a trial: a snug (`snug_s`), then a hold (`hold_s`), in steps of `dt_s`.
struct Phases {
    snug_steps: usize,
    hold_steps: usize,
}

impl Phases {
    fn new(dt_s: f64, snug_s: f64, hold_s: f64) -> Self {
        Self { snug_steps: (snug_s / dt_s).round() as usize, hold_steps: (hold_s / dt_s).round() as usize }
    }

    fn steps(&self) -> usize {
        self.snug_steps + self.hold_steps
    }

    /// The step the hold starts at ...
    fn hold_start(&self) -> usize {
        self.snug_steps
    }

    /// ... and the step half way through it.
    fn hold_half(&self) -> usize {
        self.snug_steps + self.hold_steps / 2
    }

    /// The snug's tension ramp at `step`: from 0 to 1 over the snug's first half.
    fn ramp(&self, step: usize) -> f64 {
        (2.0 * step as f64 / self.snug_steps as f64).min(1.0)
    }
}

/// One step of a trial's strands, contacts of the thread with itself taking its own friction.
pub(crate) fn step_strands(physics: &mut Physics, thread: &ThreadParams) -> Result<(), HealthError> {
    let label = |_| "thread segment".to_owned();
    match ThreadOnItself::of(thread) {
        Some(hook) => physics.step_with_hooks(&hook, &label),
        None => physics.step(&label),
    }
}

/// Steps `physics` through `phases`, pulling the two ends of a strand along z with the forces
/// `forces(step)` gives (`(first_z_n, last_z_n)`, each set fresh every step), and returns the first
/// end's height at the hold's start, half way through it and at the end, m.
fn pull_ends(
    physics: &mut Physics,
    thread: &ThreadParams,
    phases: &Phases,
    (first, last): (RigidBodyHandle, RigidBodyHandle),
    forces: impl Fn(usize) -> (f64, f64),
) -> Result<(f64, f64, f64), HealthError> {
    let z_of = |physics: &Physics| physics.bodies[first].translation().z;
    let (mut z_start, mut z_half) = (0.0, 0.0);
    for step in 0..phases.steps() {
        if step == phases.hold_start() {
            z_start = z_of(physics);
        }
        if step == phases.hold_half() {
            z_half = z_of(physics);
        }
        let (first_n, last_n) = forces(step);
        for (h, force_n) in [(first, first_n), (last, last_n)] {
            let body = &mut physics.bodies[h];
            body.reset_forces(true);
            body.add_force(Vector::new(0.0, 0.0, force_n), true);
        }
        step_strands(physics, thread)?;
    }
    Ok((z_start, z_half, z_of(physics)))
}

/// A world without gravity holding A (both ends pinned) and B wound twice round it, with `thread`'s
/// material and segment length, and the joints that hold A's first and last ends.
fn wound_pair(
    solver: &SolverParams,
    thread: &ThreadParams,
    clamped: bool,
) -> (Physics, Thread, Thread, [ImpulseJointHandle; 2]) {
    let mut physics = Physics::new(solver);
    physics.gravity = Vector::ZERO;
    let segment_m = thread.segment_length_m();
    let a_segments = ((HELD_LENGTH_M / segment_m).round() as usize).max(2);
    let a_params = ThreadParams { length_m: a_segments as f64 * segment_m, segments: a_segments, ..*thread };
    let a = Thread::build(
        &mut physics,
        &a_params,
        &Vector3::new(-0.5 * a_params.length_m, 0.0, 0.0),
        &Vector3::x(),
    );
    let a_joints = [hold_end(&mut physics, &a, true, clamped), hold_end(&mut physics, &a, false, clamped)];
    let b = strand_along(&mut physics, thread, &wound_path());
    (physics, a, b, a_joints)
}

/// Winds B twice round A with `thread`'s material and segment length, pulls B's ends apart as
/// `params` says, and watches every pair of A and B, and of B with itself.
pub fn run_cinch(
    solver: &SolverParams,
    thread: &ThreadParams,
    params: &CinchParams,
) -> Result<CinchOutcome, HealthError> {
    let (mut physics, a, b, _) = wound_pair(solver, thread, false);
    if params.ccd {
        for h in a.segments.iter().chain(&b.segments) {
            physics.bodies[*h].enable_ccd(true);
        }
    }
    let (na, nb) = (a.segments.len(), b.segments.len());
    let pairs: Vec<(usize, usize)> = (0..na)
        .flat_map(|i| (0..nb).map(move |j| (i, na + j)))
        .chain((0..nb).flat_map(|i| (i + 2..nb).map(move |j| (na + i, na + j))))
        .collect();
    let radius_m = thread.radius_m;
    let mut monitor = TunnellingMonitor::new(2.0 * radius_m);
    let ends = [(b.segments[0], -1.0), (b.segments[nb - 1], 1.0)];
    let dt_s = physics.dt_s();
    let steps = (params.ramp_s / dt_s).round() as usize;
    let mut outcome = CinchOutcome {
        first_pass_tension_n: None,
        turn_lost_tension_n: None,
        passes: 0,
        deepest_overlap: 0.0,
        turns_start: winding_turns(&a.centreline(&physics), &b.centreline(&physics)),
        turns_end: 0.0,
        wrap_radius_m: None,
        wrap_length_m: 0.0,
        steps,
    };
    for step in 0..steps {
        let tension_n = params.top_tension_n * (step as f64 * dt_s) / params.ramp_s;
        for (h, sign) in ends {
            let body = &mut physics.bodies[h];
            body.reset_forces(true);
            body.add_force(Vector::new(0.0, 0.0, sign * tension_n), true);
        }
        step_strands(&mut physics, thread)?;
        let mut capsules: Vec<Capsule> = a.capsules(&physics, radius_m);
        capsules.extend(b.capsules(&physics, radius_m));
        if monitor.update(&capsules, pairs.iter().copied()) > 0 && outcome.first_pass_tension_n.is_none() {
            outcome.first_pass_tension_n = Some(tension_n);
        }
        if outcome.turn_lost_tension_n.is_none()
            && step % 10 == 0
            && winding_turns(&a.centreline(&physics), &b.centreline(&physics)) < outcome.turns_start - 0.5
        {
            outcome.turn_lost_tension_n = Some(tension_n);
        }
        if outcome.first_pass_tension_n.is_none() {
            for &(i, j) in &pairs {
                let (p, q) = (&capsules[i], &capsules[j]);
                let distance_m = segment_distance(&p.a_m, &p.b_m, &q.a_m, &q.b_m);
                outcome.deepest_overlap = outcome.deepest_overlap.max(1.0 - distance_m / (2.0 * radius_m));
            }
        }
    }
    outcome.passes = monitor.events;
    let (a_line, b_line) = (a.centreline(&physics), b.centreline(&physics));
    outcome.turns_end = winding_turns(&a_line, &b_line);
    (outcome.wrap_radius_m, outcome.wrap_length_m) = wrap_tightness(&a_line, &b_line, WRAP_ZONE_M);
    Ok(outcome)
}

/// The capstan trial: B's turns first snugged round A with both ends pulled alike, then one end pulled
/// harder than the other.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapstanParams {
    /// Both ends pulled with this tension first, N ...
    pub snug_n: f64,
    /// ... for this long, s.
    pub snug_s: f64,
    /// Then B's first end is pulled with this tension, N ...
    pub high_n: f64,
    /// ... and its last end with this one, N ...
    pub low_n: f64,
    /// ... for this long, s.
    pub hold_s: f64,
    /// Every end held as jaws hold a thread, so that no strand can spin about its axis: A's ends
    /// clamped, B's end segments kept from turning (`false`: A's ends pinned, free to turn, and B's
    /// ends free).
    pub held_as_jaws: bool,
}

/// What the capstan trial measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CapstanOutcome {
    /// How far B slid round A towards its harder-pulled end while the tensions differed, m.
    pub slip_m: f64,
    /// ... in the last half of that time, m (near zero when friction holds; a slide goes on).
    pub late_slip_m: f64,
    /// B's winding round A at the end, turns.
    pub turns_end: f64,
    /// Whether B slid until its other end was drawn up to A (held, that end then jams there: the
    /// slide stopped for that reason, not by friction).
    pub slid_to_end: bool,
    /// Steps taken.
    pub steps: usize,
}

/// B's end segment this close to A's axis has slid to its end, m.
const END_NEAR_M: f64 = 0.005;

/// The capstan equation's bound for B's turns round A: friction holds while `high / low` stays below
/// `exp(friction * angle)`; the angle B's two turns wrap is 4 pi.
pub fn capstan_ratio(friction: f64) -> f64 {
    (friction * 2.0 * TAU).exp()
}

/// Winds B twice round A, snugs the turns and then pulls B's ends with different tensions, as `params`
/// says: friction between the strands holds B while the ratio of the tensions stays below
/// [`capstan_ratio`], and B slides round A beyond it.
pub fn run_capstan(
    solver: &SolverParams,
    thread: &ThreadParams,
    params: &CapstanParams,
) -> Result<CapstanOutcome, HealthError> {
    let (mut physics, a, b, _) = wound_pair(solver, thread, params.held_as_jaws);
    let nb = b.segments.len();
    let (first, last) = (b.segments[0], b.segments[nb - 1]);
    if params.held_as_jaws {
        for h in [first, last] {
            physics.bodies[h].lock_rotations(true, true);
        }
    }
    let phases = Phases::new(physics.dt_s(), params.snug_s, params.hold_s);
    // B's first end lies along -z, its last along +z: each pulled outwards.
    let (z_start, z_half, z_end) = pull_ends(&mut physics, thread, &phases, (first, last), |step| {
        let (first_n, last_n) = if step < phases.hold_start() {
            let ramp = phases.ramp(step);
            (params.snug_n * ramp, params.snug_n * ramp)
        } else {
            (params.high_n, params.low_n)
        };
        (-first_n, last_n)
    })?;
    let a_line = a.centreline(&physics);
    let end_m = physics.bodies[last].translation();
    let end_m = to_na(end_m);
    let end_from_a_m = a_line
        .windows(2)
        .map(|w| segment_distance(&w[0], &w[1], &end_m, &end_m))
        .fold(f64::INFINITY, f64::min);
    Ok(CapstanOutcome {
        slid_to_end: end_from_a_m < END_NEAR_M,
        slip_m: z_start - z_end,
        late_slip_m: z_half - z_end,
        turns_end: winding_turns(&a_line, &b.centreline(&physics)),
        steps: phases.steps(),
    })
}

/// The holding trial: a throw as the knot leaves it when the instruments let go. B's turns are first
/// snugged round A (A's ends held as jaws hold them, B's ends pulled alike); then the loop pulls on
/// the throw: A's first end stays held (the loop's anchor), B's last end is pulled along its tail with
/// the loop's tension, as the wound pulls on a tied stitch, and the free ends (A's last, B's first)
/// are let go or kept as `params` says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoldingParams {
    /// Both of B's ends pulled with this tension first, N ...
    pub snug_n: f64,
    /// ... for this long, s.
    pub snug_s: f64,
    /// Then the loop's tension on B's loaded end, N ...
    pub loop_n: f64,
    /// ... for this long, s.
    pub hold_s: f64,
    /// A's free end let go (else it stays held).
    pub release_a: bool,
    /// B's free end let go (else it is held where the snug left it, as jaws hold it).
    pub release_b: bool,
}

/// What the holding trial measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HoldingOutcome {
    /// How far B's loaded end moved along the loop's pull while it pulled, m (a throw that holds
    /// settles by a few mm and stops; one that slips goes on).
    pub slip_m: f64,
    /// ... in the last half of that time, m.
    pub late_slip_m: f64,
    /// B's winding round A at the end of the snug, turns ...
    pub turns_snug: f64,
    /// ... and at the end, turns (a throw that came undone: under one).
    pub turns_end: f64,
    /// Steps taken.
    pub steps: usize,
}

/// Winds B twice round A, snugs the turns, then pulls the loop's ends with the free ends let go or
/// kept, as `params` says: does a snug throw hold the loop's tension once its free ends are free?
pub fn run_holding(
    solver: &SolverParams,
    thread: &ThreadParams,
    params: &HoldingParams,
) -> Result<HoldingOutcome, HealthError> {
    let (mut physics, a, b, a_joints) = wound_pair(solver, thread, true);
    let nb = b.segments.len();
    // B's first end lies along -z (its free end), its last along +z (pulled by the loop).
    let (free, loaded) = (b.segments[0], b.segments[nb - 1]);
    for h in [free, loaded] {
        physics.bodies[h].lock_rotations(true, true);
    }
    let phases = Phases::new(physics.dt_s(), params.snug_s, params.hold_s);
    let along = |physics: &Physics| physics.bodies[loaded].translation().z;
    let (mut at_start, mut at_half, mut turns_snug) = (0.0, 0.0, 0.0);
    for step in 0..phases.steps() {
        if step == phases.hold_start() {
            at_start = along(&physics);
            turns_snug = winding_turns(&a.centreline(&physics), &b.centreline(&physics));
            if params.release_a {
                physics.impulse_joints.remove(a_joints[1], true);
            }
            if params.release_b {
                physics.bodies[free].lock_rotations(false, true);
            } else {
                let pose = *physics.bodies[free].position();
                let anchor = physics.bodies.insert(RigidBodyBuilder::fixed().pose(pose));
                physics.impulse_joints.insert(anchor, free, FixedJointBuilder::new(), true);
            }
        }
        if step == phases.hold_half() {
            at_half = along(&physics);
        }
        let ramp = phases.ramp(step);
        let (free_n, loaded_n) = if step < phases.hold_start() {
            (params.snug_n * ramp, params.snug_n * ramp)
        } else {
            (0.0, params.loop_n)
        };
        for (h, force_n) in [(free, -free_n), (loaded, loaded_n)] {
            let body = &mut physics.bodies[h];
            body.reset_forces(true);
            body.add_force(Vector::new(0.0, 0.0, force_n), true);
        }
        step_strands(&mut physics, thread)?;
    }
    let at_end = along(&physics);
    Ok(HoldingOutcome {
        slip_m: at_end - at_start,
        late_slip_m: at_end - at_half,
        turns_snug,
        turns_end: winding_turns(&a.centreline(&physics), &b.centreline(&physics)),
        steps: phases.steps(),
    })
}

/// The strand over a ball: the capstan trial against a rigid body instead of another strand. The
/// strand is laid over the top of a fixed ball (half a turn), snugged with both ends pulled down
/// alike, then its first end pulled with `high_n` and its last with `high_n / ratio` for `hold_s`.
/// Friction holds while `ratio` stays below `exp(friction * pi)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallCapstanParams {
    /// The ball's radius, m.
    pub ball_radius_m: f64,
    /// The harder pull, N (both ends pulled with it during the snug).
    pub high_n: f64,
    /// The snug's length, s.
    pub snug_s: f64,
    /// The ratio of the two pulls after the snug.
    pub ratio: f64,
    /// How long the two pulls differ, s.
    pub hold_s: f64,
}

/// Straight strand hanging down either side of the ball, m.
const BALL_TAIL_M: f64 = 0.05;

/// The strand over a ball: how far the strand slid towards its harder-pulled end after the snug, and
/// in the last half of that time, m, and whether its other end was drawn up to the ball (the slide
/// then stops there, not by friction); a strand that slid off and flew trips the speed check.
pub fn run_capstan_over_ball(
    solver: &SolverParams,
    thread: &ThreadParams,
    params: &BallCapstanParams,
) -> Result<(f64, f64, bool), HealthError> {
    let mut physics = Physics::new(solver);
    physics.gravity = Vector::ZERO;
    let ball = physics.bodies.insert(RigidBodyBuilder::fixed());
    let collider = ColliderBuilder::ball(params.ball_radius_m).friction(thread.friction).build();
    physics.colliders.insert_with_parent(collider, ball, &mut physics.bodies);
    // Down the -x side, over the top, down the +x side, just clear of the ball.
    let r = params.ball_radius_m + 1.05 * thread.radius_m;
    let mut path = vec![Vector3::new(-r, 0.0, -BALL_TAIL_M)];
    path.extend((0..=60).map(|k| {
        let a = std::f64::consts::PI * (1.0 - k as f64 / 60.0);
        Vector3::new(r * a.cos(), 0.0, r * a.sin())
    }));
    path.push(Vector3::new(r, 0.0, -BALL_TAIL_M));
    let strand = strand_along(&mut physics, thread, &path);
    let (first, last) = (strand.segments[0], strand.segments[strand.segments.len() - 1]);
    for h in [first, last] {
        physics.bodies[h].lock_rotations(true, true);
    }
    let phases = Phases::new(physics.dt_s(), params.snug_s, params.hold_s);
    // Both ends hang down and are pulled down.
    let (z_start, z_half, z_end) = pull_ends(&mut physics, thread, &phases, (first, last), |step| {
        let high_n = params.high_n * phases.ramp(step);
        let low_n = if step < phases.hold_start() { high_n } else { params.high_n / params.ratio };
        (-high_n, -low_n)
    })?;
    let to_end = physics.bodies[last].translation().z > -(params.ball_radius_m + END_NEAR_M);
    Ok((z_start - z_end, z_half - z_end, to_end))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A tight helix measures at its own radius with its whole length in the wrap zone, and a strand far from
    /// the axis measures nothing.
    #[test]
    fn a_tight_helix_lies_at_its_radius_with_its_length_in_the_zone() {
        let axis = [Vector3::new(-0.1, 0.0, 0.0), Vector3::new(0.1, 0.0, 0.0)];
        let r = 0.001;
        let helix: Vec<_> = (0..=400)
            .map(|k| {
                let t = TAU * 2.0 * k as f64 / 400.0;
                Vector3::new(0.001 * t, r * t.cos(), r * t.sin())
            })
            .collect();
        let (radius, length) = wrap_tightness(&axis, &helix, WRAP_ZONE_M);
        assert!((radius.unwrap() - r).abs() < 1e-9);
        let expected: f64 = helix.windows(2).map(|w| (w[1] - w[0]).norm()).sum();
        assert!((length - expected).abs() < 1e-9, "{length} {expected}");
        // Far away: nothing in the zone.
        let far: Vec<_> = helix.iter().map(|p| p + Vector3::new(0.0, 0.01, 0.0)).collect();
        assert_eq!(wrap_tightness(&axis, &far, WRAP_ZONE_M), (None, 0.0));
    }

    /// The winding count gives a helix's turns round its axis (negative when wound the other way), and a
    /// strand that passes by and comes back on the same side winds none.
    #[test]
    fn a_helix_winds_its_turns_round_its_axis() {
        let axis = [Vector3::new(-0.1, 0.0, 0.0), Vector3::new(0.1, 0.0, 0.0)];
        let path = wound_path();
        // Two turns, and for each tail (from -z into the helix, out of it to +z) the angle its far
        // end makes with the helix's start: nearly a quarter turn.
        let expected = TURNS + 2.0 * TAIL_M.atan2(HELIX_RADIUS_M) / TAU;
        assert!((winding_turns(&axis, &path) - expected).abs() < 0.005, "{}", winding_turns(&axis, &path));
        // Wound the other way, the turns count negative.
        let reversed: Vec<_> = path.iter().rev().copied().collect();
        assert!((winding_turns(&axis, &reversed) + expected).abs() < 0.005);
        // A strand that goes past and comes back the same side winds none.
        let past = [
            Vector3::new(0.0, 0.005, -0.02),
            Vector3::new(0.0, 0.005, 0.02),
            Vector3::new(0.0, 0.006, -0.02),
        ];
        assert!(winding_turns(&axis, &past).abs() < 0.05, "{}", winding_turns(&axis, &past));
    }
}
