//! The scripted expert knots the simulated thread: seed 1 of the nominal scene, with the human-like
//! variation on, leaves the thread knotted (a single throw at the time of writing; the surgeon's double
//! throw that issue 6 asks for comes out in about one run in sixteen, see the notes). A change
//! to the scene, the grasp model or the plan that stops the thread from being knotted fails here.

use knotlab_scenarios::expert::{RecordOptions, demonstrate};
use knotlab_sim::knot::KnotType;
use knotlab_sim::scene::parse_scene;

#[test]
fn seed_1_leaves_the_thread_knotted() {
    let scene = parse_scene(include_str!("../default.toml"), "default.toml").expect("the shipped scene");
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = demonstrate(scene, "scenarios/default.toml", 1, true, &options).expect("records");
    let e = &run.evaluation;
    println!(
        "seed 1: {} (knot {:?}, height {:?} m, stitch distance {:?} m), {:.1} s simulated in {:.1} s",
        e.verdict.label(),
        e.knot_before,
        e.height_m,
        e.stitch_distance_m,
        run.simulated_s,
        run.wall_s
    );
    assert_eq!(run.fault, None, "the controller ran the skill to its end");
    let knot = e.knot_before.expect("a centreline the classifier reads");
    assert_ne!(knot, KnotType::Unknot, "the thread is not knotted: {:?}", run.events);
}
