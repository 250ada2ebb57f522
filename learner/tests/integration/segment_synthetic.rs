//! Synthetic demonstrations of the knot-tying task with known primitive boundaries (tremor 0.1-0.2 mm
//! at 8-12 Hz, force noise 0.01-0.02 N, speed +-20 %, pauses 0.1-0.4 s) decompose by the shipped
//! pattern into the task's primitives, with a median boundary error of at most 20 ms; also at twice
//! the noise, at 1 kHz, and deterministically.

use std::path::Path;

use knotlab_learner::features::detect;
use knotlab_learner::pattern::{TaskPattern, load_pattern};
use knotlab_learner::segment::metrics::{
    BoundaryCounts, boundary_counts, boundary_errors, median, segmental_edit_score,
};
use knotlab_learner::segment::{Decomposition, decompose};
use knotlab_learner::synthetic::{GroundTruth, SyntheticSettings, canonical_demonstration};

fn pattern() -> TaskPattern {
    load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
        .expect("the shipped pattern loads")
}

fn decompose_synthetic(pattern: &TaskPattern, settings: &SyntheticSettings) -> (Decomposition, GroundTruth) {
    let (demo, truth) = canonical_demonstration(settings);
    let features = detect(&demo, &pattern.detector).expect("features");
    let decomposition = decompose(pattern, &features)
        .unwrap_or_else(|r| panic!("seed {} at {} Hz rejected: {r}", settings.seed, settings.sample_rate_hz));
    (decomposition, truth)
}

struct Scores {
    errors_s: Vec<f64>,
    counts: BoundaryCounts,
    edit: Vec<f64>,
}

fn score(pattern: &TaskPattern, runs: impl Iterator<Item = SyntheticSettings>) -> Scores {
    let mut s = Scores { errors_s: Vec::new(), counts: BoundaryCounts::default(), edit: Vec::new() };
    for settings in runs {
        let (d, truth) = decompose_synthetic(pattern, &settings);
        // The decomposition has exactly the task's primitives, with the ground truth's names and types.
        let mut got: Vec<(String, String)> =
            d.segments.iter().map(|g| (g.name.clone(), g.kind.as_str().to_owned())).collect();
        let mut want: Vec<(String, String)> =
            truth.primitives.iter().map(|p| (p.name.clone(), p.kind.as_str().to_owned())).collect();
        got.sort();
        want.sort();
        assert_eq!(got, want, "seed {}", settings.seed);
        s.errors_s.extend(boundary_errors(&truth.spans(), &d.spans()));
        s.counts.add(boundary_counts(&truth.spans(), &d.spans(), 0.05));
        s.edit.push(segmental_edit_score(&truth.spans(), &d.spans(), 0.01));
    }
    s
}

/// Synthetic demonstrations at realistic noise decompose into the task's primitives with a median
/// boundary error of at most 20 ms, a boundary F1 of at least 0.95 and an edit score of at least 95.
#[test]
fn median_boundary_error_is_at_most_20_ms_at_realistic_noise() {
    let p = pattern();
    let s = score(&p, (0..16).map(|seed| SyntheticSettings::canonical(seed, 100.0)));
    let m = median(&s.errors_s);
    assert_eq!(s.errors_s.len(), 16 * 11 * 2, "every boundary of every primitive scored");
    assert!(m <= 0.020, "median boundary error {m:.4} s");
    assert!(s.counts.f1() >= 0.95, "boundary F1 at +-50 ms: {:.3} ({:?})", s.counts.f1(), s.counts);
    let edit = s.edit.iter().sum::<f64>() / s.edit.len() as f64;
    assert!(edit >= 95.0, "segmental edit score {edit:.1}");
}

/// Demonstrations recorded at 1 kHz decompose with a median boundary error of at most 20 ms and a
/// boundary F1 of at least 0.95.
#[test]
fn one_kilohertz_recordings_decompose_as_well() {
    let p = pattern();
    let s = score(&p, (100..104).map(|seed| SyntheticSettings::canonical(seed, 1000.0)));
    let m = median(&s.errors_s);
    assert!(m <= 0.020, "median boundary error at 1 kHz {m:.4} s");
    assert!(s.counts.f1() >= 0.95, "boundary F1 at 1 kHz: {:?}", s.counts);
}

/// Twice the tremor and force noise still decomposes with a median boundary error of at most 20 ms.
#[test]
fn twice_the_tremor_and_force_noise_still_decomposes() {
    let p = pattern();
    let s = score(
        &p,
        (200..210).map(|seed| SyntheticSettings {
            tremor_m: (2e-4, 3e-4),
            position_noise_m: 5e-5,
            force_noise_n: (0.03, 0.04),
            ..SyntheticSettings::canonical(seed, 100.0)
        }),
    );
    let m = median(&s.errors_s);
    assert!(m <= 0.020, "median boundary error with twice the noise {m:.4} s");
}

/// Demonstrations at a third of the script's speed decompose with a median boundary error of at most
/// 20 ms.
#[test]
fn slow_demonstrations_at_surgical_speeds_decompose_as_well() {
    // A third of the script's speed: reaches at 1-3 cm/s, the winding in about 7 s.
    let p = pattern();
    let s = score(
        &p,
        (300..306)
            .map(|seed| SyntheticSettings { speed_scale: 0.3, ..SyntheticSettings::canonical(seed, 100.0) }),
    );
    let m = median(&s.errors_s);
    assert!(m <= 0.020, "median boundary error at a third of the speed {m:.4} s");
    assert!(s.counts.f1() >= 0.9, "boundary F1 slow: {:?}", s.counts);
}

/// The same seed gives the same decomposition, and another seed a different one.
#[test]
fn the_same_seed_gives_the_same_decomposition() {
    let p = pattern();
    let settings = SyntheticSettings::canonical(42, 100.0);
    let (a, _) = decompose_synthetic(&p, &settings);
    let (b, _) = decompose_synthetic(&p, &settings);
    assert_eq!(a, b);
    let (c, _) = decompose_synthetic(&p, &SyntheticSettings::canonical(43, 100.0));
    assert_ne!(a.segments, c.segments, "another seed, another demonstration");
}

/// The synchronized L2 spans exactly its reference R2, and the pull R5 ends where the right's jaws open,
/// within 50 ms of the truth.
#[test]
fn synchronized_primitive_spans_its_reference_and_the_pull_ends_at_the_release() {
    let p = pattern();
    let (d, truth) = decompose_synthetic(&p, &SyntheticSettings::canonical(7, 100.0));
    let (l2, r2) = (d.segment("L2").unwrap(), d.segment("R2").unwrap());
    assert_eq!((l2.start_s, l2.end_s), (r2.start_s, r2.end_s));
    assert_eq!(l2.reference.as_deref(), Some("R2"));
    // The pull R5 ends where the right's jaws open.
    assert_eq!(d.segment("R5").unwrap().end_s, d.element_time_s("R5_release").unwrap());
    let true_r5 = truth.primitives.iter().find(|t| t.name == "R5").unwrap();
    assert!((d.segment("R5").unwrap().end_s - true_r5.end_s).abs() < 0.05);
}
