//! The step-wise episode (`scenarios::episode`, the engine of the Python package's Gymnasium
//! environment): the shipped demonstration played back through its steps ties the knot; the same
//! commands give the same bits; a step lasts its control period; commands beyond their bounds are
//! refused by name; a target out of reach is not taken.

use std::path::Path;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::demonstration::load_demonstration;
use knotlab_scenarios::episode::{
    Ending, Episode, EpisodeError, EpisodeSettings, Grasp, TipCommand, demonstration_commands,
};
use knotlab_sim::knot::Verdict;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

/// The nominal scene as the shipped demonstration was recorded in it (seed 0).
fn nominal_world() -> SimWorld {
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    let mut world = SimWorld::new(scene, Rig::shipped().expect("the shipped rig")).expect("the world");
    world.reseed(0);
    world
}

fn hold() -> [TipCommand; 3] {
    // The jaws as the scene starts them: the left open, the right and the assist closed on what they hold.
    [TipCommand { jaw_rad: 0.6, ..TipCommand::default() }, TipCommand::default(), TipCommand::default()]
}

/// Guards the step API's reason to be: the scripted expert's demonstration, played back through it
/// at 20 steps a second, ties the accepted knot (the controller, its trocar IK and limits in between,
/// as for a skill), and the episode ends when the last instrument lets go.
#[test]
fn the_demonstration_played_back_through_the_steps_ties_the_knot() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let demo = load_demonstration(&root.join("demos/instrument-tie")).expect("the shipped demonstration");
    let settings = EpisodeSettings::default();
    let commands = demonstration_commands(&demo, &settings).expect("its commands");
    assert_eq!(commands.len(), 768, "38.42 s at 20 Hz");
    let mut episode = Episode::new(nominal_world(), settings).expect("an episode");
    let mut ended = None;
    for (k, c) in commands.iter().enumerate() {
        let report = episode.step(c).unwrap_or_else(|e| panic!("step {k}: {e}"));
        assert!(report.out_of_reach.is_empty(), "step {k}: {:?} out of reach", report.out_of_reach);
        if let Some(e) = report.ended {
            ended = Some((k, e));
            break;
        }
    }
    let (k, ending) = ended.expect("the episode ended when the instruments let go");
    assert_eq!(ending, Ending::Released, "at step {k}");
    assert!(k > 700, "it ended at step {k}, before the release");
    let evaluation = episode.evaluation().expect("judged");
    assert_eq!(evaluation.verdict, Verdict::Success, "{evaluation:?}");
    assert!(matches!(episode.step(&hold()), Err(EpisodeError::Ended(Ending::Released))));
}

/// Guards determinism and timing: two episodes given the same commands leave the same bits; each
/// step advances the scene by exactly its control period; a command beyond its bound is refused with
/// the instrument and the field named; a target out of the arm's reach is not taken.
#[test]
fn steps_are_deterministic_timed_bounded_and_within_reach() {
    let settings = EpisodeSettings { control_hz: 50.0, ..EpisodeSettings::default() };
    let rest = hold();
    let mut commands = hold();
    commands[0].world_velocity_mps = Vector3::new(0.0, -0.01, -0.005);
    commands[0].world_turn_rad_s = Vector3::new(0.0, 0.0, 0.5);
    // Ten steps of motion, then ten of rest for the arm to settle (its servos lag and accelerate at
    // a bounded rate, so a tip started at once curves off its line by up to a millimetre).
    let run = || {
        let mut episode = Episode::new(nominal_world(), settings).expect("an episode");
        for k in 0..20 {
            episode.step(if k < 10 { &commands } else { &rest }).expect("a step");
        }
        episode
    };
    let (a, b) = (run(), run());
    let bits = |e: &Episode| format!("{:?}", e.observation()).into_bytes();
    assert_eq!(bits(&a), bits(&b));
    assert!((a.observation().time_s - 0.4).abs() < 1e-12);
    assert!((a.world().time_s() - 0.4).abs() < 1e-9, "the scene at {} s", a.world().time_s());
    // The left moved and turned as asked, the others held.
    let start = Episode::new(nominal_world(), settings).expect("an episode");
    let (before, after) = (start.observation(), a.observation());
    let moved = Vector3::from(after.world_tip_position_m[0]) - Vector3::from(before.world_tip_position_m[0]);
    assert!((moved - Vector3::new(0.0, -0.002, -0.001)).norm() < 2e-5, "the left moved {moved:?}");
    let q = |o: &knotlab_scenarios::episode::Observation| {
        let [x, y, z, w] = o.world_tip_quaternion_xyzw[0];
        nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
    };
    let turned = (q(after) * q(before).inverse()).scaled_axis();
    assert!((turned - Vector3::new(0.0, 0.0, 0.1)).norm() < 1e-3, "the left turned {turned:?}");
    for k in [1, 2] {
        let still =
            Vector3::from(after.world_tip_position_m[k]) - Vector3::from(before.world_tip_position_m[k]);
        assert!(still.norm() < 1e-6, "instrument {k} moved {still:?}");
    }
    assert_eq!(a.observation().grasp[2], Grasp::Holding, "the assist holds the tail");
    let mut fast = hold();
    fast[1].world_velocity_mps = Vector3::new(0.2, 0.0, 0.0);
    let mut episode = run();
    let error = episode.step(&fast).expect_err("too fast");
    assert!(error.to_string().contains("right instrument's world_velocity_mps"), "{error}");
    // A target a metre away is out of every arm's reach: not taken, said so.
    let mut far = hold();
    far[2].world_velocity_mps = Vector3::new(0.0, 0.0, 0.15);
    let not_a_divisor = Episode::new(nominal_world(), EpisodeSettings { control_hz: 300.0, ..settings });
    assert!(not_a_divisor.err().is_some_and(|e| e.to_string().starts_with("control_hz")));
    let mut episode = Episode::new(nominal_world(), settings).expect("an episode");
    let mut refused = false;
    for _ in 0..400 {
        let report = episode.step(&far).expect("a step");
        if report.out_of_reach.contains(&ArmName::Assist) {
            refused = true;
            break;
        }
    }
    assert!(refused, "the assist went 1.2 m up without leaving its reach");
}
