//! A wound shut on thread lying in it: the flaps' slides (`SlideStitch`) closed to touching whatever
//! lay between them, and a loop of thread that had sagged into the open wound was left inside both
//! flaps, each flap pushing its particles back into the other every substep; the segments leaving
//! the wound stood stretched (by a fifth, in a trial at 0.15 kg/m and 24 substeps, for as long as the
//! wound stayed shut). Pinched on the seam instead, the thread was pressed with whatever pushed it
//! out of the flaps' overlap each substep, a press that grows as the square of the substeps: in a
//! trial at 24 substeps the flaps pressed a tail drawn through the shut wound with 240 N (3 N at 6)
//! and the jaws drawing it lost it. Now the rope's contacts push the flaps on their slides: the
//! thread holds the flaps apart at its diameter, pressed with what closes them.

use super::common;

use knotlab_sim::rope::rigid::RigidContacts;
use knotlab_sim::rope::slides::SlideStitch;
use knotlab_sim::rope::suture::rope_params;
use knotlab_sim::rope::{RopeParams, Ropes};
use nalgebra::Vector3;
use rapier3d::prelude::*;

/// What [`shut_on_a_loop`] measured.
struct Shut {
    /// The wound gap at the end, m.
    gap_m: f64,
    /// The largest strain of the loop's segments over the last half second.
    largest_strain: f64,
    /// The thread's radius, m.
    radius_m: f64,
    /// The thread's push on each flap across the wound (outward), averaged over the last half
    /// second, N ([exit's, entry's]).
    pressed_n: [f64; 2],
    /// What draws each flap shut there: the load less its spring's push back, N.
    closing_n: f64,
}

/// A strand of the scene's thread laid through `at` (along the wound and up out of the tissue, m,
/// in the tissue's frame) in the open wound beside the stitch, its ends held; the flaps drawn shut
/// with twice their spring's pull at the rest gap for 1 s, the rope stepped in `substeps`.
fn shut_on(at_m: &[[f64; 2]], substeps: usize) -> Shut {
    let common::StitchBench { scene, mut physics, tissue, path, across, .. } =
        common::rope_stitch_bench([0.02, 0.01], [0.02, 0.02]);
    let dt_s = scene.solver.dt_s;
    let params = RopeParams { substeps, ..rope_params(&scene.thread) };
    let radius_m = params.radius_m;
    let spacing_m = 3.0 * radius_m;
    let mut ropes = Ropes::new(params);
    let stitched = ropes.add_strand_along(&path, spacing_m);
    let frame = tissue.world_from_tissue;
    let at = |x: f64, z: f64| frame * nalgebra::Point3::new(x, 0.0, z);
    let laid: Vec<Vector3<f64>> = at_m.iter().map(|[x, z]| at(*x, *z).coords).collect();
    let hanging = ropes.add_strand_along(&laid, spacing_m);
    ropes.w[hanging.start] = 0.0;
    ropes.w[hanging.end - 1] = 0.0;
    let mut slides = SlideStitch::new(&tissue, &scene.tissue, &mut physics, &ropes);
    let shut_n = -2.0 * scene.tissue.opening_stiffness_n_per_m * scene.tissue.rest_gap_m;
    slides.load_n = [shut_n; 2];
    // The flaps touch the loop; the stitched strand passes through them.
    let colliders = tissue.flap_colliders.iter().map(|c| (*c, stitched.clone())).collect();
    let mut contacts = RigidContacts {
        colliders,
        at_collision_radius: tissue.flap_colliders.to_vec(),
        friction: scene.thread.friction,
        ..Default::default()
    };
    let label = |_: RigidBodyHandle| "flap".to_owned();
    let steps = (1.0 / dt_s).round() as usize;
    let mut largest_strain = 0.0_f64;
    let mut pressed_n = [0.0; 2];
    let outward = [-across, across];
    for k in 0..steps {
        contacts.step_with(&mut ropes, dt_s, &physics.bodies, &physics.colliders, &mut slides);
        slides.pose_flaps(&mut physics);
        physics.step(&label).expect("the flaps stay healthy");
        if k >= steps / 2 {
            for p in hanging.start..hanging.end - 1 {
                let strain = (ropes.x[p + 1] - ropes.x[p]).norm() / spacing_m - 1.0;
                largest_strain = largest_strain.max(strain);
            }
            for (flap, pressed) in pressed_n.iter_mut().enumerate() {
                let impulse = contacts.impulse_on(tissue.flaps[flap]);
                *pressed += outward[flap].dot(&impulse) / dt_s / (steps - steps / 2) as f64;
            }
        }
    }
    let gap_m = tissue.gap_m(&physics);
    let u_m = -0.5 * (scene.tissue.rest_gap_m - gap_m);
    let closing_n = -shut_n + scene.tissue.opening_stiffness_n_per_m * u_m;
    Shut { gap_m, largest_strain, radius_m, pressed_n, closing_n }
}

/// A loop sagging 5 mm into the wound, 12 mm along it from the stitch, its ends held 4 mm above the
/// flaps.
const LOOP_M: [[f64; 2]; 3] = [[0.006, 0.004], [0.012, -0.005], [0.018, 0.004]];

/// A strand along the wound 2 mm deep, held at both ends.
const DEEP_M: [[f64; 2]; 2] = [[0.006, -0.002], [0.018, -0.002]];

/// Drawn shut on thread lying in it (a loop sagging in, a strand held along it), the wound closes on
/// the thread's diameter, the thread is not stretched, and it is pressed with what draws the flaps
/// shut, at the nominal scene's 12 substeps and at 24 alike. (At 6, coarser than the scene's step
/// for its 0.15 kg/m in two passes, the strand held along the wound leaves it 0.855 mm open, 7 %
/// over its diameter, and stretched 1.8 %.)
#[test]
fn a_wound_drawn_shut_on_thread_lying_in_it_closes_on_its_diameter_pressed_by_the_closing_pull() {
    for (laid, substeps) in [(&LOOP_M[..], 12), (&LOOP_M[..], 24), (&DEEP_M[..], 12), (&DEEP_M[..], 24)] {
        let shut = shut_on(laid, substeps);
        let Shut { gap_m, largest_strain, radius_m, pressed_n, closing_n } = shut;
        println!(
            "{} points, {substeps} substeps: gap {:.3} mm (the thread {:.3} mm across), largest strain \
             {largest_strain:.4}, pressed {:.3} and {:.3} N, closing {closing_n:.3} N",
            laid.len(),
            gap_m * 1e3,
            2e3 * radius_m,
            pressed_n[0],
            pressed_n[1],
        );
        assert!(
            (1.8 * radius_m..2.1 * radius_m).contains(&gap_m),
            "at {substeps} substeps the wound closed to {gap_m} m on a thread {} m across",
            2.0 * radius_m
        );
        assert!(
            largest_strain < 0.02,
            "at {substeps} substeps the loop's segments stretched by {largest_strain}"
        );
        for pressed in pressed_n {
            assert!(
                (pressed - closing_n).abs() < 0.15 * closing_n,
                "at {substeps} substeps a flap pressed the thread with {pressed} N, drawn shut by {closing_n} N"
            );
        }
    }
}
