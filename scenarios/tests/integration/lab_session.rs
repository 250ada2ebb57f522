//! The lab's workflow in the simulator: the scripted surgeon nudges the left instrument
//! through its master (1:3), presses the skill pedal: the skill is instantiated at the stitch, previewed
//! and executed while the master is ignored; the emergency pedal then stops every arm.

use knotlab_hw::controller::{Status, TeleopSettings};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::parse_rig_config;
use knotlab_learner::demonstration::{load_demonstration, write_demonstration};
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::record::SIM_RIG_TOML;
use knotlab_scenarios::session::{Action, Script, run_session};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

use super::common;

fn tip(report: &knotlab_scenarios::session::SessionReport, arm: ArmName, time_s: f64) -> Vector3<f64> {
    report
        .tips
        .iter()
        .rev()
        .find(|(t, a, _)| *a == arm && *t <= time_s + 1e-9)
        .map(|(_, _, p)| *p)
        .expect("a tip sample")
}

/// The master moves the left at 1:3, the skill pedal starts the skill at once and the master is ignored
/// while it runs, the emergency stop halts every arm, and the teleoperated recording reads back whole.
#[test]
fn teleoperate_then_the_skill_pedal_then_the_emergency_stop() {
    let learned = common::shipped_learned();
    let scene = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    let rig = Rig::shipped().expect("the shipped rig");
    let config = parse_rig_config(SIM_RIG_TOML, "sim.toml").expect("the sim rig");
    let world = SimWorld::new(scene, rig.clone()).expect("the scene builds");

    let mut script: Script =
        vec![(0.0, Action::Handle { arm: ArmName::Left, position_m: [0.0; 3], gripper_rad: 0.6 })];
    // 1.5 cm of handle along the console's x over 0.8 s.
    for k in 1..=80 {
        let x = 0.015 * k as f64 / 80.0;
        script.push((
            0.1 + 0.01 * k as f64,
            Action::Handle { arm: ArmName::Left, position_m: [x, 0.0, 0.0], gripper_rad: 0.6 },
        ));
    }
    script.push((1.0, Action::SkillPedal(true)));
    script.push((1.1, Action::SkillPedal(false)));
    // While the skill runs the hand wanders off: ignored.
    script
        .push((1.5, Action::Handle { arm: ArmName::Left, position_m: [0.05, 0.05, 0.0], gripper_rad: 0.0 }));
    script.push((2.5, Action::EmergencyStop(true)));
    let report = run_session(
        world,
        &rig,
        &config,
        &learned,
        Method::Dmp,
        TeleopSettings::default(),
        &script,
        3.0,
        false,
    )
    .expect("the session runs");
    for (t, what) in &report.log {
        println!("{t:.3} s: {what}");
    }

    // Teleoperation: 1.5 cm of handle moved the left's tip 5 mm along the world's x.
    let start = tip(&report, ArmName::Left, 0.05);
    let nudged = tip(&report, ArmName::Left, 0.98) - start;
    assert!((nudged - Vector3::new(0.005, 0.0, 0.0)).norm() < 3e-4, "teleoperated by {nudged:?}");
    // The pedal instantiated the skill at once (its preview passed).
    assert_eq!(report.refused, None);
    let started = report.skill_started_s.expect("the skill started");
    assert!((started - 1.0).abs() < 0.01, "started at {started} s");
    // The wandering hand did not steer the left: it would be 1.7 cm off in x and y.
    let steered = start + Vector3::new(0.05, 0.05, 0.0) / 3.0;
    assert!(
        (tip(&report, ArmName::Left, 2.4) - steered).norm() > 0.005,
        "the master steered during the skill"
    );
    // The emergency stop: every arm stands still from shortly after it.
    assert_eq!(report.status, Status::EmergencyStopped);
    assert!(
        report.log.iter().any(|(t, w)| w == "emergency stop" && (*t - 2.5).abs() < 0.01),
        "{:?}",
        report.log
    );
    for arm in [ArmName::Left, ArmName::Right, ArmName::Assist] {
        let drift = (tip(&report, arm, 3.0) - tip(&report, arm, 2.6)).norm();
        assert!(drift < 1e-4, "{arm} moved {drift} m after the emergency stop");
    }
    // The session is a teleoperated recording in the demonstration format: written, read back whole.
    let dir = std::env::temp_dir().join(format!("knotlab-lab-session-{}", std::process::id()));
    write_demonstration(&dir, &report.demonstration).expect("written");
    let back = load_demonstration(&dir).expect("read back");
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(back.metadata.source, "teleoperation");
    let left = back.instrument(ArmName::Left).expect("the left's record");
    assert!(
        (left.samples.len() as i64 - 301).abs() <= 1,
        "{} samples at 100 Hz over 3 s",
        left.samples.len()
    );
    let recorded =
        left.samples.iter().find(|s| s.time_s >= 0.98).unwrap().position_m - left.samples[5].position_m;
    assert!((recorded - nudged).norm() < 1e-4, "the recording holds the nudge: {recorded:?}");
}
