//! FK(IK(target)) reproduces the target: seeded random reachable targets on every arm of the shipped rig.

use super::common;

use knotlab_hw::kinematics::{IkResiduals, TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const TARGETS_PER_ARM: usize = 10_000;
const TOL: f64 = 1e-6;

/// Targets made by forward kinematics from random joints inside the limits are reachable by
/// construction; the solver must reach each from a far-away seed (the ready pose) and, seeded with the
/// joints that made it, must return exactly those joints (the nearest branch).
#[test]
fn full_frame_targets_round_trip_on_every_instrument_arm() {
    let rig = Rig::shipped().unwrap();
    for name in [ArmName::Left, ArmName::Right, ArmName::Assist] {
        let model = rig.arm(name).model;
        let mut rng = ChaCha8Rng::seed_from_u64(0x6b6e_6f74 + name as u64);
        let mut worst = IkResiduals { tip_error_m: 0.0, orientation_error_rad: 0.0, trocar_distance_m: 0.0 };
        let mut same_branch = 0;
        for i in 0..TARGETS_PER_ARM {
            let truth = common::random_joints(&mut rng, &model);
            let trocar = common::trocar_on_shaft(&mut rng, &model, &truth);
            let tip = model.world_from_tip(&truth);
            let target = TipTarget {
                world_position_m: tip.translation.vector,
                orientation: TipOrientation::Frame(tip.rotation),
            };
            for seed in [name.ready_joints(), truth] {
                let solved = model
                    .solve_tip(&target, &trocar, &seed)
                    .unwrap_or_else(|e| panic!("{name} target {i}: {e} (joints {:?})", truth.to_array()));
                let r = IkResiduals::measure(&model, &solved, &target, &trocar);
                assert!(r.tip_error_m < TOL, "{name} target {i}: tip error {} m", r.tip_error_m);
                assert!(
                    r.orientation_error_rad < TOL,
                    "{name} target {i}: orientation error {} rad",
                    r.orientation_error_rad
                );
                assert!(
                    r.trocar_distance_m < TOL,
                    "{name} target {i}: shaft {} m from trocar",
                    r.trocar_distance_m
                );
                assert!(
                    common::inside_limits(&model, &solved),
                    "{name} target {i}: {:?} outside limits",
                    solved.to_array()
                );
                worst.tip_error_m = worst.tip_error_m.max(r.tip_error_m);
                worst.orientation_error_rad = worst.orientation_error_rad.max(r.orientation_error_rad);
                worst.trocar_distance_m = worst.trocar_distance_m.max(r.trocar_distance_m);
                if seed == truth {
                    let gap = solved
                        .to_array()
                        .iter()
                        .zip(truth.to_array())
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max);
                    assert!(
                        gap < TOL,
                        "{name} target {i}: seeded with the true joints, returned another branch (gap {gap} rad)"
                    );
                    same_branch += 1;
                }
            }
        }
        println!(
            "{name}: {TARGETS_PER_ARM} targets, worst tip {:.2e} m, orientation {:.2e} rad, trocar {:.2e} m, \
             {same_branch} returned the true branch",
            worst.tip_error_m, worst.orientation_error_rad, worst.trocar_distance_m
        );
    }
}

/// A jaw direction alone (no roll about it) is reached too, whenever the demanded bend fits the yaw
/// joint; the rest of the frame is the solver's choice.
#[test]
fn jaw_direction_targets_round_trip() {
    let rig = Rig::shipped().unwrap();
    for name in [ArmName::Left, ArmName::Right, ArmName::Assist] {
        let model = rig.arm(name).model;
        let mut rng = ChaCha8Rng::seed_from_u64(17 + name as u64);
        let mut reached = 0;
        for i in 0..2_000 {
            let mut truth = common::random_joints(&mut rng, &model);
            // All the bend in yaw, within the yaw limit, so the jaw-direction solver's choice exists.
            truth.tool.pitch_rad = 0.0;
            truth.tool.yaw_rad = rng.random_range(-1.3..1.3);
            let trocar = common::trocar_on_shaft(&mut rng, &model, &truth);
            let tip = model.world_from_tip(&truth);
            let jaw = tip.rotation * nalgebra::Vector3::z();
            let target = TipTarget {
                world_position_m: tip.translation.vector,
                orientation: TipOrientation::JawDirection(jaw),
            };
            let solved = model
                .solve_tip(&target, &trocar, &truth)
                .unwrap_or_else(|e| panic!("{name} target {i}: {e}"));
            let r = IkResiduals::measure(&model, &solved, &target, &trocar);
            assert!(
                r.tip_error_m < TOL && r.orientation_error_rad < TOL && r.trocar_distance_m < TOL,
                "{name} {i}: {r:?}"
            );
            assert!(common::inside_limits(&model, &solved));
            reached += 1;
        }
        assert_eq!(reached, 2_000);
    }
}

/// The endoscope is placed by its tip alone.
#[test]
fn endoscope_tip_targets_round_trip() {
    let rig = Rig::shipped().unwrap();
    let model = rig.arm(ArmName::Camera).model;
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for i in 0..TARGETS_PER_ARM {
        let truth = common::random_joints(&mut rng, &model);
        let trocar = common::trocar_on_shaft(&mut rng, &model, &truth);
        let target = TipTarget {
            world_position_m: model.world_from_tip(&truth).translation.vector,
            orientation: TipOrientation::AlongShaft,
        };
        let solved = model.solve_tip(&target, &trocar, &truth).unwrap_or_else(|e| panic!("camera {i}: {e}"));
        let r = IkResiduals::measure(&model, &solved, &target, &trocar);
        assert!(
            r.tip_error_m < TOL && r.orientation_error_rad < TOL && r.trocar_distance_m < TOL,
            "camera {i}: {r:?}"
        );
        assert!(common::inside_limits(&model, &solved));
    }
}

/// Around the operating site, through the default trocars: the rig layout reaches a useful workspace.
/// Every answer is either a solution meeting the tolerances or a typed error; most are solutions.
#[test]
fn workspace_around_the_site_is_mostly_reachable() {
    let rig = Rig::shipped().unwrap();
    for name in [ArmName::Left, ArmName::Right, ArmName::Assist] {
        let model = rig.arm(name).model;
        let trocar = common::default_trocar(name);
        let mut rng = ChaCha8Rng::seed_from_u64(5 + name as u64);
        let (mut ok, total) = (0, 2_000);
        for _ in 0..total {
            let p = nalgebra::Vector3::new(
                rng.random_range(-0.06..0.06),
                rng.random_range(-0.06..0.06),
                rng.random_range(0.90..0.98),
            );
            let to_site = p - trocar;
            let jaw = to_site.normalize()
                + nalgebra::Vector3::new(
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                );
            let target = TipTarget { world_position_m: p, orientation: TipOrientation::JawDirection(jaw) };
            if let Ok(solved) = model.solve_tip(&target, &trocar, &name.ready_joints()) {
                let r = IkResiduals::measure(&model, &solved, &target, &trocar);
                assert!(r.tip_error_m < TOL && r.orientation_error_rad < TOL && r.trocar_distance_m < TOL);
                assert!(common::inside_limits(&model, &solved));
                ok += 1;
            }
        }
        println!("{name}: {ok}/{total} workspace targets reached");
        assert!(ok * 10 >= total * 9, "{name}: only {ok}/{total} workspace targets reached");
    }
}
