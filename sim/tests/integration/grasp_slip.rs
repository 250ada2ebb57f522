//! (d) A grasp holds below its grip force and slips above it; opening the jaws releases.

use super::common;
use crate::common::chain;

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::grasp::GraspEvent;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// Opens the left jaws, lays the thread through them (across the jaws, its middle segment at the jaw
/// centre), closes them, and returns the held segment.
fn grasp_middle(w: &mut SimWorld) -> usize {
    let open = common::open_left_jaws(w, 0.6);
    let tip = w.world_from_tip(ArmName::Left);
    let centre = tip * nalgebra::Point3::new(0.0, 0.0, -0.005);
    let across = tip.rotation * Vector3::x();
    let half =
        0.5 * chain(w.suture()).thread().segment_length_m * chain(w.suture()).thread().segments.len() as f64;
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &(centre.coords - across * half), &across);
    common::close_left_weightless(w, open, 200);
    w.arm(ArmName::Left).held_at().expect("the closed jaws hold a segment")
}

/// Pulls the thread's tail along its length with `force_n` for up to 0.5 s, the force rising over the
/// first 0.1 s (a hand's pull, not a blow: a step force on the light end segment sends a tension wave
/// along the chain several times the force); stops pulling when the grasp slips (an unopposed pull
/// would fling the thread) and returns whether it did.
fn pull(w: &mut SimWorld, force_n: f64) -> bool {
    let tail = *chain(w.suture()).thread().segments.last().expect("segments");
    let line = chain(w.suture()).thread().centreline(w.physics());
    let direction = (line[line.len() - 1] - line[0]).normalize();
    for step in 0..500 {
        let along = direction * force_n * (f64::from(step + 1) / 100.0).min(1.0);
        w.physics_mut().bodies[tail].reset_forces(true);
        w.physics_mut().bodies[tail].add_force(Vector::new(along.x, along.y, along.z), true);
        w.step().expect("healthy step");
        if w.events().iter().any(|e| matches!(e, GraspEvent::Slipped { .. })) {
            w.physics_mut().bodies[tail].reset_forces(true);
            return true;
        }
    }
    false
}

/// A trocar no arm can pass its tool through is refused, naming the scene key.
#[test]
fn an_unreachable_trocar_is_named() {
    let text = include_str!("../../../scenarios/default.toml")
        .replace("left = [-0.08, 0.12, 1.02]", "left = [3.0, 3.0, 1.02]");
    let scene = parse_scene(&text, "far.toml").expect("in range");
    let err = SimWorld::new(scene, Rig::shipped().expect("shipped rig")).err().expect("refused");
    assert!(err.to_string().starts_with("trocars.left: the left arm cannot put its tool through"), "{err}");
}

/// A grasp pulled at half its grip force holds its segment within 1 mm, and the strain gauge reads the pull.
#[test]
fn a_grasp_holds_below_its_grip_force() {
    let mut w = common::chain_world();
    let segment = grasp_middle(&mut w);
    assert!((chain(w.suture()).thread().segments.len() / 2).abs_diff(segment) <= 1, "held segment {segment}");
    let held_at = w.physics().bodies[chain(w.suture()).thread().segments[segment]].translation();
    let grip = w.grip_force_n();
    assert!(!pull(&mut w, 0.5 * grip), "slipped below the grip force: {:?}", w.events());
    assert!(w.arm(ArmName::Left).hold().is_some());
    let moved =
        (w.physics().bodies[chain(w.suture()).thread().segments[segment]].translation() - held_at).length();
    assert!(moved < 1e-3, "the held segment moved {moved} m");
    // The strain gauge feels the pull.
    let felt = w.arm(ArmName::Left).force_n.norm();
    assert!((felt - 0.5 * w.grip_force_n()).abs() < 0.3 * w.grip_force_n(), "force reading {felt} N");
}

/// A grasp pulled at twice its grip force slips and lets go of the thread.
#[test]
fn a_grasp_slips_above_its_grip_force() {
    let mut w = common::chain_world();
    grasp_middle(&mut w);
    let grip = w.grip_force_n();
    assert!(pull(&mut w, 2.0 * grip), "held above the grip force: {:?}", w.events());
    assert!(w.arm(ArmName::Left).hold().is_none());
}

/// Opening the jaws on a held thread drops the hold and reports the release in the same step.
#[test]
fn opening_the_jaws_releases() {
    let mut w = common::chain_world();
    grasp_middle(&mut w);
    let mut open = w.arm(ArmName::Left).command;
    open.tool.jaw_rad = 0.6;
    w.command(ArmName::Left, open);
    w.step().unwrap();
    assert!(w.arm(ArmName::Left).hold().is_none());
    assert!(w.events().iter().any(|e| matches!(e, GraspEvent::Released { .. })));
}
