//! What a policy sees after each step: the instruments' tips, jaws, grasps and gauges, the wound's gap
//! and the thread's centreline resampled to a fixed number of points.

use knotlab_hw::controller::CycleRecord;
use knotlab_sim::world::SimWorld;
use nalgebra::{UnitQuaternion, Vector3};
use serde::Serialize;

use super::ARMS;

/// What an instrument's jaws are doing, as a number for a policy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Grasp {
    /// Open (or closing on nothing yet): 0.
    Open = 0,
    /// Holding the thread or the needle: 1.
    Holding = 1,
    /// Closed on nothing: 2.
    ClosedEmpty = 2,
    /// The hold slipped and the jaws have not reopened since: 3.
    Slipped = 3,
}

/// One step's observation; instruments in the order left, right, assist; world frame.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Observation {
    /// Simulated time since the episode began, s.
    pub time_s: f64,
    /// Each tip's position, m.
    pub world_tip_position_m: [[f64; 3]; 3],
    /// Each tip's orientation (z along the jaws, y the wrist's yaw axis), unit quaternion x, y, z, w.
    pub world_tip_quaternion_xyzw: [[f64; 4]; 3],
    /// Each jaw's opening as it stands, rad.
    pub jaw_rad: [f64; 3],
    /// Each instrument's grasp.
    pub grasp: [Grasp; 3],
    /// The force each instrument's strain gauges read, N.
    pub world_force_n: [[f64; 3]; 3],
    /// The wound's gap, m.
    pub wound_gap_m: f64,
    /// The thread's centreline from the needle end to the tail's end, at evenly spaced points, m.
    pub thread_m: Vec<[f64; 3]>,
}

impl Observation {
    /// What `world` shows after the cycle `record`, the thread at `thread_points` points.
    pub fn now(world: &SimWorld, record: &CycleRecord, time_s: f64, thread_points: usize) -> Self {
        let tip = |k: usize| world.world_from_tip(ARMS[k]);
        let grasp = |k: usize| {
            let arm = world.arm(ARMS[k]);
            if arm.holds() {
                Grasp::Holding
            } else if arm.slipped() {
                Grasp::Slipped
            } else if arm.closed_empty() {
                Grasp::ClosedEmpty
            } else {
                Grasp::Open
            }
        };
        Self {
            time_s,
            world_tip_position_m: std::array::from_fn(|k| tip(k).translation.vector.into()),
            world_tip_quaternion_xyzw: std::array::from_fn(|k| {
                let q = UnitQuaternion::from_rotation_matrix(&tip(k).rotation);
                [q.i, q.j, q.k, q.w]
            }),
            jaw_rad: std::array::from_fn(|k| world.arm(ARMS[k]).actual().tool.jaw_rad),
            grasp: std::array::from_fn(grasp),
            world_force_n: std::array::from_fn(|k| {
                record.arm(ARMS[k]).map_or([0.0; 3], |a| a.world_force_n.into())
            }),
            wound_gap_m: world.wound_gap_m(),
            thread_m: resample(&world.thread_centreline(), thread_points),
        }
    }
}

/// `n` points evenly spaced along the polyline `line` by arc length, its ends included (every point
/// the first when it has no length).
pub fn resample(line: &[Vector3<f64>], n: usize) -> Vec<[f64; 3]> {
    let Some(first) = line.first() else { return vec![[0.0; 3]; n] };
    let mut arc = Vec::with_capacity(line.len());
    arc.push(0.0);
    for w in line.windows(2) {
        arc.push(arc[arc.len() - 1] + (w[1] - w[0]).norm());
    }
    let total = arc[arc.len() - 1];
    if total <= 0.0 || n < 2 {
        return vec![(*first).into(); n];
    }
    let mut out = Vec::with_capacity(n);
    let mut k = 0;
    for i in 0..n {
        let s = total * i as f64 / (n - 1) as f64;
        while k + 2 < arc.len() && arc[k + 1] < s {
            k += 1;
        }
        let span = arc[k + 1] - arc[k];
        let f = if span > 0.0 { ((s - arc[k]) / span).clamp(0.0, 1.0) } else { 0.0 };
        out.push(line[k].lerp(&line[k + 1], f).into());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Resampling keeps the ends and spaces the points evenly along the line, across its corners.
    #[test]
    fn resampled_points_are_evenly_spaced_along_the_line() {
        let line = [Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 0.0)];
        let points = resample(&line, 4);
        assert_eq!(points, vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [1.0, 2.0, 0.0]]);
        assert_eq!(resample(&[Vector3::new(1.0, 1.0, 1.0)], 3), vec![[1.0; 3]; 3]);
    }
}
