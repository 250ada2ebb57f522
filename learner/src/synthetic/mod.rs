//! Synthetic demonstrations of the canonical knot-tying task with known primitive boundaries, for
//! testing and benchmarking the decomposition. Human-like: minimum-jerk moves, speed varying from run
//! to run, pauses of varying length between primitives, tremor (0.1-0.2 mm at 8-12 Hz), force and jaw
//! sensor noise; every draw from the seed. Variants make demonstrations that are not the task: a single
//! wrap, the tail never grasped, a recording cut short.
//!
//! The script follows `scenarios/patterns/knot_tying.toml` (the stitch frame: x along the wound, y
//! towards the tail's flap, z up):
//! - left: `L1` linear from its parked pose to the winding point; `L2` synchronized, a small motion
//!   following the right's winding; the jaws open during the following pause; `L3` linear over the
//!   tail, `L4` down onto it; the jaws close on it; `L5` linear up (drawing the tail through the loops,
//!   a small drag), `L6` linear back over the tail's flap; the jaws open once the right has let go.
//! - right (holds the needle): waits during `L1`; `R2` 2D: two loops around the left jaws; `R3` and
//!   `R4` linear, up and back with the left; `R5` force-controlled pull the other way until about
//!   1 N, when the jaws open (the end of `R5`), the move running on to its end.
//! - assist (holds the tail): its jaws open after the left's close; `A1` linear retreat.

pub mod motion;
pub mod track;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use knotlab_hw::rig::ArmName;

use self::motion::{Polyline, Tremor, ramped};
use self::track::{Drag, ForcePulse, JawMove, Move, Offset, Track};
use crate::demonstration::{Demonstration, FORMAT_VERSION, InstrumentRecord, Metadata, StitchPose};
use crate::pattern::PrimitiveType;
use crate::segment::metrics::LabelledSpan;

/// How to generate a synthetic demonstration.
#[derive(Clone, Debug, PartialEq)]
pub struct SyntheticSettings {
    /// Seed of every random draw.
    pub seed: u64,
    /// Sample rate, Hz.
    pub sample_rate_hz: f64,
    /// How many loops the right winds (the task: 2).
    pub wraps: u32,
    /// Whether the left's jaws close on the tail (the task: yes).
    pub grasp_tail: bool,
    /// The recording stops at this time, s (`None`: it runs to the end).
    pub cut_at_s: Option<f64>,
    /// Tremor amplitude range per axis, m: one value drawn per instrument.
    pub tremor_m: (f64, f64),
    /// White position noise, m.
    pub position_noise_m: f64,
    /// Force noise per axis, N: one value drawn per run.
    pub force_noise_n: (f64, f64),
    /// The nominal speed as a multiple of the script's (1: the winding's two loops in about 2 s, the
    /// reaches at 5-10 cm/s at their peak; 0.3 is closer to the simulator's comfortable 1-3 cm/s).
    pub speed_scale: f64,
    /// Relative speed variation from run to run (0.2: speeds between 0.8 and 1.2 times nominal).
    pub speed_variation: f64,
    /// Pause range between primitives, s.
    pub pause_s: (f64, f64),
    /// The stitch frame in the world.
    pub world_from_stitch: Isometry3<f64>,
}

impl SyntheticSettings {
    /// The canonical task at realistic noise levels, sampled at `sample_rate_hz`, seeded.
    pub fn canonical(seed: u64, sample_rate_hz: f64) -> Self {
        Self {
            seed,
            sample_rate_hz,
            wraps: 2,
            grasp_tail: true,
            cut_at_s: None,
            tremor_m: (1e-4, 2e-4),
            position_noise_m: 2e-5,
            force_noise_n: (0.01, 0.02),
            speed_scale: 1.0,
            speed_variation: 0.2,
            pause_s: (0.1, 0.4),
            world_from_stitch: Isometry3::from_parts(
                Translation3::new(0.0, 0.0, 0.958),
                UnitQuaternion::from_euler_angles(0.0, 0.0, 0.3),
            ),
        }
    }
}

/// A primitive of the script with its true span.
#[derive(Clone, Debug, PartialEq)]
pub struct TruePrimitive {
    /// The instrument.
    pub instrument: ArmName,
    /// Its name in the task pattern.
    pub name: String,
    /// Its type.
    pub kind: PrimitiveType,
    /// Start, s.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
}

/// What the script did: the true primitives, per instrument in time order.
#[derive(Clone, Debug, PartialEq)]
pub struct GroundTruth {
    /// The primitives.
    pub primitives: Vec<TruePrimitive>,
    /// The speed factor of the run, `speed_scale` times the variation drawn (durations are divided by it).
    pub speed_factor: f64,
}

