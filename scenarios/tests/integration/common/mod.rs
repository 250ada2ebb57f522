//! What the tests share: the expert files, the two-throw scene and runs on it, reading grasp events,
//! and the skill learned from the shipped demonstration.
#![allow(dead_code)]

use knotlab_scenarios::expert::{DemoRun, RecordOptions, TieGeometry, demonstrate_with, load_tie_geometry};
use knotlab_sim::scene::{SceneConfig, parse_scene};

/// An expert file: the test fixtures of `scenarios/tests/experts/`, or the shipped ones of
/// `scenarios/experts/`.
pub fn expert(name: &str) -> TieGeometry {
    load_tie_geometry(&expert_path(name)).expect("the expert file")
}

/// Where the expert file `name` is (`scenarios/tests/experts/` first).
pub fn expert_path(name: &str) -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let fixture = root.join("tests/experts").join(name);
    if fixture.exists() { fixture } else { root.join("experts").join(name) }
}

/// The scene the second throw is worked out on (`scenarios/short-suture-friction-0.5.toml`).
pub fn two_throw_scene() -> SceneConfig {
    parse_scene(include_str!("../../../short-suture-friction-0.5.toml"), "short-suture-friction-0.5.toml")
        .expect("the two-throw scene")
}

/// The time of a grasp event as the run lists it (`... time_s: T }`).
pub fn event_time_s(event: &str) -> Option<f64> {
    event.split("time_s: ").nth(1)?.trim_end_matches(" }").parse().ok()
}

/// The segment of a grasp event as the run lists it (`... segment: N, ...`).
pub fn event_segment(event: &str) -> Option<usize> {
    event.split("segment: ").nth(1)?.split(',').next()?.parse().ok()
}

/// A recorded run of the expert file `name` ([`expert`]) on the two-throw scene, with the
/// human-like variation of `seed`: sampled every 10 cycles, snapshots at `snapshot_times_s`, stopped
/// at `stop_after_s`. It must run to there without a fault.
pub fn two_throw_run(name: &str, seed: u64, snapshot_times_s: Vec<f64>, stop_after_s: f64) -> DemoRun {
    let options = RecordOptions {
        cycles_per_sample: 10,
        snapshot_times_s,
        stop_after_s: Some(stop_after_s),
        knot_trace_every_s: Some(1.0),
        ..RecordOptions::default()
    };
    let run = demonstrate_with(
        two_throw_scene(),
        "scenarios/short-suture-friction-0.5.toml",
        seed,
        true,
        &expert(name),
        &options,
        None,
    )
    .expect("records");
    assert_eq!(run.fault, None, "{name}, seed {seed}");
    run
}

/// The shipped demonstration and what `knotlab learn` makes of it with the shipped pattern.
pub fn shipped_learned() -> knotlab_scenarios::trial::Learned {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let demonstration =
        knotlab_learner::demonstration::load_demonstration(&root.join("demos/instrument-tie"))
            .expect("the shipped demonstration");
    let pattern = knotlab_learner::pattern::load_pattern(&root.join("patterns/knot_tying.toml"))
        .expect("the shipped pattern");
    let knowledge = knotlab_learner::primitive::learn(&demonstration, &pattern).expect("learned");
    knotlab_scenarios::trial::Learned { knowledge, demonstration }
}
