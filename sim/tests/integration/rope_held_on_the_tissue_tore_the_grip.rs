//! Guards against jaws that take the rope where it lies on the tissue tearing their own grip. With
//! the held particles pinned where the jaws hold them while the tissue's collider pushes them out of
//! it, and the jaws drifting down 2 µm a step (the expert's tremor), the two fight over micrometres,
//! and at the rope's stiffness a micrometre is about a quarter of a newton a particle: the grip reads
//! 0.5, 2.1, 4.0, 6.0 N in four steps and slips (the scene's grip: 5 N). So a held particle touches
//! nothing but what holds it.

use knotlab_sim::rope::grasp::RopeGrasp;
use knotlab_sim::rope::rigid::RigidContacts;
use knotlab_sim::rope::{RopeParams, Ropes};
use nalgebra::Vector3;
use rapier3d::math::{Pose, Vector};
use rapier3d::prelude::*;

const DT_S: f64 = 0.001;

/// Jaws pressing a held rope 0.1 mm into the tissue read under 0.5 N and carry the held particles with them,
/// instead of fighting the tissue's push until the grip slips.
#[test]
fn jaws_pressing_a_held_rope_onto_the_tissue_do_not_tear_their_grip() {
    // A fixed slab whose top is z = 0, the rope lying on it along x, its weight on.
    let mut bodies = RigidBodySet::new();
    let mut colliders = ColliderSet::new();
    let slab = bodies.insert(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.0, -0.005)));
    let slab_collider =
        colliders.insert_with_parent(ColliderBuilder::cuboid(0.05, 0.05, 0.005), slab, &mut bodies);
    let params = RopeParams::default();
    let r = params.radius_m;
    let mut ropes = Ropes::new(params);
    ropes.add_strand_along(&[Vector3::new(-0.02, 0.0, r), Vector3::new(0.02, 0.0, r)], 0.0009);
    for p in 0..ropes.x.len() {
        ropes.force_n[p] = -Vector3::z() * (0.05 * 9.81 * 0.0009);
    }
    let jaws =
        bodies.insert(RigidBodyBuilder::kinematic_position_based().translation(Vector::new(0.0, 0.0, 0.007)));
    let mut contacts =
        RigidContacts { colliders: vec![(slab_collider, 0..0)], friction: 0.3, ..Default::default() };
    for _ in 0..100 {
        contacts.step(&mut ropes, DT_S, &bodies, &colliders);
    }
    // The jaws' line across the rope at its middle, the carrier 7 mm above it.
    let pose = Pose::from_translation(Vector::new(0.0, 0.0, 0.007));
    let line = (Vector3::new(0.0, -0.002, r), Vector3::new(0.0, 0.002, r));
    let grasp = RopeGrasp::try_close(&ropes, &mut contacts, jaws, &pose, line, 0.0016)
        .expect("the jaws close on the rope");
    let mut largest_n: f64 = 0.0;
    let mut z_m = 0.007;
    for _ in 0..50 {
        z_m -= 2e-6;
        let next = Pose::from_translation(Vector::new(0.0, 0.0, z_m));
        bodies[jaws].set_next_kinematic_position(next);
        contacts.step(&mut ropes, DT_S, &bodies, &colliders);
        bodies[jaws].set_position(next, true);
        largest_n = largest_n.max(grasp.force_n(&contacts, DT_S).norm());
    }
    let middle = ropes.x[ropes.x.len() / 2];
    println!("the grip read up to {largest_n:.3} N; the held middle at z = {:.4} mm", middle.z * 1e3);
    // The held run weighs about 0.003 N; 0.1 mm down into soft tissue is nothing to pull on.
    assert!(largest_n < 0.5, "the grip read {largest_n:.2} N");
    assert!(
        (middle.z - (r - 1e-4)).abs() < 1e-6,
        "the held middle went with the jaws: z = {:.4} mm",
        middle.z * 1e3
    );
}
