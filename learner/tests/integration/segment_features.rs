//! The feature detectors on signals whose features are known: a minimum-jerk move (start and stop,
//! with and without tremor), circles (loops), an S-curve (one inflection), a force pulse (onset, peak,
//! release) and jaw movements (open, close); the thresholds refuse nonsense.

use nalgebra::Vector3;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use knotlab_hw::rig::ArmName;
use knotlab_learner::demonstration::{GraspState, InstrumentRecord, Sample};
use knotlab_learner::features::{DetectorParams, Feature, FeatureKind, analyse};
use knotlab_learner::synthetic::motion::{Tremor, minimum_jerk};

const RATE_HZ: f64 = 100.0;

/// An instrument record sampled at 100 Hz for `duration_s` from signal functions.
fn record(
    duration_s: f64,
    position: impl Fn(f64) -> Vector3<f64>,
    force: impl Fn(f64) -> Vector3<f64>,
    jaw: impl Fn(f64) -> f64,
) -> InstrumentRecord {
    let n = (duration_s * RATE_HZ) as usize;
    let samples = (0..=n)
        .map(|k| {
            let t = k as f64 / RATE_HZ;
            Sample {
                time_s: t,
                position_m: position(t),
                quaternion_xyzw: [0.0, 0.0, 0.0, 1.0],
                jaw_rad: jaw(t),
                grasp: if jaw(t) > 0.2 { GraspState::Open } else { GraspState::ClosedEmpty },
                force_n: force(t),
            }
        })
        .collect();
    InstrumentRecord { instrument: ArmName::Right, samples }
}

fn features(r: &InstrumentRecord) -> Vec<Feature> {
    analyse(r, &DetectorParams::default()).expect("analysis").features
}

fn of(fs: &[Feature], kind: FeatureKind) -> Vec<Feature> {
    fs.iter().filter(|f| f.kind == kind).copied().collect()
}

/// A 5 cm minimum-jerk move from 1.0 s to 2.2 s.
fn reach(t: f64) -> Vector3<f64> {
    Vector3::new(0.05 * minimum_jerk((t - 1.0) / 1.2), 0.0, 0.0)
}

/// A 5 cm minimum-jerk move gives one start and one stop within 5 ms of its own, its path length, and no
/// loop or inflection.
#[test]
fn a_minimum_jerk_move_starts_and_stops_where_it_does() {
    let fs = features(&record(3.5, reach, |_| Vector3::zeros(), |_| 0.0));
    let (starts, stops) = (of(&fs, FeatureKind::MotionStart), of(&fs, FeatureKind::MotionStop));
    assert_eq!((starts.len(), stops.len()), (1, 1), "{fs:?}");
    assert!((starts[0].time_s - 1.0).abs() < 0.005, "start at {}", starts[0].time_s);
    assert!((stops[0].time_s - 2.2).abs() < 0.005, "stop at {}", stops[0].time_s);
    assert!((starts[0].magnitude - 0.05).abs() < 0.001, "path length {}", starts[0].magnitude);
    assert!(of(&fs, FeatureKind::Loop).is_empty() && of(&fs, FeatureKind::Inflection).is_empty(), "{fs:?}");
}

/// Tremor on a minimum-jerk move adds no motion start or stop and moves its boundaries by under 20 ms.
#[test]
fn tremor_adds_no_motion_and_barely_moves_the_boundaries() {
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let tremor = Tremor::draw(&mut rng, 2e-4, 2e-5);
    let fs = features(&record(3.5, |t| reach(t) + tremor.at(t), |_| Vector3::zeros(), |_| 0.0));
    let (starts, stops) = (of(&fs, FeatureKind::MotionStart), of(&fs, FeatureKind::MotionStop));
    assert_eq!((starts.len(), stops.len()), (1, 1), "tremor alone is no motion: {fs:?}");
    assert!((starts[0].time_s - 1.0).abs() < 0.02, "start at {}", starts[0].time_s);
    assert!((stops[0].time_s - 2.2).abs() < 0.02, "stop at {}", stops[0].time_s);
}

