//! The left's wrist at a turned site: its jaws' demonstrated frame, bent past the wrist's reach as
//! it turns down towards the tail, is commanded without a jump.

use knotlab_hw::controller::ArmSetup;
use knotlab_hw::kinematics::{ArmJoints, Tool};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::Orientation;
use knotlab_hw::skill::preview::kinematic_trajectory;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::trial::{StitchMove, synthesize_for};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::Vector3;

use super::common;

/// The kinematic preview's step, s.
const STEP_S: f64 = 0.01;

/// Guards the wrist's frame past its reach: at the site of trial 27 of `knotlab mc --preset
/// workspace --seed 1` (shifted about 2.5 cm, turned 22.4 degrees, tilted 4 degrees) the left's jaws,
/// turning from across the wound down towards the tail (L3), ask for more bend than the wrist has.
/// Commanded as a jaw direction there (the whole bend in the yaw), the wrist's pitch jumped 37 degrees
/// between two keys, the arm took 0.15 s at its joints' speed to follow, its tip swung 14 mm off the
/// path, and the long end's turns came off its jaws (no knot). Turned back to the reach, the frame
/// changes as smoothly as the demonstration's: from the left's first commanded frame on, no joint of
/// the left needs more than its speed limit between two steps of the preview (as a jaw direction the
/// pitch needed 10.9 times its limit at 15.26 s).
#[test]
fn at_a_turned_site_the_lefts_joints_never_outrun_their_speed() {
    let learned = common::shipped_learned();
    let mut scene =
        parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    StitchMove {
        offset_m: Vector3::new(-0.018639, -0.015633, 0.002856),
        rotate_rad: 0.390149,
        tilt_rad: 0.069183,
    }
    .apply(&mut scene);
    let rig = Rig::shipped().expect("the rig");
    let world = SimWorld::new(scene, rig.clone()).expect("the moved world");
    let made = synthesize_for(&world, &learned, Method::Fluid).expect("the skill at the turned site");
    let arms = [ArmName::Left, ArmName::Right, ArmName::Assist];
    let setups: Vec<ArmSetup> = arms
        .iter()
        .map(|&arm| ArmSetup {
            arm,
            model: rig.arm(arm).model,
            world_trocar_m: trocar_of(world.config(), arm),
        })
        .collect();
    let current: Vec<(ArmName, ArmJoints)> = arms.iter().map(|&a| (a, world.arm(a).command)).collect();
    let trajectory =
        kinematic_trajectory(&made.skill, &setups, &current, STEP_S).expect("every target reached");
    let (_, left) = trajectory.iter().find(|(arm, _)| *arm == ArmName::Left).expect("the left's track");
    let model = rig.arm(ArmName::Left).model;
    let Tool::Instrument { limits: tool, .. } = model.tool else { panic!("the left holds an instrument") };
    let speed: Vec<f64> = model
        .limits
        .iter()
        .chain([&tool.roll, &tool.pitch, &tool.yaw])
        .map(|l| l.max_velocity_rad_s)
        .collect();
    // From the left's first commanded frame on (before it, leaving its parked pose with the wrist
    // straight, the roll is the solver's and turns to the frame's in one step: not this guard's).
    let track = made.skill.tracks.iter().find(|t| t.arm == ArmName::Left).expect("the left's track");
    let first_frame_s = track
        .poses
        .iter()
        .find(|k| matches!(k.orientation, Orientation::Frame { .. }))
        .expect("a commanded frame")
        .time_s;
    let from = (first_frame_s / STEP_S).ceil() as usize;
    let (mut worst, mut at) = (0.0f64, (0, 0));
    for (k, pair) in left.windows(2).enumerate().skip(from) {
        let (a, b) = (pair[0].to_array(), pair[1].to_array());
        for j in 0..ArmJoints::LEN - 1 {
            let over = (b[j] - a[j]).abs() / (speed[j] * STEP_S);
            if over > worst {
                (worst, at) = (over, (k, j));
            }
        }
    }
    assert!(
        worst <= 1.0,
        "the left's joint {:?} must move {worst:.1} times its speed limit at {:.2} s of the skill",
        ArmJoints::ORDER[at.1],
        at.0 as f64 * STEP_S
    );
}
