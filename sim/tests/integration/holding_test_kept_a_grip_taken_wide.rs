//! Guards against jaws that took the tail at a wide angle keeping it through the holding test. A
//! grasp holds until the jaws open past the angle they took it at (opened less, they still squeeze
//! it); the expert takes the tail with its jaws opened 0.8 rad, and closing on a tail at the jaws'
//! centre they squeeze it from about 0.7. Opening every instrument to a fixed 0.6 rad,
//! `SimWorld::release_all` (which starts the holding test) would leave the left holding the tail,
//! and the knot would be judged with an instrument still holding it; it opens each past its grasp.

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{JawState, SimWorld};

/// Releasing every instrument for the holding test lets go of a tail taken with the jaws opened wider than
/// the usual opening, and of the needle.
#[test]
fn release_all_lets_go_of_a_tail_taken_wider_than_the_usual_opening() {
    let scene = parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml")
        .expect("the shipped scene");
    let mut w = SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the rope scene builds");
    let assist = w.arms().iter().position(|a| a.name == ArmName::Assist).expect("an assist");
    assert!(w.arms()[assist].holds(), "the assist holds the tail");
    // As if its jaws had closed on the tail from 0.75 rad, wider than SimWorld::JAW_OPEN_RAD.
    let JawState::Holding { at_jaw_rad, .. } = &mut w.arm_mut(ArmName::Assist).jaws else {
        panic!("the assist holds")
    };
    *at_jaw_rad = 0.75;
    const { assert!(0.75 > SimWorld::JAW_OPEN_RAD) };
    w.release_all();
    for _ in 0..400 {
        w.step().expect("healthy");
    }
    assert!(!w.arm(ArmName::Assist).holds(), "the assist still holds the tail: {:?}", w.events());
    assert!(!w.arm(ArmName::Right).holds(), "the right still holds the needle: {:?}", w.events());
}
