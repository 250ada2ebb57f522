//! `knotlab session` end to end: with the shipped sim rig (dummy masters that stay still) a short
//! unpaced session runs and its recording is a demonstration that loads; the gamepad rig without the
//! `gamepad` feature says what to build.

use super::common;

use common::{json, knotlab};
use knotlab_learner::demonstration::load_demonstration;

/// A one-second unpaced session on the sim rig is recorded as a demonstration that loads, with three
/// instruments' samples and its source and scene named.
#[test]
fn a_short_session_is_recorded_as_a_demonstration() {
    let dir = std::env::temp_dir().join(format!("knotlab-cli-session-{}", std::process::id()));
    let (code, r) = json(&[
        "session",
        "--rig",
        "scenarios/rigs/sim.toml",
        "--seconds",
        "1",
        "--unpaced",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(code, 0, "{r}");
    assert_eq!(r["samples"], 3 * 101, "{r}");
    assert!(r["skill_started_s"].is_null(), "no pedal pressed: {r}");
    let demo = load_demonstration(&dir).expect("the recording loads");
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(demo.metadata.source, "teleoperation (scenarios/rigs/sim.toml)");
    assert_eq!(demo.metadata.scene, "scenarios/default.toml");
}

/// Without the `gamepad` feature the default gamepad rig is refused, saying to build with it and naming
/// `pedals.backend` once.
#[cfg(not(feature = "gamepad"))]
#[test]
fn the_gamepad_rig_needs_the_gamepad_feature() {
    let (code, _, stderr) = knotlab(&["session", "--seconds", "1", "--out", "/tmp/knotlab-never"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("needs knotlab built with the `gamepad` feature"), "{stderr}");
    assert_eq!(stderr.matches("pedals.backend").count(), 1, "said once: {stderr}");
}
