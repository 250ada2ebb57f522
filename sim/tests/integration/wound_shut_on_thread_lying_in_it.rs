//! A wound shut on thread lying in it stretched the thread: the flaps' slides (`SlideStitch`) close
//! to touching whatever lies between them, and a loop of thread that had sagged into the open wound
//! was left inside both flaps, each flap pushing its particles back into the other every substep;
//! the segments leaving the wound stood stretched (by a fifth, in a trial at 0.15 kg/m and 24
//! substeps, for as long as the wound stayed shut). Now a particle pushed by one body into another
//! that pushes it back is pinched between them, on the seam.

use super::common;

use knotlab_sim::rope::Ropes;
use knotlab_sim::rope::rigid::RigidContacts;
use knotlab_sim::rope::slides::SlideStitch;
use knotlab_sim::rope::suture::rope_params;
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// A loop of the scene's thread sagging 5 mm into the open wound, 12 mm along it from the stitch,
/// its ends held above the flaps; the flaps drawn shut with twice their spring's pull at the rest
/// gap for 1 s. The wound gap at the end, m, the largest strain of the loop's segments over the last
/// half second, and the thread's radius, m.
fn shut_on_a_loop() -> (f64, f64, f64) {
    let common::StitchBench { scene, mut physics, tissue, path, .. } =
        common::rope_stitch_bench([0.02, 0.01], [0.02, 0.02]);
    let dt_s = scene.solver.dt_s;
    let params = rope_params(&scene.thread);
    let radius_m = params.radius_m;
    let spacing_m = 3.0 * radius_m;
    let mut ropes = Ropes::new(params);
    let stitched = ropes.add_strand_along(&path, spacing_m);
    let frame = tissue.world_from_tissue;
    let at = |x: f64, z: f64| frame * nalgebra::Point3::new(x, 0.0, z);
    let sag: Vec<Vector3<f64>> =
        [at(0.006, 0.004), at(0.012, -0.005), at(0.018, 0.004)].iter().map(|p| p.coords).collect();
    let hanging = ropes.add_strand_along(&sag, spacing_m);
    ropes.w[hanging.start] = 0.0;
    ropes.w[hanging.end - 1] = 0.0;
    let mut slides = SlideStitch::new(&tissue, &scene.tissue, &mut physics, &ropes);
    let shut_n = -2.0 * scene.tissue.opening_stiffness_n_per_m * scene.tissue.rest_gap_m;
    slides.load_n = [shut_n; 2];
    // The flaps touch the loop; the stitched strand passes through them.
    let colliders = tissue.flap_colliders.iter().map(|c| (*c, stitched.clone())).collect();
    let mut contacts = RigidContacts { colliders, friction: scene.thread.friction, ..Default::default() };
    let label = |_: RigidBodyHandle| "flap".to_owned();
    let steps = (1.0 / dt_s).round() as usize;
    let mut largest_strain = 0.0_f64;
    for k in 0..steps {
        contacts.step_with(&mut ropes, dt_s, &physics.bodies, &physics.colliders, &mut slides);
        slides.pose_flaps(&mut physics);
        physics.step(&label).expect("the flaps stay healthy");
        if k >= steps / 2 {
            for p in hanging.start..hanging.end - 1 {
                let strain = (ropes.x[p + 1] - ropes.x[p]).norm() / spacing_m - 1.0;
                largest_strain = largest_strain.max(strain);
            }
        }
    }
    (tissue.gap_m(&physics), largest_strain, radius_m)
}

/// Drawn shut on a loop of thread lying in it, the wound shuts and the loop, pinched in it, is not
/// stretched.
#[test]
fn a_wound_drawn_shut_on_thread_lying_in_it_pinches_the_thread_unstretched() {
    let (gap_m, largest_strain, radius_m) = shut_on_a_loop();
    println!(
        "gap {:.3} mm (the thread {:.3} mm across), largest strain {largest_strain:.4}",
        gap_m * 1e3,
        2e3 * radius_m
    );
    assert!(gap_m < 0.25 * radius_m, "the wound stayed {gap_m} m open");
    assert!(largest_strain < 0.02, "the loop's segments stretched by {largest_strain}");
}
