//! Closed-form inverse kinematics of the RV-6SL for a flange pose: up to eight branches (shoulder
//! front/back, elbow up/down, wrist flip), filtered by the joint limits, nearest to the current joints.
//!
//! The wrist centre fixes axes 1-3 (no lateral offsets: it lies in the plane of axis 1, so axis 1 is
//! its azimuth or that plus pi, then a planar two-link problem). Axes 4-6 follow from
//! `R36 = Rz(t4) Rx(90) Rz(t5) Rx(90) Rz(t6) = Rz(t4) Ry(-t5) Rz(-t6) Rx(180)`, a ZYZ decomposition.

use nalgebra::{IsometryMatrix3, Matrix3, Vector3};
use std::f64::consts::PI;

use super::error::IkError;
use super::limits::{JointId, JointLimit, wrap_angle};
use super::rv6sl::Rv6slGeometry;

/// Below this sine the wrist (or shoulder) is treated as singular and the free angle is kept at its
/// current value; the orientation error this leaves is below this value times pi.
const SINGULAR_EPS: f64 = 1e-10;

/// The geometric branches for one flange pose, with axes 1-5 inside their limits. Axis 6 is left as
/// an angle in (-pi, pi]: callers pick its turn (and, for instruments, split it with the roll).
#[derive(Clone, Copy, Debug)]
pub struct ArmBranches {
    /// Branch joint vectors; only the first `count` are valid.
    pub joints_rad: [[f64; 6]; 8],
    /// Number of valid branches.
    pub count: usize,
    /// When `count` is 0: why (out of reach, or the least-violating limit).
    pub failure: Option<IkError>,
}

impl ArmBranches {
    /// The valid branches.
    pub fn as_slice(&self) -> &[[f64; 6]] {
        &self.joints_rad[..self.count]
    }
}

/// `Rz(t1) Rx(-90) Rz(t23) Rx(-90)`: the orientation of DH frame 3 for axis 1 and `t23 = q2 + q3 - pi`.
fn base_rot_frame3(s1: f64, c1: f64, s23: f64, c23: f64) -> Matrix3<f64> {
    // Rz(t1) Rx(-90) = [[c1, 0, -s1], [s1, 0, c1], [0, -1, 0]]
    // Rz(t23) Rx(-90) = [[c23, 0, -s23], [s23, 0, c23], [0, -1, 0]]
    Matrix3::new(c1 * c23, s1, -c1 * s23, s1 * c23, -c1, -s1 * s23, -s23, 0.0, -c23)
}

