//! Link collisions along a motion (the collision part of a skill's preview): an arm standing still hits
//! nothing; the left arm swung about its shoulder hits a box put in its way, both named, not before;
//! two instruments' inserted parts touching (the left's jaws driven onto the right's) are not a
//! collision by the rule.

use super::obstacles_common;

use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::*;
use nalgebra::{Point3, Vector3};
use obstacles_common::*;

const STEP_S: f64 = 0.02;

/// The left's joints with its tip moved in a straight line from where it is to `to_m`, along the shaft,
/// in `steps` steps (as far as it can reach).
fn left_towards(rig: &Rig, world: &CollisionWorld, to_m: Vector3<f64>, steps: usize) -> Vec<ArmJoints> {
    let left = world.arm(ArmName::Left).expect("the left arm");
    let model = rig.arm(ArmName::Left).model;
    let from = model.world_from_tip(&left.joints).translation.vector;
    let mut joints = left.joints;
    let mut out = vec![joints];
    for k in 1..=steps {
        let target = TipTarget {
            world_position_m: from.lerp(&to_m, k as f64 / steps as f64),
            orientation: TipOrientation::AlongShaft,
        };
        match model.solve_tip(&target, &left.trocar_m, &joints) {
            Ok(next) => joints = next,
            Err(_) => break,
        }
        out.push(joints);
    }
    out
}

/// Arms standing still at their nominal joints report no link collision.
#[test]
fn standing_still_hits_nothing() {
    let rig = Rig::shipped().expect("the shipped rig");
    let world = nominal_world(&rig);
    let still: Vec<(ArmName, Vec<ArmJoints>)> =
        world.arms.iter().map(|a| (a.name, vec![a.joints; 100])).collect();
    assert_eq!(first_link_collision(&world, &still, STEP_S), None);
}

/// The left's jaws driven onto the right's inside the patient are not reported as a collision.
#[test]
fn instruments_working_together_inside_are_not_a_collision() {
    let rig = Rig::shipped().expect("the shipped rig");
    let world = nominal_world(&rig);
    let right = world.arm(ArmName::Right).expect("the right arm");
    let right_jaws =
        (rig.arm(ArmName::Right).model.world_from_tip(&right.joints) * Point3::new(0.0, 0.0, -0.005)).coords;
    let path = left_towards(&rig, &world, right_jaws, 200);
    assert!(path.len() > 150, "the left reaches most of the way: {} steps", path.len());
    // The jaws meet (the boxes overlap at the end) ...
    let left_model = rig.arm(ArmName::Left).model;
    let end = left_model.world_from_tip(path.last().expect("a path")).translation.vector;
    assert!((end - right_jaws).norm() < 0.01, "{end:?} vs {right_jaws:?}");
    // ... and that is not a collision: both are inside the patient.
    assert_eq!(first_link_collision(&world, &[(ArmName::Left, path)], STEP_S), None);
}

/// A shoulder swing clear of everything reports no collision until a box stands where the elbow passes;
/// then the left link and the box are both named, no later than the elbow gets there.
#[test]
fn an_obstacle_in_the_arms_way_is_hit_with_both_named() {
    let rig = Rig::shipped().expect("the shipped rig");
    let mut world = nominal_world(&rig);
    let left = world.arm(ArmName::Left).expect("the left arm").joints;
    // The shoulder (axis 2) swung by 0.6 rad: clear of everything ...
    let path: Vec<ArmJoints> = (0..=300)
        .map(|k| {
            let mut j = left;
            j.arm_rad[1] += 0.6 * k as f64 / 300.0;
            j
        })
        .collect();
    assert_eq!(first_link_collision(&world, &[(ArmName::Left, path.clone())], STEP_S), None);
    // ... until a box stands where its elbow passes at two thirds of the way.
    let k = 200;
    let model = rig.arm(ArmName::Left).model;
    let elbow = model.world_from_base * model.geometry.base_from_frames(&path[k].arm_rad)[2];
    world.add_obstacle("obstacles[0]", elbow.translation.vector, Vector3::repeat(0.03)).expect("an obstacle");
    let hit = first_link_collision(&world, &[(ArmName::Left, path)], STEP_S).expect("a collision");
    assert_eq!(hit.arm, ArmName::Left);
    assert!(hit.what.starts_with("left_"), "{hit}");
    assert_eq!(hit.other, "obstacles[0]", "{hit}");
    assert!(hit.time_s > 0.0 && hit.time_s <= k as f64 * STEP_S + 1e-9, "{hit}");
    println!("{hit}");
}
