//! Regression: closing jaws took the thread segment whose centre lay nearest the jaws' centre, within
//! 3 mm plus half a segment. A coil wound around the jaws (the scripted expert's winding) was taken
//! instead of the tail held across them. The jaws now take what passes between them: the thread that
//! comes within reach of the jaws' line, from their hinge to the tip.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld};
use nalgebra::{Point3, Vector3};
use rapier3d::prelude::Vector;

/// A free thread, weightless, laid straight through `through_m` along `direction`, and the left's
/// jaws open with their centre at `jaw_centre_m`; then the jaws close. Returns whether they hold it.
fn close_on(
    offset_from_jaw_frame: impl Fn(&nalgebra::IsometryMatrix3<f64>) -> (Vector3<f64>, Vector3<f64>),
) -> bool {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("the shipped scene");
    let mut w = SimWorld::new(scene, Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    w.free_thread();
    w.physics_mut().gravity = Vector::ZERO;
    // Nothing else for the thread to touch: laid straight, its 25 cm would run through the tissue pad
    // (an 80-segment thread laid 8 mm deep in it is thrown out at over 20 m/s).
    let [flap_a, flap_b] = w.tissue().flaps;
    for body in [w.tissue().pad, flap_a, flap_b] {
        for c in w.physics().bodies[body].colliders().to_vec() {
            w.physics_mut().colliders[c].set_enabled(false);
        }
    }
    let centre = (w.tissue().world_from_tissue * Point3::new(0.02, 0.0, 0.03)).coords;
    let joints = w.joints_for_jaw_centre(ArmName::Left, &centre).expect("reachable");
    w.command(ArmName::Left, joints);
    for _ in 0..500 {
        w.step().expect("healthy");
    }
    let tip = w.world_from_tip(ArmName::Left);
    let (through, direction) = offset_from_jaw_frame(&tip);
    let half =
        0.5 * chain(w.suture()).thread().segment_length_m * chain(w.suture()).thread().segments.len() as f64;
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &(through - direction.normalize() * half), &direction);
    let mut closed = joints;
    closed.tool.jaw_rad = 0.0;
    w.command(ArmName::Left, closed);
    for _ in 0..200 {
        w.step().expect("healthy");
    }
    w.arm(ArmName::Left).hold().is_some()
}

/// Closing jaws do not take a thread running 4 mm beside them, where a coil wound round them lies.
#[test]
fn a_thread_beside_the_jaws_is_not_taken() {
    // 4 mm beside the jaws' centre, across them: outside the jaws, like a segment of a coil wound
    // around them (its centre as near the jaws' centre as the old rule reached).
    let held = close_on(|tip| {
        let centre = (tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
        (centre + tip.rotation * Vector3::new(0.004, 0.0, 0.0), tip.rotation * Vector3::y())
    });
    assert!(!held, "the jaws took a thread running beside them");
}

/// Closing jaws take a thread lying across their line near the tips.
#[test]
fn a_thread_across_the_jaws_near_their_tips_is_taken() {
    // Across the jaws' line (along the hinge axis), 4 mm from their centre towards the tip.
    let held = close_on(|tip| {
        let near_tip = (tip * Point3::new(0.0, 0.0, -0.001)).coords;
        (near_tip, tip.rotation * Vector3::y())
    });
    assert!(held, "the jaws did not take the thread lying between them");
}
