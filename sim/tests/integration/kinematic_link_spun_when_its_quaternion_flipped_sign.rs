//! Regression: a link's pose is a rotation matrix from the kinematic tree, turned into a quaternion
//! each step; where `from_rotation_matrix` changed branch the quaternion flipped sign (the same
//! rotation), and Rapier, which derives a kinematic body's velocity from `next * current^-1` without
//! taking the shorter arc, gave the link a one-step spin of about 780 rad/s. An instrument shaft that
//! a thread lay on flung it off at 24 m/s (`thread_drag.rs` with an 80-segment thread).
//!
//! A full turn of the left arm's last joint passes every link beyond it through such a flip: each
//! link's angular velocity must stay within what the joint's servo can do.

use crate::common::chain;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use std::f64::consts::TAU;

/// A full turn of the wrist joint spins no link of the arm faster than the joint's speed limit, even where a
/// link pose's quaternion flips sign.
#[test]
fn a_full_turn_of_the_wrist_joint_spins_no_link_faster_than_the_joint() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let rig = Rig::shipped().expect("shipped rig");
    let joint_speed_limit_rad_s = rig
        .tree
        .joints
        .iter()
        .find(|j| j.name == "left_joint6")
        .and_then(|j| j.limit.as_ref())
        .map(|l| l.max_velocity_rad_s)
        .expect("left_joint6 has a velocity limit");
    let mut w = SimWorld::new(scene, rig).expect("the shipped scene builds");
    // Nothing for the turning instrument to hit: the thread is freed and floats out of the way.
    w.free_thread();
    w.physics_mut().gravity = rapier3d::prelude::Vector::ZERO;
    let far = nalgebra::Vector3::new(0.0, 0.0, 3.0);
    let (suture, physics) = w.suture_and_physics_mut();
    chain(suture).thread().lay_straight(physics, &far, &nalgebra::Vector3::x());

    let mut command = w.arm(ArmName::Left).command;
    let start_rad = command.arm_rad[5];
    // A full turn towards the middle of the joint's +-2 pi range.
    command.arm_rad[5] = if start_rad <= 0.0 { start_rad + TAU } else { start_rad - TAU };
    w.command(ArmName::Left, command);

    let links: Vec<_> = w
        .rig()
        .tree
        .links
        .iter()
        .enumerate()
        .filter(|(_, l)| l.name.starts_with("left_"))
        .filter_map(|(i, _)| w.link_body(i))
        .filter(|h| w.physics().bodies[*h].is_kinematic())
        .collect();
    assert!(links.len() > 3, "the left arm has {} moving link bodies", links.len());
    let mut fastest_rad_s: f64 = 0.0;
    for _ in 0..1500 {
        w.step().expect("a healthy step");
        for h in &links {
            fastest_rad_s = fastest_rad_s.max(w.physics().bodies[*h].angvel().length());
        }
    }
    let reached_rad = w.arm(ArmName::Left).actual().arm_rad[5];
    println!(
        "joint 6 from {start_rad:.3} to {reached_rad:.3} rad; fastest link {fastest_rad_s:.2} rad/s \
         (joint limit {joint_speed_limit_rad_s:.2} rad/s)"
    );
    assert!(
        (reached_rad - command.arm_rad[5]).abs() < 1e-3,
        "the joint made its full turn: at {reached_rad} rad, commanded {}",
        command.arm_rad[5]
    );
    assert!(
        fastest_rad_s <= joint_speed_limit_rad_s * 1.01,
        "a link spun at {fastest_rad_s} rad/s, faster than its joint can turn ({joint_speed_limit_rad_s} rad/s)"
    );
}
