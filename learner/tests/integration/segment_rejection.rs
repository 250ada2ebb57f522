//! Demonstrations that are not the task are rejected with a reason naming what is missing: a single
//! wrap where the pattern wants two, the tail never grasped, a recording cut short before the
//! force-controlled pulls.

use std::path::Path;

use knotlab_hw::rig::ArmName;
use knotlab_learner::features::{FeatureKind, detect};
use knotlab_learner::pattern::{TaskPattern, load_pattern};
use knotlab_learner::segment::{FailureReason, Rejection, decompose};
use knotlab_learner::synthetic::{SyntheticSettings, canonical_demonstration};

fn pattern() -> TaskPattern {
    load_pattern(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/patterns/knot_tying.toml"))
        .expect("the shipped pattern loads")
}

fn rejection(settings: &SyntheticSettings) -> Rejection {
    let p = pattern();
    let (demo, _) = canonical_demonstration(settings);
    let features = detect(&demo, &p.detector).expect("features");
    decompose(&p, &features).expect_err("not the task: must be rejected")
}

/// A demonstration with a single wrap is rejected for the right's missing second loop, the reason saying
/// so.
#[test]
fn a_single_wrap_is_rejected_for_the_missing_second_loop() {
    for seed in 0..6 {
        let r = rejection(&SyntheticSettings { wraps: 1, ..SyntheticSettings::canonical(seed, 100.0) });
        let primary = r.primary().unwrap();
        assert_eq!(primary.instrument, ArmName::Right, "{r}");
        assert_eq!(primary.element, "R2_loop2", "{r}");
        assert_eq!(primary.kind, FeatureKind::Loop);
        assert_eq!(primary.primitive.as_deref(), Some("R2"));
        assert!(matches!(primary.reason, FailureReason::NotFound { .. }));
        let text = r.to_string();
        assert!(text.contains("second wrap"), "the reason says what is missing: {text}");
        assert!(primary.stopped_at_s > 0.0 && primary.stopped_at_s < primary.recording_end_s, "{text}");
    }
}

/// A demonstration that never grasps the tail is rejected for the missing grasp, with what waits on it
/// named as consequences, not causes.
#[test]
fn a_tail_never_grasped_is_rejected_for_the_missing_grasp() {
    for seed in 0..6 {
        let r =
            rejection(&SyntheticSettings { grasp_tail: false, ..SyntheticSettings::canonical(seed, 100.0) });
        let primary = r.primary().unwrap();
        assert_eq!((primary.instrument, primary.element.as_str()), (ArmName::Left, "grasp_tail"), "{r}");
        assert_eq!(primary.kind, FeatureKind::JawClose);
        assert!(r.to_string().contains("grasps the tail"), "{r}");
        // The assist's release and the right's pull wait for that grasp: named as consequences.
        let consequences: Vec<&str> = r.failures.iter().skip(1).map(|f| f.element.as_str()).collect();
        assert!(consequences.contains(&"A_release"), "{r}");
        assert!(r.failures.iter().skip(1).all(|f| !f.is_root()), "{r}");
    }
}

/// Jaws closed on nothing (closed_empty, not holding) are not taken for the tail's grasp.
#[test]
fn closing_the_jaws_on_nothing_is_no_grasp_either() {
    let p = pattern();
    let (mut demo, _) = canonical_demonstration(&SyntheticSettings::canonical(3, 100.0));
    // The left closes its jaws but holds nothing: the grasp state says so.
    for s in &mut demo.instruments[0].samples {
        if s.grasp == knotlab_learner::demonstration::GraspState::Holding {
            s.grasp = knotlab_learner::demonstration::GraspState::ClosedEmpty;
        }
    }
    let features = detect(&demo, &p.detector).unwrap();
    let r = decompose(&p, &features).unwrap_err();
    let primary = r.primary().unwrap();
    assert_eq!(primary.element, "grasp_tail", "{r}");
    assert!(r.to_string().contains("closed_empty, not holding"), "{r}");
}

/// A recording cut just before the pull is rejected naming the right's missing pull and where the
/// recording ends.
#[test]
fn a_recording_cut_before_the_pulls_is_rejected_for_the_missing_pull() {
    for seed in 0..6 {
        let full = SyntheticSettings::canonical(seed, 100.0);
        let (_, truth) = canonical_demonstration(&full);
        let pull_start = truth.primitives.iter().find(|p| p.name == "R5").expect("the pull").start_s;
        let cut = pull_start - 0.05;
        let r = rejection(&SyntheticSettings { cut_at_s: Some(cut), ..full });
        // The right's pull is missing (and the left's release after it).
        let pull = r.failures.iter().find(|f| f.element == "R5_start").expect("the pull's start is named");
        assert_eq!(pull.primitive.as_deref(), Some("R5"), "{r}");
        assert!((pull.recording_end_s - cut).abs() < 0.011, "{r}");
        assert!(r.to_string().contains("pulling"), "the reason names the pull: {r}");
    }
}

/// A demonstration missing the assist instrument is rejected saying there is no record of it.
#[test]
fn a_demonstration_without_an_instrument_the_pattern_needs_says_so() {
    let p = pattern();
    let (mut demo, _) = canonical_demonstration(&SyntheticSettings::canonical(2, 100.0));
    demo.instruments.retain(|r| r.instrument != ArmName::Assist);
    let features = detect(&demo, &p.detector).unwrap();
    let r = decompose(&p, &features).unwrap_err();
    let f = r.failures.iter().find(|f| f.instrument == ArmName::Assist).unwrap();
    assert!(r.to_string().contains("no record of the assist instrument"), "{r}");
    assert_eq!(f.element, "A_release");
}
