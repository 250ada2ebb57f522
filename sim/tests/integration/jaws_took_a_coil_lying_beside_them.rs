//! Guards against closing jaws taking a coil of the rope wound round them. A grasp that fires as
//! soon as any thread comes within reach (1.6 mm) of the jaws' line where the gap between their
//! capsules is narrower than the thread, and takes the particle nearest that line wherever round it
//! it lies, takes the wrong thread: on the rope scene's seed 3 (`looks-and-cinches.toml`) the left,
//! its jaws still 0.66 rad open, would take the long end's coil lying in the notch beside them,
//! 1.32 mm from their line and all of it along the hinge, instead of the tail. The jaws take only
//! thread between their faces: its centre no further along the hinge than the jaws' radius less its
//! own (1.5 - 0.4 mm).

use knotlab_sim::grasp::{Grasp, JawFaces, jaw_line_m};
use knotlab_sim::rope::grasp::RopeGrasp;
use knotlab_sim::rope::{RopeParams, Ropes};
use knotlab_sim::tunnelling::Capsule;
use knotlab_sim::world::{GRASP_REACH_M, JAW_CENTRE_OFFSET_M};
use nalgebra::{IsometryMatrix3, Vector3};

/// The jaws' tip at the origin, pointing along +z, their hinge along y (the tip frame is the world).
const JAW_RADIUS_M: f64 = 0.0015;
const THREAD_RADIUS_M: f64 = 0.0004;

/// A straight piece of thread through `at_m` along `along`, 20 mm long.
fn piece(at_m: Vector3<f64>, along: Vector3<f64>) -> [Vector3<f64>; 2] {
    [at_m - along * 0.01, at_m + along * 0.01]
}

/// Jaws 0.66 rad open squeeze a thread lying between their faces but not one lying 1.32 mm beside them along
/// the hinge.
#[test]
fn closing_jaws_squeeze_thread_between_their_faces_not_beside_them() {
    let tip = IsometryMatrix3::identity();
    // 4.6 mm from the hinge (10 mm behind the tip), where jaws 0.66 rad open leave no room.
    let z_m = -0.0054;
    // Beside the jaws: 1.32 mm along the hinge (within reach of the line), running across them.
    let beside = piece(Vector3::new(0.0, 0.00132, z_m), Vector3::x());
    // Between them: 1.2 mm off the line across the hinge, running along it.
    let between = piece(Vector3::new(0.0012, 0.0, z_m), Vector3::y());
    let squeezes = |[a_m, b_m]: [Vector3<f64>; 2]| {
        let capsules = [Capsule { a_m, b_m, radius_m: 0.0 }];
        Grasp::squeeze(&capsules, &tip, JAW_CENTRE_OFFSET_M, 0.66, JAW_RADIUS_M, THREAD_RADIUS_M)
    };
    assert!(!squeezes(beside), "a thread beside the jaws is not squeezed");
    assert!(squeezes(between), "a thread between them is");
    let faces = JawFaces::of(&tip, JAW_RADIUS_M, THREAD_RADIUS_M);
    let middle = |[a, b]: [Vector3<f64>; 2]| a.lerp(&b, 0.5);
    assert!(!faces.between(&middle(beside)) && faces.between(&middle(between)));
}

/// Closing jaws take the rope strand between their faces rather than a coil beside them nearer their line,
/// and take nothing when only the coil is there.
#[test]
fn closing_jaws_take_the_rope_between_their_faces_not_the_coil_beside_them() {
    let tip = IsometryMatrix3::identity();
    let line = jaw_line_m(&tip, JAW_CENTRE_OFFSET_M);
    let faces = JawFaces::of(&tip, JAW_RADIUS_M, THREAD_RADIUS_M);
    // A strand beside the jaws, nearer their line (1.32 mm), and one between them (1.58 mm off it).
    let mut ropes = Ropes::new(RopeParams::default());
    let [a, b] = piece(Vector3::new(0.0, 0.00132, -0.005), Vector3::x());
    let coil = ropes.add_strand_along(&[a, b], 0.0005);
    let [a, b] = piece(Vector3::new(0.00158, 0.0, -0.005), Vector3::y());
    let tail = ropes.add_strand_along(&[a, b], 0.0005);
    // Without the faces, the nearest particle is the coil's.
    let nearest = RopeGrasp::run_between(&ropes, line, GRASP_REACH_M, None).expect("within reach");
    assert!(coil.contains(&nearest.start), "{nearest:?} in {coil:?}");
    // Between the faces, the tail's.
    let taken = RopeGrasp::run_between(&ropes, line, GRASP_REACH_M, Some(&faces)).expect("the tail");
    assert!(tail.contains(&taken.start) && tail.contains(&(taken.end - 1)), "{taken:?} in {tail:?}");
    // The coil alone beside the jaws: nothing to take.
    let mut alone = Ropes::new(RopeParams::default());
    let [a, b] = piece(Vector3::new(0.0, 0.00132, -0.005), Vector3::x());
    alone.add_strand_along(&[a, b], 0.0005);
    assert_eq!(RopeGrasp::run_between(&alone, line, GRASP_REACH_M, Some(&faces)), None);
}
