//! While the rope's stitch moves the flaps on its slides (`SlideStitch`), the flaps' prismatic joints
//! are disabled: Rapier would otherwise go on solving them every step between two bodies neither of
//! which is dynamic, at a cost to throughput. Taken out of the stitch, the flaps are
//! dynamic bodies again and must be held by their joints once more, or they fall off the tissue.

use super::common;

use knotlab_sim::rope::slides::SlideStitch;
use knotlab_sim::rope::{RopeParams, Ropes};
use knotlab_sim::tissue::Flap;
use rapier3d::prelude::*;

/// The flaps' joints are disabled while the stitch's slides move them and enabled again on release, so the
/// released flaps stay in place.
#[test]
fn the_flaps_joints_rest_while_the_slides_move_them_and_hold_them_after() {
    let common::StitchBench { scene, mut physics, tissue, path, .. } =
        common::rope_stitch_bench([0.02, 0.01], [0.02, 0.02]);
    let enabled = |physics: &knotlab_sim::physics::Physics| {
        tissue.joints.map(|j| physics.impulse_joints.get(j).expect("the flap's joint").data.is_enabled())
    };
    assert_eq!(enabled(&physics), [true, true], "built on their joints");
    let mut ropes = Ropes::new(RopeParams::default());
    ropes.add_strand_along(&path, 0.0009);
    let slides = SlideStitch::new(&tissue, &scene.tissue, &mut physics, &ropes);
    assert_eq!(enabled(&physics), [false, false], "the slides move the flaps");
    let flap = tissue.flap(Flap::A);
    let at_rest = physics.bodies[flap].translation();
    slides.release(&mut physics);
    assert_eq!(enabled(&physics), [true, true], "released onto their joints");
    let label = |_: RigidBodyHandle| "flap".to_owned();
    for _ in 0..500 {
        physics.step(&label).expect("the flaps stay healthy");
    }
    let fell_m = (physics.bodies[flap].translation() - at_rest).length();
    assert!(fell_m < 0.002, "released, flap A moved {:.1} mm in 0.5 s", fell_m * 1e3);
}
