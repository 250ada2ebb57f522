//! The collision world built from the rig: boxes hung on anchors follow the URDF walk, parts are
//! classified as the patient exemption and self-collision rules need, bad input is refused with the
//! field named, and the IK shortcut for along-shaft tips gives `hw`'s solutions exactly.

use super::obstacles_common;

use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget, Tool, ToolJoints};
use knotlab_hw::rig::{ArmName, Rig, Shape};
use knotlab_learner::obstacles::frames::{AnchorKinematics, world_from_anchors};
use knotlab_learner::obstacles::world::MIN_SELF_JOINTS;
use knotlab_learner::obstacles::*;
use nalgebra::Vector3;
use obstacles_common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn random_joints(rig: &Rig, name: ArmName, jaw_rad: f64, rng: &mut ChaCha8Rng) -> ArmJoints {
    let model = rig.arm(name).model;
    let arm_rad =
        std::array::from_fn(|i| rng.random_range(model.limits[i].lower_rad..model.limits[i].upper_rad));
    let tool = match model.tool {
        Tool::Instrument { limits, .. } => ToolJoints {
            roll_rad: rng.random_range(limits.roll.lower_rad..limits.roll.upper_rad),
            pitch_rad: rng.random_range(limits.pitch.lower_rad..limits.pitch.upper_rad),
            yaw_rad: rng.random_range(limits.yaw.lower_rad..limits.yaw.upper_rad),
            jaw_rad,
        },
        Tool::Endoscope { .. } => ToolJoints::default(),
    };
    ArmJoints { arm_rad, tool }
}

