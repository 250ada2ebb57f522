//! Closed-form inverse kinematics of the RV-6SL for a flange pose: up to eight branches (shoulder
//! front/back, elbow up/down, wrist flip), filtered by the joint limits, nearest to the current joints
//! (searched nearest-first, so the far branches are usually never solved).
//!
//! The wrist centre fixes axes 1-3 (no lateral offsets: it lies in the plane of axis 1, so axis 1 is
//! its azimuth or that plus pi, then a planar two-link problem). Axes 4-6 follow from
//! `R36 = Rz(t4) Rx(90) Rz(t5) Rx(90) Rz(t6) = Rz(t4) Ry(-t5) Rz(-t6) Rx(180)`, a ZYZ decomposition.

use nalgebra::{IsometryMatrix3, Vector3};
use std::f64::consts::PI;

use super::error::IkError;
use super::limits::{JointId, JointLimit, wrap_angle};
use super::rv6sl::Rv6slGeometry;

/// Below this sine the wrist (or shoulder) is treated as singular and the free angle is kept at its
/// current value; the orientation error this leaves is below this value times pi.
const SINGULAR_EPS: f64 = 1e-10;

/// Records the least-violating limit failure seen so far.
struct FailureLog {
    best_violation: f64,
    failure: Option<IkError>,
}

impl FailureLog {
    fn limit(&mut self, limits: &[JointLimit; 6], joint: usize, raw: f64) {
        let value = wrap_angle(raw);
        let excess = limits[joint].violation(value);
        if excess < self.best_violation {
            self.best_violation = excess;
            self.failure = Some(IkError::JointLimit {
                joint: JointId::Arm(joint as u8 + 1),
                value_rad: value,
                lower_rad: limits[joint].lower_rad,
                upper_rad: limits[joint].upper_rad,
            });
        }
    }
}

/// Two candidates ordered by a cost, the cheaper first (the first on a tie).
fn cheaper_first<T>(a: T, b: T, cost: impl Fn(&T) -> f64) -> [T; 2] {
    if cost(&b) < cost(&a) { [b, a] } else { [a, b] }
}

/// A wrist branch: axis 4 angle, raw axis 5 angle, axis 6 angle, and axes 4 and 5 inside their limits.
type WristBranch = (f64, f64, f64, Option<f64>, Option<f64>);

