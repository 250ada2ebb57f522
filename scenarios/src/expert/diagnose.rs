//! What the expert's developer needs to see in a run: how many times the thread winds around an
//! instrument's jaws (the winding number of the centreline about the jaw axis), and how the long end
//! lay round both instruments when the left took the tail, and which of its segments lay on the right.

use knotlab_hw::rig::ArmName;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld};
use nalgebra::{Point3, Vector3};

/// Signed turns of the polyline `points` about the line through `centre_m` along `axis`: the angle
/// its points sweep around the line, projected on the plane at right angles to it, over 2 pi.
/// Positive is right-handed about `axis`.
pub fn turns_about(points: &[Vector3<f64>], centre_m: &Vector3<f64>, axis: &Vector3<f64>) -> f64 {
    let a = axis.normalize();
    let helper = if a.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    let e1 = a.cross(&helper).normalize();
    let e2 = a.cross(&e1);
    let angles: Vec<f64> = points
        .iter()
        .map(|p| {
            let q = p - centre_m;
            q.dot(&e2).atan2(q.dot(&e1))
        })
        .collect();
    let total: f64 = angles
        .windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            (d + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        })
        .sum();
    total / std::f64::consts::TAU
}

/// `arm`'s jaw centre and jaw direction as they stand, world frame.
fn jaw_axis(world: &SimWorld, arm: ArmName) -> (Vector3<f64>, Vector3<f64>) {
    let tip = world.world_from_tip(arm);
    ((tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords, tip.rotation * Vector3::z())
}

/// Turns of the thread (needle end to tail end) around `arm`'s jaws, as they stand.
pub fn thread_turns_around_jaws(world: &SimWorld, arm: ArmName) -> f64 {
    let (centre, axis) = jaw_axis(world, arm);
    turns_about(&world.thread_centreline(), &centre, &axis)
}

/// Turns of the long end (needle end to the exit hole) around `arm`'s jaws, as they stand; `None`
/// while the stitch holds no thread.
pub fn long_end_turns_around_jaws(world: &SimWorld, arm: ArmName) -> Option<f64> {
    let inside = world.thread_inside()?;
    let line = world.thread_centreline();
    let (centre, axis) = jaw_axis(world, arm);
    let long_end = &line[..=(*inside.start()).min(line.len() - 1)];
    Some(turns_about(long_end, &centre, &axis))
}

/// The long end's segments touching the links whose names start with `link_prefix`, sorted, each
/// once; `None` while the stitch holds no thread.
pub fn long_end_segments_on(world: &SimWorld, link_prefix: &str) -> Option<Vec<usize>> {
    let inside = world.thread_inside()?;
    let mut segments: Vec<usize> = world
        .thread_contacts()
        .into_iter()
        .filter(|(segment, link)| *segment < *inside.start() && link.starts_with(link_prefix))
        .map(|(segment, _)| segment)
        .collect();
    segments.dedup();
    Some(segments)
}

/// How the long end lay when the left first closed on the thread (taking the tail): the throw's
/// turns should be round the left's jaws only. Turns about each jaw axis, right-handed about the
/// jaws' direction; a loop round both instruments counts about both (with opposite signs when the
/// jaws point towards each other).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CoilsAtTake {
    /// When the left closed, s from the start of the recording.
    pub time_s: f64,
    /// Turns of the long end round the left's jaws.
    pub left_turns: f64,
    /// Turns of the long end round the right's jaws.
    pub right_turns: f64,
    /// The long end's segments (from the needle end) touching the right's instrument: besides the
    /// few next to the needle in its jaws, a bight of the exit's leg hooked over the right's jaws
    /// shows as two segments far apart, and the right's pulls drag it along.
    pub long_end_on_right: Vec<usize>,
}

impl CoilsAtTake {
    /// The long end's turns round both instruments' jaws now; `None` while the stitch holds no thread.
    pub fn now(world: &SimWorld, time_s: f64) -> Option<Self> {
        Some(Self {
            time_s,
            left_turns: long_end_turns_around_jaws(world, ArmName::Left)?,
            right_turns: long_end_turns_around_jaws(world, ArmName::Right)?,
            long_end_on_right: long_end_segments_on(world, "right_")?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A two-turn helix counts two turns about its axis, minus two about the reversed axis, and none about a
    /// line beside it.
    #[test]
    fn a_helix_of_two_turns_counts_two() {
        let points: Vec<Vector3<f64>> = (0..=200)
            .map(|i| {
                let t = i as f64 / 200.0 * 2.0 * std::f64::consts::TAU;
                Vector3::new(0.01 * t.cos(), 0.01 * t.sin(), 0.001 * t)
            })
            .collect();
        let turns = turns_about(&points, &Vector3::zeros(), &Vector3::z());
        assert!((turns - 2.0).abs() < 1e-9, "{turns}");
        let mirrored = turns_about(&points, &Vector3::zeros(), &-Vector3::z());
        assert!((mirrored + 2.0).abs() < 1e-9, "{mirrored}");
        let beside = turns_about(&points, &Vector3::new(0.05, 0.0, 0.0), &Vector3::z());
        assert!(beside.abs() < 0.5, "a line beside the helix is not wound around: {beside}");
    }
}
