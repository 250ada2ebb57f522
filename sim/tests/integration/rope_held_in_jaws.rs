//! Jaws holding the rope (`knotlab_sim::rope::grasp`): closed across it, they take the run
//! between them, lift it with the rest hanging, and feel its weight; pulled harder than the grip
//! would hold, the grasp reads the pull, and once let go the rope no longer follows the jaws.

use knotlab_sim::rope::grasp::RopeGrasp;
use knotlab_sim::rope::rigid::RigidContacts;
use knotlab_sim::rope::{RopeParams, Ropes};
use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

const DT_S: f64 = 0.001;
const G_M_S2: f64 = 9.81;

/// A 30 mm rope along x at z = 0, weighed down by gravity, and a kinematic jaw carrier at the
/// origin whose jaws' line crosses the rope along y.
fn setup() -> (Ropes, RigidBodySet, RigidBodyHandle, RopeGrasp, RigidContacts) {
    let mut ropes = Ropes::new(RopeParams::default());
    ropes.add_strand_along(&[Vector3::new(-0.015, 0.0, 0.0), Vector3::new(0.015, 0.0, 0.0)], 0.0003);
    for p in 0..ropes.x.len() {
        ropes.force_n[p] = -Vector3::z() * (G_M_S2 / ropes.w[p]);
    }
    let mut bodies = RigidBodySet::new();
    let body = bodies.insert(RigidBodyBuilder::kinematic_position_based());
    let mut contacts = RigidContacts::default();
    let line = (Vector3::new(0.0, -0.002, 0.0), Vector3::new(0.0, 0.002, 0.0));
    let grasp = RopeGrasp::try_close(&ropes, &mut contacts, body, &Pose::IDENTITY, line, 0.0016)
        .expect("the jaws lie across the rope");
    (ropes, bodies, body, grasp, contacts)
}

/// Moves the carrier to `to` over this step and steps the rope.
fn step(
    ropes: &mut Ropes,
    bodies: &mut RigidBodySet,
    body: RigidBodyHandle,
    contacts: &mut RigidContacts,
    to: Vector,
) {
    let next = Pose::from_translation(to);
    bodies[body].set_next_kinematic_position(next);
    contacts.step(ropes, DT_S, bodies, &ColliderSet::new());
    bodies[body].set_position(next, true);
}

/// Jaws closed across the rope take the 11 particles within reach, lift them with the ends hanging, and carry
/// the rope's weight within 5 %.
#[test]
fn closed_jaws_lift_the_run_between_them_and_feel_the_rope_hang() {
    let (mut ropes, mut bodies, body, grasp, mut contacts) = setup();
    // The particles within 1.6 mm of the jaws' line: 11 of 101.
    assert_eq!(grasp.particles.len(), 11, "{grasp:?}");
    let mut force = Vector3::zeros();
    for k in 0..1000 {
        let lift = 0.01 * ((k + 1) as f64 / 500.0).min(1.0);
        step(&mut ropes, &mut bodies, body, &mut contacts, Vector::new(0.0, 0.0, lift));
        force = grasp.force_n(&contacts, DT_S);
    }
    let middle = ropes.x[ropes.x.len() / 2];
    assert!((middle.z - 0.01).abs() < 1e-9, "the held middle is at z = {:.4} mm", middle.z * 1e3);
    for end in [ropes.x[0], ropes.x[ropes.x.len() - 1]] {
        assert!(end.z < 0.0, "an end hangs only to z = {:.2} mm", end.z * 1e3);
    }
    let weight: f64 = ropes.w.iter().map(|w| G_M_S2 / w).sum();
    println!("held with {force:?} N; the rope weighs {weight:.4} N");
    assert!((force.z - weight).abs() < 0.05 * weight, "the jaws hold it up with {:.4} N", force.z);
}

/// A 2 N pull on a held rope reads back through the grasp, and released, the rope moves off with the pull.
#[test]
fn a_pull_on_the_rope_reads_on_the_grasp_and_a_released_rope_is_pulled_away() {
    let (mut ropes, mut bodies, body, grasp, mut contacts) = setup();
    let end = ropes.x.len() - 1;
    ropes.force_n[end] += Vector3::x() * 2.0;
    let mut force = Vector3::zeros();
    for _ in 0..500 {
        step(&mut ropes, &mut bodies, body, &mut contacts, Vector::ZERO);
        force = grasp.force_n(&contacts, DT_S);
    }
    println!("held against the pull with {force:?} N");
    // The pull of 2 N along +x comes back through the jaws.
    assert!((force.x + 2.0).abs() < 0.1, "the jaws hold against it with {:.3} N", force.x);
    let middle = ropes.x.len() / 2;
    let before = ropes.x[middle];
    grasp.release(&mut contacts);
    assert!(contacts.attachments.is_empty());
    for _ in 0..200 {
        step(&mut ropes, &mut bodies, body, &mut contacts, Vector::ZERO);
    }
    let moved = ropes.x[middle].x - before.x;
    assert!(moved > 0.005, "released, the rope moved only {:.2} mm with the pull", moved * 1e3);
}
