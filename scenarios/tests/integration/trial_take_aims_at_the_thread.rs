//! The take aimed where the thread lies: at a turned and tilted site the left's jaws close on the tail.

use knotlab_hw::rig::Rig;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::take::take_offsets;
use knotlab_scenarios::trial::{StitchMove, TrialSetup, run_trial};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

use super::common;

/// Guards the take at a moved site: the stitch shifted 2-3 cm, turned -24 degrees and tilted 13.9
/// degrees (the site of trial 1 of `knotlab mc --preset workspace --seed 1`), where the left's jaws
/// going where the demonstration had them relative to the stitch closed on nothing (the assist, dragged
/// to its demonstrated pose, lost the tail). Aimed at the tail where it lies (L4 and L5 moved by more
/// than the jaws' 1.6 mm reach), the left takes the tail near its end.
#[test]
fn at_a_turned_and_tilted_site_the_left_takes_the_tail_where_it_lies() {
    let learned = common::shipped_learned();
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the nominal scene");
    let stitch = StitchMove {
        offset_m: Vector3::new(0.0211, -0.0269, 0.0012),
        rotate_rad: (-24f64).to_radians(),
        tilt_rad: 13.9f64.to_radians(),
    };
    let mut moved = scene.clone();
    stitch.apply(&mut moved);
    let world = SimWorld::new(moved, Rig::shipped().expect("the rig")).expect("the moved world");
    let offsets = take_offsets(&world, &learned, &world.tissue().world_from_tissue).expect("the take's aim");
    let names: Vec<&str> = offsets.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["L4", "L5"], "{offsets:?}");
    let by_m = offsets[0].stitch_offset_m.norm();
    assert!(by_m > 0.0016, "the tail lies {:.2} mm from the demonstration's take", by_m * 1e3);
    let setup = TrialSetup {
        scene,
        scene_name: "default.toml".to_owned(),
        seed: 0,
        stitch,
        method: Method::Fluid,
        offsets: Vec::new(),
    };
    // The take comes about 16.2 s into the skill, after the way in that turns the right's jaws from
    // along its shaft to the demonstration's first frame at this site (1 s).
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(17.6), ..RecordOptions::default() };
    let trial = run_trial(&learned, &setup, &options, None).expect("the trial runs");
    let take = trial
        .run
        .events
        .iter()
        .find(|e| e.starts_with("Grasped { arm: Left"))
        .unwrap_or_else(|| panic!("the left took nothing: {:?}", trial.run.events));
    let particle: usize = take
        .split("segment: ")
        .nth(1)
        .and_then(|s| s.split(',').next())
        .and_then(|s| s.parse().ok())
        .expect("a segment");
    let particles = trial.run.final_scene.thread_m.len();
    assert!(particle > particles * 3 / 4, "the left took particle {particle} of {particles}, not the tail");
}
