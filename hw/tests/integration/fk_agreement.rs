//! The closed-form FK and the FK computed by walking the URDF's joint tree agree: two descriptions of
//! one robot must never drift apart. The links' sizes are read from the same URDF.

use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::kinematics::residuals::rotation_distance_rad;
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::{IsometryMatrix3, Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const TOL: f64 = 1e-9;

fn distance(a: &IsometryMatrix3<f64>, b: &IsometryMatrix3<f64>) -> f64 {
    (a.translation.vector - b.translation.vector).norm().max(rotation_distance_rad(&a.rotation, &b.rotation))
}

/// Every arm link, the flange and the tip, on random joint vectors (inside and well outside the limits).
#[test]
fn closed_form_and_urdf_walk_agree_on_random_joints() {
    let rig = Rig::shipped().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1982);
    let mut worst: f64 = 0.0;
    for name in ArmName::ALL {
        let arm = rig.arm(name);
        for _ in 0..2_000 {
            let joints = ArmJoints::from_array(std::array::from_fn(|_| rng.random_range(-7.0..7.0)));
            let walked = rig.link_poses(name, &joints);
            let model = &arm.model;
            // URDF link i's frame is DH frame i-1 turned by q_i about its z.
            let dh = model.geometry.base_from_frames(&joints.arm_rad);
            for i in 0..6 {
                let before = if i == 0 { IsometryMatrix3::identity() } else { dh[i - 1] };
                let turn = IsometryMatrix3::from_parts(
                    nalgebra::Translation3::identity(),
                    Rotation3::from_axis_angle(&Vector3::z_axis(), joints.arm_rad[i]),
                );
                let closed = model.world_from_base * before * turn;
                let link = rig.tree.joints[arm.tree_joints[i]].child;
                let d = distance(&walked[link], &closed);
                assert!(d < TOL, "{name} link {}: {d:e} at {:?}", i + 1, joints.to_array());
                worst = worst.max(d);
            }
            for (link, closed) in [
                (arm.flange_link, model.world_from_flange(&joints)),
                (arm.tip_link, model.world_from_tip(&joints)),
            ] {
                let d = distance(&walked[link], &closed);
                assert!(d < TOL, "{name} {}: {d:e} at {:?}", rig.tree.links[link].name, joints.to_array());
                worst = worst.max(d);
            }
        }
    }
    println!("worst disagreement {worst:e}");
}

/// A URDF whose arm differs from the closed-form model (a longer upper arm) is refused on load, naming
/// the arm.
#[test]
fn a_urdf_that_drifts_from_the_model_is_refused() {
    let text = knotlab_hw::rig::DEFAULT_URDF;
    // Joint 3's origin holds DH row 2: the upper arm, 0.38 m along -y.
    let needle = "<joint name=\"right_joint3\" type=\"revolute\">";
    let at = text.find(needle).unwrap();
    let origin_at = at + text[at..].find("xyz=\"").unwrap();
    let end = origin_at + text[origin_at..].find("\" rpy").unwrap();
    let drifted = format!("{}xyz=\"0.0 -0.381 0.0{}", &text[..origin_at], &text[end..]);
    let err = Rig::from_urdf_str(&drifted, "drifted.urdf").unwrap_err().to_string();
    assert!(
        err.contains("drifted.urdf") && err.contains("arm 'right'") && err.contains("kinematics"),
        "{err}"
    );
    assert!(!err.contains("arm 'left'"), "only the drifted arm is named: {err}");
}

/// The tip pose a joint vector reaches is the same whichever arm's tree vector it is written into.
#[test]
fn writing_one_arm_leaves_the_others_at_zero() {
    let rig = Rig::shipped().unwrap();
    let joints = ArmJoints::from_array([0.3; 10]);
    let left = rig.link_poses(ArmName::Left, &joints);
    let zero = rig.link_poses(ArmName::Right, &ArmJoints::default());
    let right_tip = rig.arm(ArmName::Right).tip_link;
    assert!(distance(&left[right_tip], &zero[right_tip]) < 1e-15);
    let left_tip = rig.arm(ArmName::Left).tip_link;
    assert!(distance(&left[left_tip], &zero[left_tip]) > 0.01);
}

/// A link's radius is its capsule's in the shipped URDF (4 mm wrist, 1.5 mm jaw); an unknown link has none.
#[test]
fn a_links_radius_is_its_capsules_in_the_shipped_urdf() {
    let rig = Rig::shipped().expect("the shipped rig");
    assert_eq!(rig.link_radius_m(ArmName::Left, "wrist"), Some(0.004));
    assert_eq!(rig.link_radius_m(ArmName::Right, "jaw_1"), Some(0.0015));
    assert_eq!(rig.link_radius_m(ArmName::Left, "no_such_link"), None);
}