/// Three circles of 8 mm radius are found as three loops of 16 mm diameter, with no inflection.
#[test]
fn three_circles_are_three_loops_of_their_diameter() {
    // Three turns of radius 8 mm at 1 turn per second in a tilted plane, with a gentle start and stop.
    let (e1, e2) = (Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 0.8, 0.6));
    let circles = |t: f64| {
        let phase = std::f64::consts::TAU * 3.0 * minimum_jerk((t - 0.5) / 4.0);
        0.008 * (e1 * phase.cos() + e2 * phase.sin())
    };
    let fs = features(&record(5.0, circles, |_| Vector3::zeros(), |_| 0.0));
    let loops = of(&fs, FeatureKind::Loop);
    assert_eq!(loops.len(), 3, "{fs:?}");
    for l in &loops {
        assert!((l.magnitude - 0.016).abs() < 0.0025, "diameter {}", l.magnitude);
    }
    assert!(of(&fs, FeatureKind::Inflection).is_empty(), "a circle has no inflection: {fs:?}");
}

/// An S-curve gives exactly one inflection, where and when its curvature changes sign.
#[test]
fn an_s_curve_has_one_inflection_where_it_turns_the_other_way() {
    // Two half circles of radius 1 cm, the second curving the other way, at constant speed between a
    // minimum-jerk start and stop; the curvature changes sign at 2.0 s.
    let r = 0.01;
    let half = std::f64::consts::PI * r;
    let s_curve = |t: f64| {
        let s = 2.0 * half * minimum_jerk((t - 0.5) / 3.0);
        if s <= half {
            let a = s / r;
            Vector3::new(r - r * a.cos(), r * a.sin(), 0.0)
        } else {
            let a = (s - half) / r;
            Vector3::new(3.0 * r - r * a.cos(), -r * a.sin(), 0.0)
        }
    };
    let fs = features(&record(4.0, s_curve, |_| Vector3::zeros(), |_| 0.0));
    let inflections = of(&fs, FeatureKind::Inflection);
    assert_eq!(inflections.len(), 1, "{fs:?}");
    assert!((inflections[0].time_s - 2.0).abs() < 0.05, "inflection at {}", inflections[0].time_s);
    assert!((inflections[0].position_m - Vector3::new(0.02, 0.0, 0.0)).norm() < 0.002);
}

/// A noisy force pulse gives one onset where it passes the threshold, one peak at its 1.2 N top, and one
/// release as it falls.
#[test]
fn a_force_pulse_has_an_onset_a_peak_and_a_release() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    use rand_distr::{Distribution, Normal};
    let noise: Vec<Vector3<f64>> = (0..=400)
        .map(|_| Vector3::from_fn(|_, _| Normal::new(0.0, 0.02).unwrap().sample(&mut rng)))
        .collect();
    let pulse = |t: f64| {
        let f = if (1.0..=2.0).contains(&t) {
            1.2 * (t - 1.0)
        } else if t > 2.0 {
            1.2 * (-(t - 2.0) / 0.02).exp()
        } else {
            0.0
        };
        Vector3::new(0.0, -f, 0.0) + noise[(t * RATE_HZ).round() as usize]
    };
    let fs = features(&record(4.0, |_| Vector3::zeros(), pulse, |_| 0.0));
    let (onsets, peaks, releases) = (
        of(&fs, FeatureKind::ForceOnset),
        of(&fs, FeatureKind::ForcePeak),
        of(&fs, FeatureKind::ForceRelease),
    );
    assert_eq!((onsets.len(), peaks.len(), releases.len()), (1, 1, 1), "{fs:?}");
    // 0.2 N is reached at 1.17 s.
    assert!((onsets[0].time_s - 1.167).abs() < 0.03, "onset at {}", onsets[0].time_s);
    assert!((peaks[0].magnitude - 1.2).abs() < 0.1, "peak {}", peaks[0].magnitude);
    assert!((peaks[0].time_s - 2.0).abs() < 0.03, "peak at {}", peaks[0].time_s);
    assert!(releases[0].time_s > 2.0 && releases[0].time_s < 2.1, "release at {}", releases[0].time_s);
}