/// All limit-respecting branches for `base_from_flange`. `current_rad` resolves singular free angles.
pub fn arm_branches(
    geometry: &Rv6slGeometry,
    limits: &[JointLimit; 6],
    base_from_flange: &IsometryMatrix3<f64>,
    current_rad: &[f64; 6],
) -> ArmBranches {
    let mut out = ArmBranches { joints_rad: [[0.0; 6]; 8], count: 0, failure: None };
    let g = geometry;
    let r_flange = base_from_flange.rotation.matrix();
    let approach = r_flange.column(2).into_owned();
    let wrist: Vector3<f64> = base_from_flange.translation.vector - g.d6_m * approach;

    let l3 = g.forearm_m();
    let gamma = g.a3_m.atan2(g.d4_m);
    let (reach_min, reach_max) = g.reach_m();

    let radial = wrist.x.hypot(wrist.y);
    let azimuth = if radial < SINGULAR_EPS { current_rad[0] } else { wrist.y.atan2(wrist.x) };

    let mut best_violation = f64::INFINITY;
    let mut nearest_reach: Option<IkError> = None;

    for t1 in [azimuth, azimuth + PI] {
        let (s1, c1) = t1.sin_cos();
        let r = wrist.x * c1 + wrist.y * s1 - g.a1_m;
        let s = wrist.z - g.d1_m;
        let dist = r.hypot(s);
        let cos_elbow = (dist * dist - g.a2_m * g.a2_m - l3 * l3) / (2.0 * g.a2_m * l3);
        if !(-1.0 - 1e-12..=1.0 + 1e-12).contains(&cos_elbow) {
            if nearest_reach.is_none() || t1 == azimuth {
                nearest_reach =
                    Some(IkError::OutOfReach { distance_m: dist, min_m: reach_min, max_m: reach_max });
            }
            continue;
        }
        let elbow = cos_elbow.clamp(-1.0, 1.0).acos();
        let heading = r.atan2(s);
        for delta in [elbow, -elbow] {
            let q3 = gamma + delta;
            let q2 = heading - (l3 * delta.sin()).atan2(g.a2_m + l3 * delta.cos());
            let (s23, c23) = (q2 + q3 - PI).sin_cos();
            let r03 = base_rot_frame3(s1, c1, s23, c23);
            // M = R36 Rx(180) = Rz(t4) Ry(-t5) Rz(-t6): negate columns y and z of R36.
            let r36 = r03.transpose() * r_flange;
            let m = Matrix3::from_columns(&[
                r36.column(0).into_owned(),
                -r36.column(1),
                -r36.column(2),
            ]);
            let sb = m[(0, 2)].hypot(m[(1, 2)]);
            let b = sb.atan2(m[(2, 2)]);
            // Axis 4 from the approach direction; when axes 4 and 6 are (nearly) in line it is free
            // and stays where it is. Axis 6 then comes from what is left, `Ry(b)^T Rz(a)^T M`, so
            // any error in axis 4 is absorbed rather than doubled.
            let a = if sb < SINGULAR_EPS { current_rad[3] } else { m[(1, 2)].atan2(m[(0, 2)]) };
            let (sa, ca) = a.sin_cos();
            let (sbb, cbb) = b.sin_cos();
            let n00 = cbb * (ca * m[(0, 0)] + sa * m[(1, 0)]) - sbb * m[(2, 0)];
            let n10 = -sa * m[(0, 0)] + ca * m[(1, 0)];
            let c = n10.atan2(n00);
            // The flipped wrist: Rz(a + pi) Ry(-b) Rz(c + pi) is the same rotation.
            let wrist_solutions = [(a, b, c), (a + PI, -b, c + PI)];
            let n_wrist = if sb < SINGULAR_EPS { 1 } else { 2 };
            for &(a, b, c) in &wrist_solutions[..n_wrist] {
                let raw = [t1, q2, q3, a, -b - PI, -c];
                let mut q = [0.0; 6];
                let mut ok = true;
                let mut violation = 0.0;
                let mut worst: Option<(usize, f64, f64)> = None;
                for j in 0..5 {
                    match limits[j].nearest_equivalent(raw[j], current_rad[j]) {
                        Some(v) => q[j] = v,
                        None => {
                            ok = false;
                            let v = wrap_angle(raw[j]);
                            let excess = limits[j].violation(v);
                            violation += excess;
                            if worst.is_none_or(|(_, _, e)| excess > e) {
                                worst = Some((j, v, excess));
                            }
                        }
                    }
                }
                q[5] = wrap_angle(raw[5]);
                if ok {
                    out.joints_rad[out.count] = q;
                    out.count += 1;
                } else if let Some((j, v, _)) = worst
                    && violation < best_violation
                {
                    best_violation = violation;
                    out.failure = Some(IkError::JointLimit {
                        joint: JointId::Arm(j as u8 + 1),
                        value_rad: v,
                        lower_rad: limits[j].lower_rad,
                        upper_rad: limits[j].upper_rad,
                    });
                }
            }
        }
    }
    if out.count == 0 && out.failure.is_none() {
        out.failure = nearest_reach;
    }
    out
}

/// Squared joint-space distance, the measure "nearest the current joints" uses.
pub fn joint_distance_sq(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Full 6-axis inverse kinematics for a flange pose in the base frame: the limit-respecting solution
/// nearest to `current_rad`.
pub fn solve_flange_pose(
    geometry: &Rv6slGeometry,
    limits: &[JointLimit; 6],
    base_from_flange: &IsometryMatrix3<f64>,
    current_rad: &[f64; 6],
) -> Result<[f64; 6], IkError> {
    let branches = arm_branches(geometry, limits, base_from_flange, current_rad);
    let mut best: Option<([f64; 6], f64)> = None;
    for branch in branches.as_slice() {
        let Some(q6) = limits[5].nearest_equivalent(branch[5], current_rad[5]) else {
            continue;
        };
        let mut q = *branch;
        q[5] = q6;
        let cost = joint_distance_sq(&q, current_rad);
        if best.is_none_or(|(_, c)| cost < c) {
            best = Some((q, cost));
        }
    }
    match best {
        Some((q, _)) => Ok(q),
        None => Err(branches.failure.unwrap_or(IkError::JointLimit {
            joint: JointId::Arm(6),
            value_rad: f64::NAN,
            lower_rad: limits[5].lower_rad,
            upper_rad: limits[5].upper_rad,
        })),
    }
}
