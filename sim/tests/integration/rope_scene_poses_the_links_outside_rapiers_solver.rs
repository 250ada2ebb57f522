//! With the rope as the suture Rapier has nothing to do with a moving link but carry the needle in
//! the jaws: the links' colliders are out of its broad phase and the arms' own links
//! are fixed bodies posed after each step, out of its solver. Posed so, every link must still stand
//! where the rig's kinematics put it, step after step, as the kinematic ones do (a link left where it
//! was built would show wrong in Rerun and in the thread's contacts); the jaws' carriers stay
//! kinematic, for the needle's grasp joint.

use super::common;

use knotlab_hw::rig::ArmName;

/// While an arm moves, every moving link posed outside Rapier's solver stands exactly at its kinematic pose,
/// its colliders out of the broad phase, and the jaws' carriers stay kinematic.
#[test]
fn every_link_stands_where_the_kinematics_put_it_while_an_arm_moves() {
    let mut w = common::rope_world();
    let link4 =
        w.rig().tree.links.iter().position(|l| l.name == "left_link4").expect("the left's fourth link");
    let body4 = w.link_body(link4).expect("the left's fourth link has a body");
    let start_m = w.physics().bodies[body4].position().translation;
    // The left holds nothing: turn its shoulder 0.05 rad and its wrist 0.1 rad.
    let mut command = w.arm(ArmName::Left).command;
    command.arm_rad[0] += 0.05;
    command.arm_rad[5] += 0.1;
    w.command(ArmName::Left, command);
    for _ in 0..300 {
        w.step().expect("a healthy step");
    }
    let mut positions = vec![0.0; w.rig().tree.joints.len()];
    for arm in ArmName::ALL {
        w.rig().arm(arm).write_tree_positions(&w.arm(arm).actual(), &mut positions);
    }
    let poses = w.rig().tree.root_from_links(&positions);
    let (mut posed, mut kinematic) = (0, 0);
    for (i, pose) in poses.iter().enumerate() {
        let Some(h) = w.link_body(i) else { continue };
        let b = &w.physics().bodies[h];
        let moving = w.rig().tree.path_to(i).iter().any(|&j| w.rig().tree.joints[j].limit.is_some());
        if !moving {
            continue;
        }
        let name = &w.rig().tree.links[i].name;
        if b.is_fixed() {
            posed += 1;
        } else if b.is_kinematic() {
            kinematic += 1;
        }
        let t = pose.translation.vector;
        let at = b.position().translation;
        let off_m = ((at.x - t.x).powi(2) + (at.y - t.y).powi(2) + (at.z - t.z).powi(2)).sqrt();
        assert!(off_m < 1e-9, "{name} stands {off_m:.2e} m from where the kinematics put it");
        let z_axis = b.position().rotation * rapier3d::math::Vector::Z;
        let want = poses[i].rotation * nalgebra::Vector3::z();
        let turn = (z_axis.x * want.x + z_axis.y * want.y + z_axis.z * want.z).clamp(-1.0, 1.0).acos();
        assert!(turn < 1e-6, "{name} is turned {turn:.2e} rad from its kinematic pose");
        for c in b.colliders() {
            assert!(!w.physics().colliders[*c].is_enabled(), "{name}'s collider is in Rapier's broad phase");
        }
    }
    let moved_m = (w.physics().bodies[body4].position().translation - start_m).length();
    println!(
        "{posed} links posed, {kinematic} kinematic; the left's fourth link moved {:.1} mm",
        moved_m * 1e3
    );
    assert!(moved_m > 0.001, "the left's fourth link did not move ({moved_m} m): the test tests nothing");
    assert!(posed >= 24, "{posed} links posed: the arms' own links are Rapier's kinematic bodies again");
    assert!(kinematic >= 3, "{kinematic} kinematic links: the jaws' carriers must be");
    assert!(w.arm(ArmName::Right).holds_needle(), "the right lost the needle");
}
