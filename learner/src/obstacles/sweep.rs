//! Link collisions along a whole motion (the collision part of a skill's preview): every arm's boxes
//! posed at each step of a joint trajectory and tested against the other arms', the fixed boxes
//! (gantry, table, patient, scene obstacles) and their own (boxes at least [`MIN_SELF_JOINTS`] apart),
//! bounding spheres first, then the separating-axis test. The first collision is reported with the two
//! boxes and the time. Two instruments' parts inside the patient (shafts, wrists, jaws) are not tested
//! against each other: in a knot they work around each other by design (the right winds the thread
//! around the left's jaws), and the box model of their capsules would call every winding a collision;
//! what the preview guards against is the arms, the instruments' housings and anything outside.

use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::rig::ArmName;

use super::obb::Obb;
use super::world::{CollisionWorld, FixedKind, MIN_SELF_JOINTS};

/// The first collision found along a trajectory.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("the {arm} arm's {what} hits {other} at {time_s:.2} s of the skill")]
pub struct LinkCollision {
    /// The moving arm.
    pub arm: ArmName,
    /// Its box (URDF link and collision index).
    pub what: String,
    /// What it hits: another arm's box, a fixed box, or one of its own.
    pub other: String,
    /// When, s.
    pub time_s: f64,
}

/// A posed box with what a message needs.
struct Posed<'a> {
    obb: Obb,
    radius_m: f64,
    arm: Option<ArmName>,
    name: &'a str,
    depth: u8,
    inserted: bool,
    patient: bool,
}

fn meet(a: &Posed<'_>, b: &Posed<'_>) -> bool {
    let reach = a.radius_m + b.radius_m;
    (a.obb.centre_m - b.obb.centre_m).norm_squared() <= reach * reach && a.obb.intersects(&b.obb)
}

/// Whether two boxes are tested: different arms always; one arm's boxes when far enough apart along its
/// chain; an arm's box against a fixed one unless it is inserted and that is the patient.
fn tested(a: &Posed<'_>, b: &Posed<'_>) -> bool {
    match (a.arm, b.arm) {
        (Some(x), Some(y)) if x == y => a.depth.abs_diff(b.depth) >= MIN_SELF_JOINTS,
        (Some(_), Some(_)) => !(a.inserted && b.inserted),
        (Some(_), None) => !(a.inserted && b.patient),
        (None, Some(_)) => !(b.inserted && a.patient),
        (None, None) => false,
    }
}

/// The first link collision along `trajectory` (per arm, its joints at every `step_s` from 0; arms of
/// the world not in it stand at their joints), `None` if there is none. Pairs already touching at the
/// start are left out: they are how the world stands (a box model of links that touch by design), not
/// what the motion does.
pub fn first_link_collision(
    world: &CollisionWorld,
    trajectory: &[(ArmName, Vec<ArmJoints>)],
    step_s: f64,
) -> Option<LinkCollision> {
    let steps = trajectory.iter().map(|(_, j)| j.len()).max().unwrap_or(0);
    let fixed: Vec<Posed<'_>> = world
        .fixed
        .iter()
        .map(|f| Posed {
            obb: f.obb,
            radius_m: f.obb.bounding_radius_m(),
            arm: None,
            name: &f.name,
            depth: 0,
            inserted: false,
            patient: f.kind == FixedKind::Patient,
        })
        .collect();
    let pose_at = |k: usize| -> Vec<Posed<'_>> {
        let mut boxes = Vec::new();
        for arm in &world.arms {
            let joints = trajectory
                .iter()
                .find(|(a, _)| *a == arm.name)
                .and_then(|(_, j)| j.get(k).or(j.last()))
                .unwrap_or(&arm.joints);
            for (b, obb) in arm.boxes.iter().zip(arm.world_boxes_at(joints)) {
                boxes.push(Posed {
                    obb,
                    radius_m: obb.bounding_radius_m(),
                    arm: Some(arm.name),
                    name: &b.name,
                    depth: b.depth,
                    inserted: b.inserted,
                    patient: false,
                });
            }
        }
        boxes
    };
    let moving_count = world.arms.iter().map(|a| a.boxes.len()).sum::<usize>();
    let all = moving_count + fixed.len();
    // Pairs (i, j), i a moving box, j a moving box after it or a fixed one (j >= moving_count).
    let start = pose_at(0);
    let pair = |boxes: &[Posed<'_>], i: usize, j: usize| -> bool {
        let a = &boxes[i];
        let b = if j < moving_count { &boxes[j] } else { &fixed[j - moving_count] };
        tested(a, b) && meet(a, b)
    };
    let touching_at_start: std::collections::HashSet<(usize, usize)> = (0..moving_count)
        .flat_map(|i| ((i + 1)..all).map(move |j| (i, j)))
        .filter(|&(i, j)| pair(&start, i, j))
        .collect();
    for k in 0..steps {
        let boxes = pose_at(k);
        for i in 0..moving_count {
            for j in (i + 1)..all {
                if pair(&boxes, i, j) && !touching_at_start.contains(&(i, j)) {
                    let a = &boxes[i];
                    let b = if j < moving_count { &boxes[j] } else { &fixed[j - moving_count] };
                    let (arm, what, other) = match (a.arm, b.arm) {
                        (Some(x), Some(y)) if x != y && trajectory.iter().all(|(t, _)| *t != x) => {
                            (y, b.name, format!("the {x} arm's {}", a.name))
                        }
                        (Some(x), Some(y)) if x != y => (x, a.name, format!("the {y} arm's {}", b.name)),
                        (Some(x), Some(_)) => (x, a.name, format!("its own {}", b.name)),
                        (Some(x), None) => (x, a.name, b.name.to_owned()),
                        _ => continue,
                    };
                    return Some(LinkCollision {
                        arm,
                        what: what.to_owned(),
                        other,
                        time_s: k as f64 * step_s,
                    });
                }
            }
        }
    }
    None
}