/// Jaws opening and closing are timed where they start to move, with the opening's size and the grasp
/// state after each.
#[test]
fn jaws_opening_and_closing_are_timed_where_they_start_to_move() {
    let jaw = |t: f64| {
        if t < 1.0 {
            0.03
        } else if t < 1.2 {
            0.03 + 0.67 * minimum_jerk((t - 1.0) / 0.2)
        } else if t < 2.0 {
            0.7
        } else {
            0.7 - 0.67 * minimum_jerk((t - 2.0) / 0.2)
        }
    };
    let fs = features(&record(3.0, |_| Vector3::zeros(), |_| Vector3::zeros(), jaw));
    let (opens, closes) = (of(&fs, FeatureKind::JawOpen), of(&fs, FeatureKind::JawClose));
    assert_eq!((opens.len(), closes.len()), (1, 1), "{fs:?}");
    assert!((opens[0].time_s - 1.0).abs() < 0.04, "open at {}", opens[0].time_s);
    assert!((closes[0].time_s - 2.0).abs() < 0.04, "close at {}", closes[0].time_s);
    assert!((opens[0].magnitude - 0.7).abs() < 1e-9);
    assert_eq!(opens[0].grasp_after, GraspState::Open);
    assert_eq!(closes[0].grasp_after, GraspState::ClosedEmpty);
}

/// A motion-off threshold above the motion-on one, a NaN smoothing time, or a shape step outside 0.1 mm
/// to 1 cm, is refused naming the parameter.
#[test]
fn nonsense_thresholds_are_refused_naming_the_parameter() {
    let r = record(1.0, |_| Vector3::zeros(), |_| Vector3::zeros(), |_| 0.0);
    let bad = DetectorParams { motion_off_mps: 0.01, ..DetectorParams::default() };
    let e = knotlab_learner::features::detect(
        &knotlab_learner::demonstration::Demonstration {
            metadata: knotlab_learner::synthetic::canonical_demonstration(
                &knotlab_learner::synthetic::SyntheticSettings::canonical(0, 100.0),
            )
            .0
            .metadata,
            instruments: vec![r],
        },
        &bad,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("detector.motion_off_mps"), "{e}");
    let e = DetectorParams { smoothing_s: f64::NAN, ..DetectorParams::default() }.check().unwrap_err();
    assert_eq!(e.0, "smoothing_s");
    // A shape step of 1e-12 m asked for 3 TB of resampled path; 0.1 mm to 1 cm is allowed.
    for step_m in [1e-12, 5e-5, 0.02] {
        let e = DetectorParams { shape_step_m: step_m, ..DetectorParams::default() }.check().unwrap_err();
        assert_eq!(e.0, "shape_step_m", "{step_m}: {e:?}");
        assert!(e.1.contains("0.0001-0.01 m"), "{e:?}");
    }
    for step_m in [1e-4, 0.01] {
        assert!(DetectorParams { shape_step_m: step_m, ..DetectorParams::default() }.check().is_ok());
    }
}

/// Jaws closing over 0.6 s onto the thread are read as holding, the grasp taken once they have closed,
/// not as they start.
#[test]
fn a_slow_grasp_is_read_once_the_jaws_have_closed() {
    // The jaws close over 0.6 s (from 1.0 s); they hold the thread from 1.6 s on.
    let jaw = |t: f64| if t < 1.0 { 0.7 } else { 0.7 - 0.67 * minimum_jerk((t - 1.0) / 0.6) };
    let mut r = record(3.0, |_| Vector3::zeros(), |_| Vector3::zeros(), jaw);
    for s in &mut r.samples {
        if s.time_s >= 1.6 {
            s.grasp = GraspState::Holding;
        }
    }
    let fs = features(&r);
    let closes = of(&fs, FeatureKind::JawClose);
    assert_eq!(closes.len(), 1, "{fs:?}");
    assert!((closes[0].time_s - 1.0).abs() < 0.1, "close at {}", closes[0].time_s);
    assert_eq!(
        closes[0].grasp_after,
        GraspState::Holding,
        "read after the jaws closed, not 0.15 s after they started"
    );
}