/// Each arm's collision boxes, hung on anchors, match the URDF walk's link poses within 1e-9 and the
/// shapes' extents at random joints.
#[test]
fn anchored_boxes_follow_the_urdf_walk() {
    let rig = Rig::shipped().unwrap();
    let world = nominal_world(&rig);
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let mut compared = 0;
    for arm in &world.arms {
        for _ in 0..50 {
            // The jaws hang on the clevis at the arm's jaw opening: keep it.
            let joints = random_joints(&rig, arm.name, arm.joints.tool.jaw_rad, &mut rng);
            let walked = rig.link_poses(arm.name, &joints);
            for (b, obb) in arm.boxes.iter().zip(arm.world_boxes_at(&joints)) {
                let (link_name, index) = b.name.split_once(" collision ").unwrap();
                let link = rig.tree.link(link_name).unwrap();
                let shape = rig.tree.links[link].collisions[index.parse::<usize>().unwrap()];
                let expected = walked[link] * shape.link_from_shape;
                let dp = (expected.translation.vector - obb.centre_m).norm();
                let dr = (expected.rotation.matrix() - obb.rotation).abs().max();
                assert!(dp < 1e-9 && dr < 1e-9, "{}: {dp:e} m, {dr:e}", b.name);
                let half = match shape.shape {
                    Shape::Box { half_extents_m } => half_extents_m,
                    Shape::Capsule { radius_m, length_m } => {
                        Vector3::new(radius_m, radius_m, 0.5 * length_m + radius_m)
                    }
                    Shape::Sphere { radius_m } => Vector3::repeat(radius_m),
                };
                assert_eq!(obb.half_extents_m, half, "{}", b.name);
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 50 * (15 * 3 + 11));
}

/// The cached anchor kinematics give the uncached anchor poses within 1e-12 at random joints of every arm.
#[test]
fn cached_forward_kinematics_matches_hw() {
    let rig = Rig::shipped().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for name in ArmName::ALL {
        let model = rig.arm(name).model;
        let fast = AnchorKinematics::new(&model);
        for _ in 0..200 {
            let joints = random_joints(&rig, name, 0.3, &mut rng);
            for (a, b) in fast.world_from_anchors(&joints).iter().zip(world_from_anchors(&model, &joints)) {
                assert!((a.to_homogeneous() - b.to_homogeneous()).abs().max() < 1e-12, "{name}");
            }
        }
    }
}

/// The rig's fixed parts are classed as 4 gantry, 1 table and 2 patient, arm boxes as inserted or not,
/// and two boxes of one arm are tested against each other only with enough joints between them.
#[test]
fn rig_parts_are_classified() {
    let rig = Rig::shipped().unwrap();
    let world = nominal_world(&rig);
    let kinds = |kind| world.fixed.iter().filter(|f| f.kind == kind).count();
    assert_eq!(kinds(FixedKind::Gantry), 4);
    assert_eq!(kinds(FixedKind::Table), 1);
    assert_eq!(kinds(FixedKind::Patient), 2);
    assert_eq!(world.fixed.len(), 7);
    for arm in &world.arms {
        for b in &arm.boxes {
            let link = b.name.split_once(" collision ").unwrap().0;
            let tube = link.ends_with("_endoscope") && b.half_extents_m.x < 0.01;
            let through_trocar =
                ["_shaft", "_wrist", "_clevis", "_jaw_1", "_jaw_2"].iter().any(|s| link.ends_with(s));
            assert_eq!(b.inserted, through_trocar || tube, "{}", b.name);
            assert_eq!(b.depth == 0, link == format!("{}_base", arm.name), "{}", b.name);
        }
        for (a, b) in arm.self_pairs() {
            assert!(arm.boxes[a].depth.abs_diff(arm.boxes[b].depth) >= MIN_SELF_JOINTS);
        }
    }
    let left = world.arm(ArmName::Left).unwrap();
    // link 3 against the shaft: tested; link 5 against the shaft (two joints apart): not.
    let idx = |name: &str| left.boxes.iter().position(|b| b.name.starts_with(name)).unwrap();
    let pairs = left.self_pairs();
    assert!(pairs.contains(&(idx("left_link3"), idx("left_shaft"))));
    assert!(!pairs.contains(&(idx("left_link5"), idx("left_shaft"))));
    assert!(!pairs.contains(&(idx("left_jaw_1"), idx("left_jaw_2"))));
}

/// Every arm's tip where it is parked is judged free, not colliding or unreachable.
#[test]
fn parked_arms_are_free() {
    let rig = Rig::shipped().unwrap();
    let world = nominal_world(&rig);
    for arm in &world.arms {
        let tip = arm.model.world_from_tip(&arm.joints).translation.vector;
        let plane = square(tip, 0.01, 2, 1);
        let prepared = PreparedGrid::new(
            &world,
            &GridRequest { arm: arm.name, plane, orientation: SubcellOrientation::AlongShaft },
        )
        .unwrap();
        assert_eq!(prepared.verdict_at(&tip), SubcellVerdict::Free, "{} parked", arm.name);
    }
}

/// The grid's along-shaft IK shortcut solves and refuses exactly the tips `hw`'s solver does, with the
/// same joints.
#[test]
fn along_shaft_shortcut_gives_hw_solutions() {
    let rig = Rig::shipped().unwrap();
    let world = nominal_world(&rig);
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for name in ArmName::ALL {
        let plane = square(Vector3::new(0.0, 0.0, 0.97), 0.3, 10, 1);
        let prepared = PreparedGrid::new(
            &world,
            &GridRequest { arm: name, plane, orientation: SubcellOrientation::AlongShaft },
        )
        .unwrap();
        let arm = world.arm(name).unwrap();
        let (mut solved, mut refused) = (0, 0);
        for _ in 0..400 {
            let tip = Vector3::new(
                rng.random_range(-0.25..0.25),
                rng.random_range(-0.25..0.25),
                rng.random_range(0.85..1.05),
            );
            let target = TipTarget { world_position_m: tip, orientation: TipOrientation::AlongShaft };
            let expected = arm.model.solve_tip(&target, &arm.trocar_m, &arm.joints).ok();
            let got = prepared.solve(&tip);
            assert_eq!(got.map(|j| j.to_array()), expected.map(|j| j.to_array()), "{name} at {tip:?}");
            if got.is_some() { solved += 1 } else { refused += 1 }
        }
        assert!(solved > 50 && refused > 50, "{name}: {solved} solved, {refused} refused");
    }
}

/// A missing arm state, a NaN trocar, a negative box size, bad grid-plane values, a camera given a jaw
/// direction and a zero jaw direction are refused naming what is wrong.
#[test]
fn bad_input_is_refused_with_its_field() {
    let rig = Rig::shipped().unwrap();
    let mut states = nominal_states(&rig);
    let err = CollisionWorld::from_rig(&rig, &states[..3]).unwrap_err();
    assert!(err.to_string().contains("camera"), "{err}");
    states[1].trocar_m.x = f64::NAN;
    let err = CollisionWorld::from_rig(&rig, &states).unwrap_err();
    assert!(err.to_string().contains("arm right") && err.to_string().contains("not finite"), "{err}");

    let mut world = nominal_world(&rig);
    let err = world.add_obstacle("box 7", Vector3::zeros(), Vector3::new(0.1, -0.1, 0.1)).unwrap_err();
    assert!(err.to_string().contains("box 7"), "{err}");

    let o = Vector3::zeros();
    let cases = [
        (GridPlane::new(o, Vector3::x(), Vector3::new(0.1, 1.0, 0.0), 0.1, 10, 2), "axis_v"),
        (GridPlane::new(o, Vector3::zeros(), Vector3::y(), 0.1, 10, 2), "axis_u"),
        (GridPlane::new(o, Vector3::x(), Vector3::y(), 0.0, 10, 2), "size"),
        (GridPlane::new(o, Vector3::x(), Vector3::y(), f64::NAN, 10, 2), "size"),
        (GridPlane::new(o, Vector3::x(), Vector3::y(), 0.1, 1, 2), "cells"),
        (GridPlane::new(o, Vector3::x(), Vector3::y(), 0.1, 10, 0), "subcells"),
        (GridPlane::new(o, Vector3::x(), Vector3::y(), 0.1, 1000, 5), "subcells"),
        (
            GridPlane::new(Vector3::new(f64::INFINITY, 0.0, 0.0), Vector3::x(), Vector3::y(), 0.1, 10, 2),
            "origin",
        ),
    ];
    for (result, field) in cases {
        let err = result.unwrap_err();
        assert!(err.to_string().starts_with(&format!("grid plane: {field}:")), "{err}");
    }
    let plane = square(Vector3::new(0.0, 0.0, 0.97), 0.06, 10, 2);
    let jaw = SubcellOrientation::JawDirection(Vector3::new(0.0, 0.0, -1.0));
    let err = PreparedGrid::new(&world, &GridRequest { arm: ArmName::Camera, plane, orientation: jaw })
        .unwrap_err();
    assert!(err.to_string().contains("camera") && err.to_string().contains("along-shaft"), "{err}");
    let zero = SubcellOrientation::JawDirection(Vector3::zeros());
    let err =
        PreparedGrid::new(&world, &GridRequest { arm: ArmName::Left, plane, orientation: zero }).unwrap_err();
    assert!(err.to_string().contains("jaw direction"), "{err}");
}
