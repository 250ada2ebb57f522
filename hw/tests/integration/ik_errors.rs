//! Targets the solver must refuse, each with its typed error, and never a NaN.

use super::common;

use knotlab_hw::kinematics::{ArmJoints, IkError, IkResiduals, JointId, TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::{Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn at(p: Vector3<f64>, orientation: TipOrientation) -> TipTarget {
    TipTarget { world_position_m: p, orientation }
}

fn left() -> (knotlab_hw::kinematics::ArmModel, Vector3<f64>, ArmJoints) {
    let rig = Rig::shipped().expect("the shipped rig loads");
    (rig.arm(ArmName::Left).model, common::default_trocar(ArmName::Left), ArmName::Left.ready_joints())
}

/// A target whose wrist centre lies beyond any reach is refused as out of reach, its distance past the max.
#[test]
fn a_target_far_out_of_reach_is_out_of_reach() {
    let (model, _, seed) = left();
    // Shaft pointing at the floor from 3 m away: the wrist centre is beyond any reach.
    let trocar = Vector3::new(3.0, 3.0, 1.0);
    let err = model
        .solve_tip(&at(Vector3::new(3.0, 3.0, 0.9), TipOrientation::AlongShaft), &trocar, &seed)
        .unwrap_err();
    assert!(matches!(err, IkError::OutOfReach { distance_m, max_m, .. } if distance_m > max_m), "{err:?}");
}

/// A tip within a millimetre of the trocar, or a wrist bent back to put its pitch axis on the trocar, is
/// refused as too close to the trocar, naming which.
#[test]
fn a_target_within_a_millimetre_of_the_trocar_is_refused() {
    let (model, trocar, seed) = left();
    for offset in [0.0, 0.5e-3, 0.999e-3] {
        let err = model
            .solve_tip(
                &at(trocar + Vector3::new(0.0, 0.0, -offset), TipOrientation::AlongShaft),
                &trocar,
                &seed,
            )
            .unwrap_err();
        assert!(matches!(err, IkError::TooCloseToTrocar { what: "tip", .. }), "{offset}: {err:?}");
    }
    // The tip 2 mm away but the wrist bent back so its pitch axis sits on the trocar.
    let err = model
        .solve_tip(
            &at(
                trocar + Vector3::new(0.0, 0.0, -0.0191),
                TipOrientation::JawDirection(Vector3::new(0.0, 0.0, -1.0)),
            ),
            &trocar,
            &seed,
        )
        .unwrap_err();
    assert!(matches!(err, IkError::TooCloseToTrocar { what: "wrist pitch axis", .. }), "{err:?}");
}

/// A target deeper than the shaft can be inserted is refused as too deep, its depth past the maximum.
#[test]
fn a_target_deeper_than_the_shaft_allows_is_refused() {
    let (model, trocar, seed) = left();
    let err = model
        .solve_tip(&at(trocar + Vector3::new(0.0, 0.0, -0.30), TipOrientation::AlongShaft), &trocar, &seed)
        .unwrap_err();
    assert!(matches!(err, IkError::InsertionTooDeep { depth_m, max_m } if depth_m > max_m), "{err:?}");
}

/// Jaws pointing back up the shaft are refused with a joint-limit error naming a wrist joint, for a jaw
/// direction and a full frame alike.
#[test]
fn a_jaw_bent_past_the_wrist_limit_names_the_wrist_joint() {
    let (model, trocar, seed) = left();
    // Jaws pointing straight back up the shaft: a 180 degree bend.
    let tip = trocar + Vector3::new(0.0, 0.0, -0.10);
    let err = model
        .solve_tip(&at(tip, TipOrientation::JawDirection(Vector3::new(0.0, 0.01, 1.0))), &trocar, &seed)
        .unwrap_err();
    assert!(matches!(err, IkError::JointLimit { joint: JointId::WristYaw, .. }), "{err:?}");
    // A full frame with the jaws pointing straight up, back along a shaft that comes down from above.
    let frame = Rotation3::identity();
    let err = model.solve_tip(&at(tip, TipOrientation::Frame(frame)), &trocar, &seed).unwrap_err();
    assert!(
        matches!(err, IkError::JointLimit { joint: JointId::WristPitch | JointId::WristYaw, .. }),
        "{err:?}"
    );
}

/// A pose reachable only by turning an arm axis past its limit is refused naming that arm joint.
#[test]
fn a_pose_only_reachable_past_an_arm_limit_names_the_arm_joint() {
    let (model, _, seed) = left();
    // Behind the arm's base, reached only by turning axis 1 past its 170 degree limit.
    let base = model.world_from_base.translation.vector;
    let behind =
        base + (base - Vector3::new(0.0, 0.0, base.z)).normalize() * 0.35 - Vector3::new(0.0, 0.0, 0.9);
    let trocar = behind + Vector3::new(0.0, 0.0, 0.1);
    let err = model.solve_tip(&at(behind, TipOrientation::AlongShaft), &trocar, &seed).unwrap_err();
    assert!(matches!(err, IkError::JointLimit { joint: JointId::Arm(_), .. }), "{err:?}");
}

/// Non-finite targets, trocars and jaw directions, a zero jaw direction, and an orientation asked of the
/// camera are each refused with their own typed error, not solved into NaNs.
#[test]
fn non_finite_and_degenerate_inputs_are_typed_errors() {
    let (model, trocar, seed) = left();
    let tip = trocar + Vector3::new(0.0, 0.0, -0.1);
    let nan = Vector3::new(f64::NAN, 0.0, 0.0);
    assert_eq!(
        model.solve_tip(&at(nan, TipOrientation::AlongShaft), &trocar, &seed),
        Err(IkError::NonFiniteTarget)
    );
    assert_eq!(
        model.solve_tip(&at(tip, TipOrientation::AlongShaft), &nan, &seed),
        Err(IkError::NonFiniteTarget)
    );
    assert_eq!(
        model.solve_tip(
            &at(tip, TipOrientation::JawDirection(Vector3::new(0.0, f64::INFINITY, 0.0))),
            &trocar,
            &seed
        ),
        Err(IkError::NonFiniteTarget)
    );
    assert_eq!(
        model.solve_tip(&at(tip, TipOrientation::JawDirection(Vector3::zeros())), &trocar, &seed),
        Err(IkError::ZeroJawDirection)
    );
    let camera = Rig::shipped().unwrap().arm(ArmName::Camera).model;
    assert_eq!(
        camera.solve_tip(&at(tip, TipOrientation::JawDirection(Vector3::z())), &trocar, &seed),
        Err(IkError::OrientationNotControllable)
    );
}

/// Random targets and trocars anywhere in a 4 m box, random seeds: each answer is a finite solution that
/// meets the tolerances, or an error; never a NaN, never a panic.
#[test]
fn random_requests_never_give_nan() {
    let rig = Rig::shipped().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(2026);
    let (mut solved, mut refused) = (0, 0);
    for name in ArmName::ALL {
        let model = rig.arm(name).model;
        for _ in 0..5_000 {
            let mut v = || {
                Vector3::new(
                    rng.random_range(-2.0..2.0),
                    rng.random_range(-2.0..2.0),
                    rng.random_range(0.0..2.5),
                )
            };
            let (tip, trocar, jaw) = (v(), v(), v());
            let tip = trocar + (tip - trocar) * 0.1; // mostly within the shaft's length
            let seed = common::random_joints(&mut rng, &model);
            let orientation = if name == ArmName::Camera {
                TipOrientation::AlongShaft
            } else {
                TipOrientation::JawDirection(jaw)
            };
            let target = at(tip, orientation);
            match model.solve_tip(&target, &trocar, &seed) {
                Ok(q) => {
                    assert!(q.to_array().iter().all(|x| x.is_finite()), "{name}: {q:?}");
                    let r = IkResiduals::measure(&model, &q, &target, &trocar);
                    assert!(
                        r.tip_error_m < 1e-6 && r.orientation_error_rad < 1e-6 && r.trocar_distance_m < 1e-6,
                        "{name}: {r:?}"
                    );
                    solved += 1;
                }
                Err(e) => {
                    assert!(!e.to_string().contains("NaN"), "{e}");
                    refused += 1;
                }
            }
        }
    }
    println!("{solved} solved, {refused} refused");
    assert!(
        solved > 100 && refused > 100,
        "both outcomes must be exercised: {solved} solved, {refused} refused"
    );
}

/// Near the branch boundaries (wrist singularity q5 = 0, elbow stretched, wrist centre on axis 1) the
/// solver still meets the tolerances.
#[test]
fn branch_boundaries_still_meet_the_tolerances() {
    let rig = Rig::shipped().unwrap();
    let model = rig.arm(ArmName::Left).model;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let gamma = 0.1f64.atan2(0.425);
    let mut checked = 0;
    for i in 0..3_000 {
        let mut truth = common::random_joints(&mut rng, &model);
        let eps = [0.0, 1e-12, 1e-9, 1e-6, 1e-3][i % 5] * if i % 2 == 0 { 1.0 } else { -1.0 };
        match (i / 5) % 3 {
            0 => truth.arm_rad[4] = eps,         // wrist singular: axes 4 and 6 in line
            1 => truth.arm_rad[2] = gamma + eps, // elbow stretched: upper arm and forearm in line
            _ => {
                // shoulder singular: wrist centre on axis 1 (q2 chosen to bring it there)
                truth.arm_rad[1] = -(0.085f64 / 0.8).asin() + eps;
            }
        }
        let trocar = common::trocar_on_shaft(&mut rng, &model, &truth);
        let tip = model.world_from_tip(&truth);
        let target = at(tip.translation.vector, TipOrientation::Frame(tip.rotation));
        for seed in [truth, name_seed()] {
            match model.solve_tip(&target, &trocar, &seed) {
                Ok(q) => {
                    let r = IkResiduals::measure(&model, &q, &target, &trocar);
                    assert!(
                        r.tip_error_m < 1e-6 && r.orientation_error_rad < 1e-6 && r.trocar_distance_m < 1e-6,
                        "case {i}: {r:?}"
                    );
                    assert!(common::inside_limits(&model, &q));
                    checked += 1;
                }
                Err(e) => panic!("case {i}: a reachable target was refused: {e}"),
            }
        }
    }
    assert_eq!(checked, 6_000);
}

fn name_seed() -> ArmJoints {
    ArmName::Left.ready_joints()
}
