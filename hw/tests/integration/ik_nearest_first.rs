//! The nearest-first branch search skips branches that cannot beat the best found so far; it must
//! return exactly what choosing among all eight branches returns. Seeded random flange poses (from
//! random joints, so reachable) solved from random current joints, nearby and far away.

use super::common;

use knotlab_hw::kinematics::arm_ik::{joint_distance_sq, solve_flange_pose, visit_branches};
use knotlab_hw::rig::{ArmName, Rig};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const POSES: usize = 20_000;

/// The pruned nearest-first branch search returns exactly the nearest of all eight branches over 20,000
/// seeded poses, and does prune.
#[test]
fn nearest_first_search_returns_the_nearest_of_all_branches() {
    let rig = Rig::shipped().unwrap();
    let model = rig.arm(ArmName::Left).model;
    let (geometry, limits) = (model.geometry, model.limits);
    let mut rng = ChaCha8Rng::seed_from_u64(0x6e65_6172);
    let mut pruned_branches = 0usize;
    for i in 0..POSES {
        let truth = common::random_joints(&mut rng, &model).arm_rad;
        let base_from_flange = geometry.base_from_flange(&truth);
        // Half the time the current joints are near the truth (the usual case), else anywhere.
        let current: [f64; 6] = if i % 2 == 0 {
            std::array::from_fn(|k| truth[k] + rng.random_range(-0.3..0.3))
        } else {
            common::random_joints(&mut rng, &model).arm_rad
        };
        // Every branch, no pruning: the visitor never reports a best.
        let mut all = Vec::new();
        let exhaustive = visit_branches(&geometry, &limits, &base_from_flange, &current, |b| {
            all.push(*b);
            f64::INFINITY
        });
        let mut visited = 0;
        let _ = visit_branches(&geometry, &limits, &base_from_flange, &current, |_| {
            visited += 1;
            0.0
        });
        assert!(exhaustive.is_ok() && visited >= 1, "pose {i}: a reachable pose has a branch");
        pruned_branches += all.len() - visited;
        let nearest = all
            .iter()
            .filter_map(|b| {
                let q6 = limits[5].nearest_equivalent(b[5], current[5])?;
                let mut q = *b;
                q[5] = q6;
                Some((q, joint_distance_sq(&q, &current)))
            })
            .fold(None::<([f64; 6], f64)>, |best, (q, c)| match best {
                Some((_, bc)) if bc <= c => best,
                _ => Some((q, c)),
            })
            .map(|(q, _)| q);
        let solved = solve_flange_pose(&geometry, &limits, &base_from_flange, &current).ok();
        assert_eq!(solved, nearest, "pose {i}: current {current:?}");
    }
    println!("{POSES} poses: the search visited {pruned_branches} fewer branches than there are");
    assert!(
        pruned_branches > POSES,
        "the search prunes (a visitor returning 0 stops it at the first branch)"
    );
}