/// Visits the limit-respecting branches for `base_from_flange` (shoulder front/back, elbow up/down,
/// wrist flip), the ones nearest `current_rad` first, and hands each to `visit`, which returns the cost
/// of the best solution it has so far (infinity while it has none). A branch whose axes 1-5 alone are
/// already at least that far from `current_rad` (squared joint distance) is skipped as soon as the
/// axes computed so far show it, so a caller whose cost is that distance plus anything non-negative
/// gets the same nearest solution as from all branches, usually after solving one wrist instead of
/// eight. Axis 6 is handed over as an angle in (-pi, pi]: callers pick its turn (and, for
/// instruments, split it with the roll). `current_rad` also resolves singular free angles.
///
/// Written for speed: sines and cosines come from ratios and angle sums rather than from `sin_cos` of
/// computed angles, and only the two needed columns of `R36` are formed.
///
/// `Err` when no branch was visited, with why (out of reach, or the least-violating limit) if known.
pub fn visit_branches(
    geometry: &Rv6slGeometry,
    limits: &[JointLimit; 6],
    base_from_flange: &IsometryMatrix3<f64>,
    current_rad: &[f64; 6],
    mut visit: impl FnMut(&[f64; 6]) -> f64,
) -> Result<(), Option<IkError>> {
    let mut log = FailureLog { best_violation: f64::INFINITY, failure: None };
    let mut reach: Option<IkError> = None;
    let mut bound = f64::INFINITY;
    let mut visited = false;
    let g = geometry;
    let f = base_from_flange.rotation.matrix();
    let wrist: Vector3<f64> = base_from_flange.translation.vector - g.d6_m * f.column(2);
    let sq = |q: f64, k: usize| (q - current_rad[k]) * (q - current_rad[k]);

    let l3 = g.forearm_m();
    let gamma = g.elbow_offset_rad();
    let (sg, cg) = (g.a3_m / l3, g.d4_m / l3);
    let (reach_min, reach_max) = g.reach_m();

    let radial = (wrist.x * wrist.x + wrist.y * wrist.y).sqrt();
    let (azimuth, s1a, c1a) = if radial < SINGULAR_EPS {
        let (s, c) = current_rad[0].sin_cos();
        (current_rad[0], s, c)
    } else {
        (wrist.y.atan2(wrist.x), wrist.y / radial, wrist.x / radial)
    };
    let shoulder =
        |(t1, s1, c1): (f64, f64, f64)| (t1, s1, c1, limits[0].nearest_equivalent(t1, current_rad[0]));
    let shoulders = cheaper_first(shoulder((azimuth, s1a, c1a)), shoulder((azimuth + PI, -s1a, -c1a)), |s| {
        s.3.map_or(f64::INFINITY, |q1| sq(q1, 0))
    });

    for (t1, s1, c1, q1) in shoulders {
        let Some(q1) = q1 else {
            log.limit(limits, 0, t1);
            continue;
        };
        let cost1 = sq(q1, 0);
        if cost1 >= bound {
            continue;
        }
        let r = wrist.x * c1 + wrist.y * s1 - g.a1_m;
        let s = wrist.z - g.d1_m;
        let dist = (r * r + s * s).sqrt();
        let cos_elbow = (dist * dist - g.a2_m * g.a2_m - l3 * l3) / (2.0 * g.a2_m * l3);
        if !(-1.0 - 1e-12..=1.0 + 1e-12).contains(&cos_elbow) || dist < SINGULAR_EPS {
            if reach.is_none() || t1 == azimuth {
                reach = Some(IkError::OutOfReach { distance_m: dist, min_m: reach_min, max_m: reach_max });
            }
            continue;
        }
        let cd = cos_elbow.clamp(-1.0, 1.0);
        let sin_elbow = (1.0 - cd * cd).max(0.0).sqrt();
        let elbow = sin_elbow.atan2(cd);
        // heading as a unit complex number (cos, sin); the law of cosines makes |k| = dist below.
        let (ch, sh) = (s / dist, r / dist);
        let elbow_branch = |sign: f64| {
            let q3_raw = gamma + sign * elbow;
            (sign, q3_raw, limits[2].nearest_equivalent(q3_raw, current_rad[2]))
        };
        let elbows = cheaper_first(elbow_branch(1.0), elbow_branch(-1.0), |e| {
            e.2.map_or(f64::INFINITY, |q3| sq(q3, 2))
        });
        for (sign, q3_raw, q3) in elbows {
            if q3.is_some_and(|q3| cost1 + sq(q3, 2) >= bound) {
                continue;
            }
            let sd = sign * sin_elbow;
            let (ky, kx) = (l3 * sd, g.a2_m + l3 * cd);
            // q2 = heading - angle(k), as a unit complex number, then one atan2.
            let (ck, sk) = (kx / dist, ky / dist);
            let (c_a, s_a) = (ch * ck + sh * sk, sh * ck - ch * sk);
            let q2_raw = s_a.atan2(c_a);
            let Some(q2) = limits[1].nearest_equivalent(q2_raw, current_rad[1]) else {
                log.limit(limits, 1, q2_raw);
                continue;
            };
            let Some(q3) = q3 else {
                log.limit(limits, 2, q3_raw);
                continue;
            };
            let cost123 = cost1 + sq(q2, 1) + sq(q3, 2);
            if cost123 >= bound {
                continue;
            }
            // q2 + q3 = (heading - angle(k)) + (gamma + delta), summed as unit complex numbers.
            let (c_b, s_b) = (cg * cd - sg * sd, sg * cd + cg * sd); // gamma + delta
            let (c_sum, s_sum) = (c_a * c_b - s_a * s_b, s_a * c_b + c_a * s_b);
            // t23 = q2 + q3 - pi
            let (s23, c23) = (-s_sum, -c_sum);
            // R03 = Rz(t1) Rx(-90) Rz(t23) Rx(-90), by columns.
            let r0 = Vector3::new(c1 * c23, s1 * c23, -s23);
            let r1 = Vector3::new(s1, -c1, 0.0);
            let r2 = Vector3::new(-c1 * s23, -s1 * s23, -c23);
            // M = R36 Rx(180): columns 0 and 2 of R36 = R03^T F, the second negated.
            let f0 = f.column(0);
            let f2 = f.column(2);
            let (m00, m10, m20) = (r0.dot(&f0), r1.dot(&f0), r2.dot(&f0));
            let (m02, m12, m22) = (-r0.dot(&f2), -r1.dot(&f2), -r2.dot(&f2));
            let sb = (m02 * m02 + m12 * m12).sqrt();
            let b = sb.atan2(m22);
            // Axis 4 from the approach direction; when axes 4 and 6 are (nearly) in line it is free
            // and stays where it is. Axis 6 then comes from what is left, `Ry(b)^T Rz(a)^T M`, so
            // any error in axis 4 is absorbed rather than doubled.
            let (a, sa, ca) = if sb < SINGULAR_EPS {
                let (sa, ca) = current_rad[3].sin_cos();
                (current_rad[3], sa, ca)
            } else {
                (m12.atan2(m02), m12 / sb, m02 / sb)
            };
            let n00 = m22 * (ca * m00 + sa * m10) - sb * m20;
            let n10 = -sa * m00 + ca * m10;
            let c = n10.atan2(n00);
            // The flipped wrist, Rz(a + pi) Ry(-b) Rz(c + pi), is the same rotation; at the
            // singularity only the unflipped one is taken.
            let wrist_branch = |(a, b, c): (f64, f64, f64)| -> WristBranch {
                let q5_raw = -b - PI;
                let q4 = limits[3].nearest_equivalent(a, current_rad[3]);
                let q5 = limits[4].nearest_equivalent(q5_raw, current_rad[4]);
                (a, q5_raw, c, q4, q5)
            };
            let unflipped = wrist_branch((a, b, c));
            let wrists: ([WristBranch; 2], usize) = if sb < SINGULAR_EPS {
                ([unflipped, unflipped], 1)
            } else {
                let cost45 = |w: &WristBranch| match (w.3, w.4) {
                    (Some(q4), Some(q5)) => sq(q4, 3) + sq(q5, 4),
                    _ => f64::INFINITY,
                };
                (cheaper_first(unflipped, wrist_branch((a + PI, -b, c + PI)), cost45), 2)
            };
            for &(a, q5_raw, c, q4, q5) in wrists.0.iter().take(wrists.1) {
                let Some(q4) = q4 else {
                    log.limit(limits, 3, a);
                    continue;
                };
                let Some(q5) = q5 else {
                    log.limit(limits, 4, q5_raw);
                    continue;
                };
                if cost123 + sq(q4, 3) + sq(q5, 4) >= bound {
                    continue;
                }
                bound = visit(&[q1, q2, q3, q4, q5, wrap_angle(-c)]);
                visited = true;
            }
        }
    }
    if visited { Ok(()) } else { Err(log.failure.or(reach)) }
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
    let mut best: Option<([f64; 6], f64)> = None;
    let searched = visit_branches(geometry, limits, base_from_flange, current_rad, |branch| {
        if let Some(q6) = limits[5].nearest_equivalent(branch[5], current_rad[5]) {
            let mut q = *branch;
            q[5] = q6;
            let cost = joint_distance_sq(&q, current_rad);
            if best.is_none_or(|(_, c)| cost < c) {
                best = Some((q, cost));
            }
        }
        best.map_or(f64::INFINITY, |(_, c)| c)
    });
    match (best, searched) {
        (Some((q, _)), _) => Ok(q),
        (None, Err(Some(failure))) => Err(failure),
        (None, _) => Err(IkError::NoBranch),
    }
}
