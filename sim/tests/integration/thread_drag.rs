//! (b) A thread dragged across an instrument shaft never passes through it: the signed side of every
//! (thread segment, shaft) pair is tracked from step to step.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::convert::to_na;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::tunnelling::{Capsule, TunnellingMonitor};
use knotlab_sim::world::SimWorld;
use nalgebra::{Point3, Vector3};
use rapier3d::prelude::*;

fn world() -> SimWorld {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the shipped scene builds")
}

/// The left instrument's shaft collider.
fn left_shaft(w: &SimWorld) -> ColliderHandle {
    let i = w.rig().tree.links.iter().position(|l| l.name == "left_shaft").expect("a left_shaft link");
    let body = w.link_body(i).expect("the shaft has a body");
    w.physics().bodies[body].colliders()[0]
}

fn shaft_capsule(w: &SimWorld, h: ColliderHandle) -> Capsule {
    let c = &w.physics().colliders[h];
    let cap = c.shape().as_capsule().expect("the shaft is a capsule");
    Capsule {
        a_m: to_na(c.position().transform_point(cap.segment.a)),
        b_m: to_na(c.position().transform_point(cap.segment.b)),
        radius_m: cap.radius,
    }
}

/// Pins a thread end (a segment's end point) to a fixed body where it lies.
fn pin(w: &mut SimWorld, segment: usize, local_x: f64) {
    let body = chain(w.suture()).thread().segments[segment];
    let local = Vector::new(local_x, 0.0, 0.0);
    let at = w.physics().bodies[body].position().transform_point(local);
    let anchor = w.physics_mut().bodies.insert(RigidBodyBuilder::fixed().translation(at));
    w.physics_mut().impulse_joints.insert(
        anchor,
        body,
        SphericalJointBuilder::new().local_anchor2(local),
        true,
    );
}

/// Lays a free thread across the left shaft's path, pins its needle end, then sweeps the shaft through
/// it at `speed_m_s`; returns (tunnelling events, steps in contact, how far the thread's middle moved).
fn drag(speed_m_s: f64) -> (usize, usize, f64) {
    let mut w = world();
    w.free_thread();
    let frame = w.tissue().world_from_tissue;
    let at = |p: [f64; 3]| (frame * Point3::from(Vector3::from(p))).coords;
    // The left jaws start beside the thread's line and sweep across it along +x, 2 cm above the flaps.
    let (from, to) = (at([-0.03, -0.01, 0.02]), at([0.05, -0.01, 0.02]));
    let joints = w.joints_for_jaw_centre(ArmName::Left, &from).expect("reachable start");
    w.command(ArmName::Left, joints);
    for _ in 0..400 {
        w.step().expect("healthy while the shaft gets there");
    }
    // The thread straight along y, across the shaft's path, 1 cm below the jaws' line where the shaft
    // (slanting down towards the tip) will meet it.
    let shaft = left_shaft(&w);
    let s = shaft_capsule(&w, shaft);
    let axis = (s.b_m - s.a_m).normalize();
    // The point of the shaft 5 cm up from its tip end (well above the jaws), then swept along +x.
    let tip_end = if (s.a_m - from).norm() < (s.b_m - from).norm() { s.a_m } else { s.b_m };
    let up = if (s.a_m - from).norm() < (s.b_m - from).norm() { axis } else { -axis };
    let crossing = tip_end + up * 0.05 + Vector3::new(0.015, 0.0, 0.0);
    let half =
        0.5 * chain(w.suture()).thread().segment_length_m * chain(w.suture()).thread().segments.len() as f64;
    let across = frame.rotation * Vector3::y();
    let gravity = w.physics_mut().gravity;
    w.physics_mut().gravity = Vector::ZERO;
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &(crossing - across * half), &across);
    // Held at the needle end only: the shaft carries the rest along, pivoting about the pin.
    let seg = chain(w.suture()).thread().segment_length_m;
    pin(&mut w, 0, -0.5 * seg);
    let middle = chain(w.suture()).thread().segments[chain(w.suture()).thread().segments.len() / 2];
    let middle_start = to_na(w.physics().bodies[middle].translation());

    let mut monitor = TunnellingMonitor::new(0.004);
    let n = chain(w.suture()).thread().segments.len();
    let steps = ((to - from).norm() / speed_m_s / w.config().solver.dt_s) as usize;
    let mut touching = 0;
    // The sweep, then half a second for the lagging servos to arrive.
    for k in 0..steps + 500 {
        let target = from + (to - from) * ((k + 1).min(steps) as f64 / steps as f64);
        let joints = w.joints_for_jaw_centre(ArmName::Left, &target).expect("reachable sweep");
        w.command(ArmName::Left, joints);
        w.step().expect("healthy drag");
        let mut caps = chain(w.suture()).thread().capsules(w.physics(), w.config().thread.radius_m);
        caps.push(shaft_capsule(&w, shaft));
        monitor.update(&caps, (0..n).map(|i| (i, n)));
        if w.physics().narrow_phase.contact_pairs_with(shaft).any(|p| p.has_any_active_contact()) {
            touching += 1;
        }
    }
    w.physics_mut().gravity = gravity;
    let moved = (to_na(w.physics().bodies[middle].translation()) - middle_start).norm();
    (monitor.events, touching, moved)
}

/// A thread dragged by an instrument shaft at 2, 5 and 10 cm/s is carried along by it and never passes
/// through it.
#[test]
fn a_thread_dragged_across_a_shaft_never_passes_through_it() {
    for speed in [0.02, 0.05, 0.1] {
        let (events, touching, moved) = drag(speed);
        println!(
            "{speed} m/s: {events} tunnelling events, {touching} steps in contact, middle moved {moved:.4} m"
        );
        // The drag really happened: the shaft pressed on the thread and carried its middle along.
        assert!(touching > 50, "{speed} m/s: the shaft touched the thread in {touching} steps only");
        assert!(moved > 0.01, "{speed} m/s: the thread's middle moved {moved} m");
        assert_eq!(events, 0, "{speed} m/s: the thread passed through the shaft");
    }
}