impl GroundTruth {
    /// The primitives as labelled spans for [`crate::segment::metrics`].
    pub fn spans(&self) -> Vec<LabelledSpan> {
        self.primitives
            .iter()
            .map(|p| LabelledSpan {
                instrument: p.instrument,
                label: p.name.clone(),
                start_s: p.start_s,
                end_s: p.end_s,
            })
            .collect()
    }
}

/// Generates a demonstration of the canonical task (or one of its variants) and its ground truth.
pub fn canonical_demonstration(settings: &SyntheticSettings) -> (Demonstration, GroundTruth) {
    let mut rng = ChaCha8Rng::seed_from_u64(settings.seed);
    let rng = &mut rng;
    let v = settings.speed_variation;
    let speed = settings.speed_scale * rng.random_range(1.0 - v..=1.0 + v);
    let duration = |rng: &mut ChaCha8Rng, nominal: f64| nominal / speed * rng.random_range(0.93..1.07);
    let (p0, p1) = settings.pause_s;
    let pause = |rng: &mut ChaCha8Rng| rng.random_range(p0..=p1);
    let jitter = |rng: &mut ChaCha8Rng, r: f64| Vector3::from_fn(|_, _| rng.random_range(-r..=r));

    // Where things are (stitch frame).
    let left_trocar = Vector3::new(-0.08, 0.12, 0.07);
    let right_trocar = Vector3::new(-0.08, -0.12, 0.07);
    let assist_trocar = Vector3::new(0.12, 0.10, 0.07);
    let left_park = Vector3::new(-0.035, 0.035, 0.045) + jitter(rng, 0.002);
    let winding_point = Vector3::new(-0.004, -0.002, 0.006) + jitter(rng, 0.001);
    let right_start = Vector3::new(-0.01, -0.045, 0.03) + jitter(rng, 0.002);
    let tail = Vector3::new(0.0, 0.03, 0.015) + jitter(rng, 0.001);
    let grasp_point = tail + Vector3::new(-0.004, -0.003, 0.0);
    let looking = |trocar: Vector3<f64>, tip: Vector3<f64>| {
        UnitQuaternion::rotation_between(&Vector3::z(), &(tip - trocar))
            .unwrap_or_else(UnitQuaternion::identity)
    };
    let mut left = Track::new(left_park, looking(left_trocar, winding_point), 0.02, false);
    let mut right = Track::new(right_start, looking(right_trocar, right_start), 0.08, true);
    let mut assist = Track::new(tail, looking(assist_trocar, tail), 0.03, true);
    for track in [&mut left, &mut right, &mut assist] {
        track.wobble_axis = jitter(rng, 1.0).try_normalize(1e-9).unwrap_or_else(Vector3::x);
    }
    let open_rad = |rng: &mut ChaCha8Rng| rng.random_range(0.6..0.9);
    let mut truth = Vec::new();
    let mut record = |instrument: ArmName, name: &str, kind: PrimitiveType, start_s: f64, end_s: f64| {
        truth.push(TruePrimitive { instrument, name: name.to_owned(), kind, start_s, end_s });
    };

    // L1: the left from its parked pose to the winding point.
    let mut t = rng.random_range(0.3..0.6);
    let l1 = (t, t + duration(rng, 1.2));
    left.moves.push(Move { t0: l1.0, t1: l1.1, path: Polyline::line(left_park, winding_point), ramp: 0.5 });
    record(ArmName::Left, "L1", PrimitiveType::Linear, l1.0, l1.1);
    t = l1.1 + pause(rng);

    // R2: the right winds `wraps` loops around the left jaws, in the plane through the jaws' axis
    // (tilted to hold the right's start), cruising between a minimum-jerk start and stop; L2 follows.
    let jaw_axis = (winding_point - left_trocar).normalize();
    let centre = winding_point - 0.004 * jaw_axis;
    let rel = right_start - centre;
    let normal = (jaw_axis - jaw_axis.dot(&rel.normalize()) * rel.normalize()).normalize();
    let e1 = rel.normalize();
    let e2 = normal.cross(&e1);
    let radius = rng.random_range(0.005..0.008);
    let wraps = f64::from(settings.wraps.max(1));
    let turn = std::f64::consts::TAU * wraps;
    // The loop starts where the line from the right's start touches the circle, going round `e1 -> e2`.
    let phi0 = (radius / rel.norm()).acos();
    let ring = |phi: f64| {
        let r = radius * (1.0 - 0.15 * (phi - phi0) / turn);
        centre + r * (phi.cos() * e1 + phi.sin() * e2)
    };
    let tangent = |phi: f64| -phi.sin() * e1 + phi.cos() * e2;
    let mut points = vec![right_start];
    points.extend((0..=(200.0 * wraps) as usize).map(|k| ring(phi0 + turn * k as f64 / (200.0 * wraps))));
    let last = points[points.len() - 1];
    points.push(last + rng.random_range(0.015..0.025) * tangent(phi0 + turn));
    let r2 = (t, t + duration(rng, 0.5 + 0.8 * wraps));
    let winding = Polyline::new(points);
    right.moves.push(Move { t0: r2.0, t1: r2.1, path: winding.clone(), ramp: 0.2 });
    right.drags.push(Drag {
        t0: r2.0,
        t1: r2.1,
        peak_n: rng.random_range(0.03..0.06),
        direction: -(right_start - centre).normalize(),
    });
    assist.drags.push(Drag {
        t0: r2.0,
        t1: r2.1,
        peak_n: rng.random_range(0.03..0.08),
        direction: Vector3::y(),
    });
    record(ArmName::Right, "R2", PrimitiveType::TwoD, r2.0, r2.1);
    record(ArmName::Left, "L2", PrimitiveType::Synchronized, r2.0, r2.1);
    let follow = rng.random_range(0.0008..0.0015);
    left.offset = Some(Offset(std::sync::Arc::new(move |t_s: f64| {
        if t_s <= r2.0 || t_s >= r2.1 {
            return Vector3::zeros();
        }
        let tau = (t_s - r2.0) / (r2.1 - r2.0);
        let p = winding.at(ramped(tau, 0.2) * winding.length_m()) - centre;
        let angle = p.dot(&e2).atan2(p.dot(&e1));
        let window = (std::f64::consts::PI * tau).sin().powi(2);
        follow * window * (angle.cos() * e1 + angle.sin() * e2)
    })));
    t = r2.1 + pause(rng);

    // L3: the left opens its jaws, then moves over the tail; L4: down onto it.
    let open_end = t + 0.15;
    left.jaw_moves.push(JawMove { t0: t, t1: open_end, to_rad: open_rad(rng) });
    let l3_start = open_end + rng.random_range(0.1..0.2);
    let l3 = (l3_start, l3_start + duration(rng, 0.9));
    let over_tail = grasp_point + Vector3::new(0.0, 0.0, rng.random_range(0.01..0.015));
    left.moves.push(Move { t0: l3.0, t1: l3.1, path: Polyline::line(winding_point, over_tail), ramp: 0.5 });
    record(ArmName::Left, "L3", PrimitiveType::Linear, l3.0, l3.1);
    t = l3.1 + pause(rng);
    let l4 = (t, t + duration(rng, 0.5));
    left.moves.push(Move { t0: l4.0, t1: l4.1, path: Polyline::line(over_tail, grasp_point), ramp: 0.5 });
    record(ArmName::Left, "L4", PrimitiveType::Linear, l4.0, l4.1);
    t = l4.1 + pause(rng);

    // The left grasps the tail (or does not); the assist lets go and retreats (A1).
    let close_end = t + 0.15;
    if settings.grasp_tail {
        left.jaw_moves.push(JawMove { t0: t, t1: close_end, to_rad: 0.03 });
        left.holding.push((close_end, true));
    }
    let assist_open = close_end + rng.random_range(0.1..0.3);
    let assist_open_end = assist_open + 0.15;
    assist.jaw_moves.push(JawMove { t0: assist_open, t1: assist_open_end, to_rad: open_rad(rng) });
    assist.holding.push((assist_open + 0.05, false));
    let a1_start = assist_open_end + rng.random_range(0.1..0.2);
    let a1 = (a1_start, a1_start + duration(rng, 0.8));
    assist.moves.push(Move {
        t0: a1.0,
        t1: a1.1,
        path: Polyline::line(tail, tail + Vector3::new(0.01, 0.02, 0.025)),
        ramp: 0.5,
    });
    record(ArmName::Assist, "A1", PrimitiveType::Linear, a1.0, a1.1);

    // L5 and R3: up together, the left drawing the tail through the loops; L6 and R4: back together,
    // over the tail's flap.
    let l5_start = assist_open_end + rng.random_range(0.15..0.35);
    let together =
        |rng: &mut ChaCha8Rng, left: &mut Track, right: &mut Track, start: f64, way: Vector3<f64>| {
            let l = (start, start + duration(rng, 0.8));
            let r_start = start + rng.random_range(-0.05..0.05);
            let r = (r_start, r_start + (l.1 - l.0) * rng.random_range(0.95..1.05));
            let from = left.end_position();
            left.moves.push(Move { t0: l.0, t1: l.1, path: Polyline::line(from, from + way), ramp: 0.5 });
            left.drags.push(Drag {
                t0: l.0,
                t1: l.1,
                peak_n: rng.random_range(0.2..0.5),
                direction: -way.normalize(),
            });
            let from = right.end_position();
            right.moves.push(Move { t0: r.0, t1: r.1, path: Polyline::line(from, from + way), ramp: 0.5 });
            (l, r)
        };
    let (l5, r3) = together(rng, &mut left, &mut right, l5_start, Vector3::new(0.0, 0.0, 0.025));
    record(ArmName::Left, "L5", PrimitiveType::Linear, l5.0, l5.1);
    record(ArmName::Right, "R3", PrimitiveType::Linear, r3.0, r3.1);
    let l6_start = l5.1.max(r3.1) + pause(rng);
    let (l6, r4) = together(rng, &mut left, &mut right, l6_start, Vector3::new(0.0, 0.018, 0.005));
    record(ArmName::Left, "L6", PrimitiveType::Linear, l6.0, l6.1);
    record(ArmName::Right, "R4", PrimitiveType::Linear, r4.0, r4.1);

    // R5: the right pulls the long end until about 1 N, then opens its jaws; the left lets go after.
    let r5_start = l6.1.max(r4.1) + pause(rng);
    let pull = |rng: &mut ChaCha8Rng, track: &mut Track, start: f64, direction: Vector3<f64>| {
        let d = direction.normalize();
        let from = track.end_position();
        let end = start + duration(rng, 1.2);
        track.moves.push(Move { t0: start, t1: end, path: Polyline::line(from, from + 0.03 * d), ramp: 0.5 });
        let span = end - start;
        let release = start + rng.random_range(0.65..0.85) * span;
        track.pulses.push(ForcePulse {
            t_tight_s: start + rng.random_range(0.3..0.45) * span,
            t_release_s: release,
            peak_n: rng.random_range(0.95..1.1),
            direction: -d,
        });
        track.jaw_moves.push(JawMove { t0: release, t1: release + 0.12, to_rad: open_rad(rng) });
        track.holding.push((release + 0.03, false));
        (start, release, end)
    };
    let r5 = pull(rng, &mut right, r5_start, Vector3::new(-0.2, -1.0, 0.3));
    record(ArmName::Right, "R5", PrimitiveType::Force, r5.0, r5.1);
    let l_release = r5.1 + rng.random_range(0.3..0.8);
    if settings.grasp_tail {
        left.jaw_moves.push(JawMove { t0: l_release, t1: l_release + 0.12, to_rad: open_rad(rng) });
        left.holding.push((l_release + 0.03, false));
    }
    let end = r5.2.max(l_release + 0.12).max(a1.1) + rng.random_range(0.4..0.8);

    // Sampling.
    let end = settings.cut_at_s.map_or(end, |c| c.min(end));
    let count = (end * settings.sample_rate_hz).floor() as usize;
    let times: Vec<f64> = (0..=count).map(|k| k as f64 / settings.sample_rate_hz).collect();
    let force_noise = rng.random_range(settings.force_noise_n.0..=settings.force_noise_n.1);
    let mut instruments = Vec::new();
    for (name, track) in [(ArmName::Left, &left), (ArmName::Right, &right), (ArmName::Assist, &assist)] {
        let amplitude = rng.random_range(settings.tremor_m.0..=settings.tremor_m.1);
        let tremor = Tremor::draw(rng, amplitude, settings.position_noise_m);
        let samples = track.sample(&times, &settings.world_from_stitch, &tremor, force_noise, rng);
        instruments.push(InstrumentRecord { instrument: name, samples });
    }
    truth.sort_by(|a, b| a.instrument.cmp(&b.instrument).then(a.start_s.total_cmp(&b.start_s)));
    let metadata = Metadata {
        format_version: FORMAT_VERSION,
        source: "synthetic".to_owned(),
        scene: String::new(),
        seed: Some(settings.seed),
        sample_rate_hz: settings.sample_rate_hz,
        stitch: StitchPose::from_isometry(&settings.world_from_stitch),
        description: format!(
            "synthetic canonical knot-tying demonstration: {} wrap(s), tail {}grasped{}",
            settings.wraps,
            if settings.grasp_tail { "" } else { "not " },
            settings.cut_at_s.map_or(String::new(), |c| format!(", cut at {c} s")),
        ),
    };
    (Demonstration { metadata, instruments }, GroundTruth { primitives: truth, speed_factor: speed })
}
