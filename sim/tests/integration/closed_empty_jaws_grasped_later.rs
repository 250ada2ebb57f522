//! Regression: jaws that had closed on nothing grasped whatever came within reach later (the scripted
//! expert's left, closed to wind the thread around, caught the needle swinging past), and the thread
//! passed through them. Jaws that close on nothing now stay empty, and solid, until they reopen.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

fn world() -> SimWorld {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("the shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("the shipped rig")).expect("the scene builds")
}

fn segment_m(w: &SimWorld, i: usize) -> Vector3<f64> {
    let t = w.physics().bodies[chain(w.suture()).thread().segments[i]].translation();
    Vector3::new(t.x, t.y, t.z)
}

fn go(w: &mut SimWorld, target: &Vector3<f64>, jaw_rad: f64, steps: usize) {
    let mut joints = w.joints_for_jaw_centre(ArmName::Left, target).expect("reachable");
    joints.tool.jaw_rad = jaw_rad;
    w.command(ArmName::Left, joints);
    for _ in 0..steps {
        w.step().expect("healthy");
    }
}

/// Jaws closed on nothing do not grasp the thread they are later lowered onto, and reopening clears their
/// empty state.
#[test]
fn jaws_closed_on_nothing_do_not_grasp_what_comes_later() {
    let mut w = world();
    let middle = chain(w.suture()).thread().segments.len() / 2;
    let above = segment_m(&w, middle) + Vector3::new(0.0, 0.0, 0.02);
    // Closed 2 cm above the thread: nothing to hold.
    go(&mut w, &above, 0.0, 600);
    assert!(w.arm(ArmName::Left).hold().is_none());
    assert!(w.arm(ArmName::Left).closed_empty(), "the jaws closed on nothing");
    // Down onto the thread, still closed: no grasp.
    let on = segment_m(&w, middle);
    go(&mut w, &on, 0.0, 600);
    assert!(w.arm(ArmName::Left).hold().is_none(), "closed jaws grasped the thread they came upon");
    assert!(
        !w.events()
            .iter()
            .any(|e| matches!(e, knotlab_sim::grasp::GraspEvent::Grasped { arm: ArmName::Left, .. }))
    );
    // Reopened, the jaws may close on the thread again.
    go(&mut w, &above, SimWorld::JAW_OPEN_RAD, 400);
    assert!(!w.arm(ArmName::Left).closed_empty(), "reopening clears it");
}
