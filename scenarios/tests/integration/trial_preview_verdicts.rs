//! A trial's verdict as the preview gate sees it: a skill whose collision preview finds a link
//! against something is judged `collision`, whatever the simulated knot.

use std::path::Path;

use knotlab_hw::controller::ArmSetup;
use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::preview::{KinematicProblem, kinematic_trajectory};
use knotlab_learner::demonstration::load_demonstration;
use knotlab_learner::pattern::load_pattern;
use knotlab_learner::primitive::learn;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::{Learned, StitchMove, TrialSetup, run_trial};
use knotlab_sim::knot::{FailureMode, Verdict};
use knotlab_sim::scene::{Obstacle, parse_scene};
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::Vector3;

/// The skill learned from the shipped demonstration, and the nominal scene.
fn shipped() -> (Learned, knotlab_sim::scene::SceneConfig) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let demonstration =
        load_demonstration(&root.join("demos/instrument-tie")).expect("the shipped demonstration");
    let pattern = load_pattern(&root.join("patterns/knot_tying.toml")).expect("the shipped pattern");
    let knowledge = learn(&demonstration, &pattern).expect("learned");
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    (Learned { knowledge, demonstration }, scene)
}

/// Guards against a failure mode the reports list but nothing produced: a box standing where the left
/// arm's elbow passes halfway through the skill makes the collision preview find the left arm against
/// it, and the trial is judged `collision` (on real devices the skill would not run), though the
/// simulated trial ran; without the box the same short trial is judged by its knot.
#[test]
fn a_skill_whose_preview_hits_an_obstacle_is_judged_collision() {
    let (learned, scene) = shipped();
    let rig = Rig::shipped().expect("the shipped rig");
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(0.3), ..RecordOptions::default() };
    let trial = |scene| {
        let setup = TrialSetup {
            scene,
            scene_name: "default.toml".to_owned(),
            seed: 0,
            stitch: StitchMove::default(),
            method: Method::Replay,
            offsets: Vec::new(),
        };
        run_trial(&learned, &setup, &options, None).expect("the trial runs")
    };
    let clear = trial(scene.clone());
    assert!(clear.collision.is_none(), "{:?}", clear.collision);
    assert_eq!(clear.verdict(), clear.run.evaluation.verdict);
    // Where the left elbow is halfway through the skill, by the preview's own trajectory.
    let world = SimWorld::new(scene.clone(), rig.clone()).expect("the nominal world");
    let arms = [ArmName::Left, ArmName::Right, ArmName::Assist];
    let setups: Vec<ArmSetup> = arms
        .iter()
        .map(|&a| ArmSetup { arm: a, model: rig.arm(a).model, world_trocar_m: trocar_of(world.config(), a) })
        .collect();
    let current: Vec<(ArmName, ArmJoints)> = arms.iter().map(|&a| (a, world.arm(a).command)).collect();
    let trajectory = kinematic_trajectory(&clear.skill, &setups, &current, 0.02).expect("reachable");
    let left = &trajectory.iter().find(|(a, _)| *a == ArmName::Left).expect("the left's joints").1;
    let model = rig.arm(ArmName::Left).model;
    let elbow_at = |j: &ArmJoints| -> Vector3<f64> {
        (model.world_from_base * model.geometry.base_from_frames(&j.arm_rad)[2]).translation.vector
    };
    // The elbow where it is farthest from where it starts (a box it touches at the start is how the
    // world stands, and the preview leaves it out).
    let start = elbow_at(&left[0]);
    let middle = left
        .iter()
        .map(elbow_at)
        .max_by(|a, b| (a - start).norm().total_cmp(&(b - start).norm()))
        .expect("joints");
    assert!((middle - start).norm() > 0.1, "the elbow moves: {start} to {middle}");
    let mut boxed = scene;
    boxed.obstacles.push(Obstacle { centre_m: middle.into(), half_extents_m: [0.01; 3] });
    let hit = trial(boxed);
    let collision = hit.collision.as_ref().expect("the left arm meets the box");
    assert_eq!(collision.arm, ArmName::Left, "{collision}");
    assert_eq!(hit.verdict(), Verdict::Failure(FailureMode::Collision));
}

/// The kinematic preview of the shipped skill (fluid) at the stitch moved by `stitch`.
fn preview_at(stitch: StitchMove) -> Result<(), KinematicProblem> {
    let (learned, scene) = shipped();
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(0.1), ..RecordOptions::default() };
    let setup = TrialSetup {
        scene,
        scene_name: "default.toml".to_owned(),
        seed: 0,
        stitch,
        method: Method::Fluid,
        offsets: Vec::new(),
    };
    run_trial(&learned, &setup, &options, None).expect("the trial runs").kinematics
}

/// Guards the force-controlled pull within reach: at a stitch moved 2.8 cm towards the right's side
/// (and 7 mm along the wound) the right's pull of R5, on to 125 % of its line, would take its wrist
/// centre beyond the arm's reach (0.8166 m from the shoulder) 40 s into the skill, and the trial would
/// be judged `unreachable`; the pull stops where the reach ends and the kinematic preview passes.
#[test]
fn a_pull_that_would_leave_the_reach_stops_within_it() {
    let stitch = StitchMove {
        offset_m: Vector3::new(0.0066, -0.0281, -0.0001),
        rotate_rad: 0.0373,
        tilt_rad: -0.0245,
    };
    assert_eq!(preview_at(stitch), Ok(()), "the kinematic preview");
}

/// Guards the pulls after the last primitive within reach: at a stitch moved 3 cm towards the tail's
/// side, turned 21 degrees clockwise and tilted 12 degrees, the left's pull on the tail to the
/// demonstration's 3 N, played back moved to the new stitch, would take its wrist centre beyond the
/// arm's reach 26 s into the skill (`unreachable`); it stops where the reach ends and the kinematic
/// preview passes.
#[test]
fn the_tails_pull_after_the_last_primitive_stops_within_reach() {
    let stitch =
        StitchMove { offset_m: Vector3::new(-0.0028, 0.0299, 0.0064), rotate_rad: -0.372, tilt_rad: -0.207 };
    assert_eq!(preview_at(stitch), Ok(()), "the kinematic preview");
}
