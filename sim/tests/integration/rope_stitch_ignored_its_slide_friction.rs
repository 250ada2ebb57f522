//! The rope slid through the stitch with no friction at all: `stitch.slide_friction_n` (the friction
//! holding the thread in each flap) was honoured by the capsule chain's stitch only, and the rope's
//! stitch points moved the thread across itself, never along (in the expert's first throw the
//! tail's pull drew 94 mm of the long end through the tissue, 204 to 110 mm of it left between the
//! needle and the exit). Now each flap holds the thread with that friction, split
//! between its two stitch points: drawn out by one end, the rope slides through only once the pull
//! reaches the stitch's friction.

use super::common;

use knotlab_sim::rope::rigid::{Attachment, RigidContacts};
use knotlab_sim::rope::slides::SlideStitch;
use knotlab_sim::rope::{RopeParams, Ropes};
use knotlab_sim::tissue::Flap;
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// The exit end drawn out across the wound at 20 mm/s for 1 s, the entry end free; the pull on the
/// drawn end once the rope slides (the median over the last half second), N, and how far the rope
/// slid through the entry point, m.
fn drawn_through(slide_friction_n: f64) -> (f64, f64) {
    // The exit's end 2 cm up and 1 cm out from its hole; the entry's a 3 cm tail lying up and out.
    let common::StitchBench { scene, mut physics, tissue, across, ends, path, .. } =
        common::rope_stitch_bench([0.02, 0.01], [0.02, 0.02]);
    let dt_s = scene.solver.dt_s;
    let spacing_m = 0.0009;
    // No friction of the rope on itself: the slack drawn through the stitch heaps where it touches
    // itself (a dozen contacts at once), and its friction there (0.1 N) is not the stitch's.
    let no_self_friction =
        RopeParams { static_friction: 0.0, kinetic_friction: 0.0, ..RopeParams::default() };
    let mut ropes = Ropes::new(RopeParams { damping_per_s: 10.0, ..no_self_friction });
    let strand = ropes.add_strand_along(&path, spacing_m);
    let mut slides = SlideStitch::new(&tissue, &scene.tissue, &mut physics, &ropes);
    slides.slide_friction_n = slide_friction_n;
    let start_at_m = slides.at(Flap::A);
    let holder = physics.bodies.insert(
        RigidBodyBuilder::kinematic_position_based()
            .translation(Vector::new(ends[0].x, ends[0].y, ends[0].z)),
    );
    let mut contacts = RigidContacts {
        attachments: vec![Attachment { particle: strand.start, body: holder, local_m: Vector3::zeros() }],
        attachment_impulses: vec![Vector3::zeros()],
        ..Default::default()
    };
    let label = |_: RigidBodyHandle| "body".to_owned();
    let steps = (1.0 / dt_s).round() as usize;
    let mut late_pulls_n = Vec::new();
    for k in 0..steps {
        let to = ends[0] - across * (0.02 * k as f64 * dt_s);
        physics.bodies[holder].set_next_kinematic_translation(Vector::new(to.x, to.y, to.z));
        contacts.step_with(&mut ropes, dt_s, &physics.bodies, &physics.colliders, &mut slides);
        contacts.apply_impulses(&mut physics.bodies);
        slides.pose_flaps(&mut physics);
        physics.step(&label).expect("the bodies stay healthy");
        if k >= steps / 2 {
            late_pulls_n.push(contacts.attachment_impulses[0].norm() / dt_s);
        }
    }
    late_pulls_n.sort_by(f64::total_cmp);
    let slid_m = (slides.at(Flap::A) - start_at_m) * spacing_m;
    (late_pulls_n[late_pulls_n.len() / 2], slid_m)
}

/// The rope drawn through the stitch slides only under a pull of about both flaps' slide friction, and under
/// next to nothing without friction.
#[test]
fn the_rope_slides_through_the_stitch_only_once_pulled_with_its_friction() {
    let (free_n, free_slid_m) = drawn_through(0.0);
    let friction_n = 0.3;
    let (held_n, held_slid_m) = drawn_through(friction_n);
    println!(
        "pulled with {free_n:.3} N without friction (slid {:.1} mm), {held_n:.3} N with {friction_n} N a flap (slid {:.1} mm)",
        free_slid_m * 1e3,
        held_slid_m * 1e3
    );
    // Drawn 20 mm, the rope slides through in both (towards the drawn end: the entry point's place
    // on the rope moves towards the needle's end).
    assert!(free_slid_m.abs() > 0.005 && held_slid_m.abs() > 0.005, "{free_slid_m} m, {held_slid_m} m");
    // Through both flaps, the pull that slides it is their friction; without, next to nothing.
    assert!(held_n > 1.5 * friction_n && held_n < 3.0 * friction_n, "{held_n} N");
    assert!(free_n < 0.2 * friction_n, "{free_n} N");
}
