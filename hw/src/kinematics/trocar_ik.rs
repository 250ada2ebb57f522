//! Inverse kinematics for a tool tip target with the shaft passing through a trocar point: geometric
//! decoupling to a flange pose, then the arm's closed-form branches, nearest to the current joints.
//!
//! Instrument, for a tip position `p`, jaw direction `j` and yaw axis `y` (the tip frame's z and y):
//! 1. The yaw axis point is `p - jaw_m j`.
//! 2. The wrist link `w` is perpendicular to the yaw axis, and the pitch axis (`y x w`) must be
//!    perpendicular to the shaft, which passes through the trocar `c`. Both hold exactly when `w` is the
//!    part of `(yaw point - c)` perpendicular to `y`, normalised: the pitch axis point follows, and the
//!    shaft is the line from `c` through it.
//! 3. Pitch and yaw are read off the frames; the flange lies on the shaft, `coupling_m + shaft_m` behind
//!    the pitch axis, with its z along the shaft.
//! 4. Arm axis 6 and the instrument roll turn about the same line, so only their sum is fixed: the split
//!    nearest the current joints that keeps both in their limits is chosen in closed form.
//!
//! With only a jaw direction, the yaw axis is taken perpendicular to both the jaw and the trocar-to-tip
//! line (all the bend in yaw, pitch at zero), trying both signs; when the jaw points along that line
//! (a straight wrist) the yaw axis keeps the current one. Everything is allocation-free.

use nalgebra::{IsometryMatrix3, Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::{PI, TAU};

use super::arm_ik::{joint_distance_sq, visit_branches};
use super::error::IkError;
use super::joints::{ArmJoints, ToolJoints};
use super::limits::{JointId, JointLimit, wrap_angle};
use super::model::ArmModel;
use super::tool::{EndoscopeGeometry, InstrumentGeometry, InstrumentLimits, MIN_TROCAR_DISTANCE_M, Tool};

/// How the tip should be oriented.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TipOrientation {
    /// Jaws along the line from the trocar to the tip (a straight wrist); the only choice for the
    /// endoscope, which looks along its shaft.
    AlongShaft,
    /// Jaws pointing this way (need not be unit length); the rotation about it is chosen by the solver.
    JawDirection(Vector3<f64>),
    /// The full tip frame: z the jaw direction, y the wrist yaw axis.
    Frame(Rotation3<f64>),
}

/// A tip target in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TipTarget {
    /// Tip position, world frame, m.
    pub world_position_m: Vector3<f64>,
    /// Tip orientation.
    pub orientation: TipOrientation,
}

/// Sines below this count as a straight wrist when choosing the yaw axis for a jaw direction.
const STRAIGHT_WRIST_SIN: f64 = 1e-9;

fn is_finite(v: &Vector3<f64>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// A unit vector perpendicular to unit `v`.
fn any_perpendicular(v: &Vector3<f64>) -> Vector3<f64> {
    let helper = if v.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    v.cross(&helper).normalize()
}

fn limit_error(joint: JointId, value_rad: f64, limit: &JointLimit) -> IkError {
    IkError::JointLimit { joint, value_rad, lower_rad: limit.lower_rad, upper_rad: limit.upper_rad }
}

/// Splits the rotation about the shaft, `q6 + roll = total (mod 2 pi)`, between arm axis 6 and the
/// instrument roll: the pair inside both limits nearest to the current pair, and its squared distance.
pub fn split_shaft_rotation(
    total_rad: f64,
    q6_limit: &JointLimit,
    roll_limit: &JointLimit,
    q6_now: f64,
    roll_now: f64,
) -> Option<(f64, f64, f64)> {
    // Move both joints by (t, e - t) from where they are; e, the change of the sum, is `base` plus
    // whole turns. Unconstrained, the best t is e / 2 at cost e^2 / 2, so the turn giving the smallest
    // |e| wins outright when its optimum is feasible: every other turn costs at least pi^2 / 2 more.
    let base = wrap_angle(total_rad - q6_now - roll_now);
    let candidate = |e: f64| {
        let t_lo = (q6_limit.lower_rad - q6_now).max(e - (roll_limit.upper_rad - roll_now));
        let t_hi = (q6_limit.upper_rad - q6_now).min(e - (roll_limit.lower_rad - roll_now));
        (t_lo <= t_hi).then(|| {
            let t = (0.5 * e).clamp(t_lo, t_hi);
            (q6_now + t, roll_now + (e - t), t * t + (e - t) * (e - t))
        })
    };
    if let Some(best) = candidate(base)
        && (best.2 - 0.5 * base * base).abs() <= 1e-12
    {
        return Some(best);
    }
    let mut best: Option<(f64, f64, f64)> = None;
    for k in -3..=3 {
        if let Some(c) = candidate(base + TAU * f64::from(k))
            && best.is_none_or(|(_, _, b)| c.2 < b)
        {
            best = Some(c);
        }
    }
    best
}

impl ArmModel {
    /// Joints that put the tool tip on `target` with the shaft through `world_trocar_m`, the solution
    /// nearest to `current` among the arm's branches. The jaw opening is kept from `current`.
    pub fn solve_tip(
        &self,
        target: &TipTarget,
        world_trocar_m: &Vector3<f64>,
        current: &ArmJoints,
    ) -> Result<ArmJoints, IkError> {
        let p = target.world_position_m;
        let c = *world_trocar_m;
        if !is_finite(&p) || !is_finite(&c) {
            return Err(IkError::NonFiniteTarget);
        }
        let to_tip = p - c;
        let distance_m = to_tip.norm();
        if distance_m < MIN_TROCAR_DISTANCE_M {
            return Err(IkError::TooCloseToTrocar { what: "tip", distance_m, min_m: MIN_TROCAR_DISTANCE_M });
        }
        let (geometry, limits) = match &self.tool {
            Tool::Endoscope { geometry } => {
                return match target.orientation {
                    TipOrientation::AlongShaft => self.solve_endoscope(geometry, &p, &c, current),
                    _ => Err(IkError::OrientationNotControllable),
                };
            }
            Tool::Instrument { geometry, limits } => (geometry, limits),
        };
        let solve = |jaw: &Vector3<f64>, yaw_axis: &Vector3<f64>, either_sign: bool| {
            self.solve_instrument(geometry, limits, &p, jaw, yaw_axis, either_sign, &c, current)
        };
        match target.orientation {
            TipOrientation::Frame(rotation) => {
                let m = rotation.matrix();
                if !m.iter().all(|x| x.is_finite()) {
                    return Err(IkError::NonFiniteTarget);
                }
                solve(&m.column(2).into_owned(), &m.column(1).into_owned(), false)
            }
            TipOrientation::AlongShaft => {
                let jaw = to_tip / distance_m;
                solve(&jaw, &self.current_yaw_axis(&jaw, current), false)
            }
            TipOrientation::JawDirection(direction) => {
                if !is_finite(&direction) {
                    return Err(IkError::NonFiniteTarget);
                }
                let norm = direction.norm();
                if norm < 1e-12 {
                    return Err(IkError::ZeroJawDirection);
                }
                let jaw = direction / norm;
                let normal = jaw.cross(&to_tip);
                let n = normal.norm();
                if n <= STRAIGHT_WRIST_SIN * distance_m {
                    return solve(&jaw, &self.current_yaw_axis(&jaw, current), false);
                }
                solve(&jaw, &(normal / n), true)
            }
        }
    }

    /// The current tip's yaw axis made perpendicular to `jaw` (any perpendicular if it is parallel).
    fn current_yaw_axis(&self, jaw: &Vector3<f64>, current: &ArmJoints) -> Vector3<f64> {
        let y_now = self.world_from_tip(current).rotation * Vector3::y();
        let perp = y_now - jaw * jaw.dot(&y_now);
        let n = perp.norm();
        if n > 1e-6 { perp / n } else { any_perpendicular(jaw) }
    }

    /// Decoupling and arm branches for a jaw frame (jaw direction and yaw axis), the solution nearest
    /// to `current`. With `either_sign` the opposite yaw axis is allowed too: it is the same shaft and
    /// arm branch with pitch and yaw negated and the roll turned by pi, so it costs no second solve.
    #[allow(clippy::too_many_arguments)]
    fn solve_instrument(
        &self,
        geometry: &InstrumentGeometry,
        limits: &InstrumentLimits,
        tip: &Vector3<f64>,
        jaw: &Vector3<f64>,
        yaw_axis: &Vector3<f64>,
        either_sign: bool,
        trocar: &Vector3<f64>,
        current: &ArmJoints,
    ) -> Result<ArmJoints, IkError> {
        let yaw_point = tip - geometry.jaw_m * jaw;
        let d = yaw_point - trocar;
        let d_perp = d - yaw_axis * yaw_axis.dot(&d);
        let n = d_perp.norm();
        if n < 1e-9 {
            return Err(IkError::WristAxisThroughTrocar);
        }
        let wrist = d_perp / n;
        let pitch_point = yaw_point - geometry.wrist_m * wrist;
        let e = pitch_point - trocar;
        let depth_m = e.norm();
        if depth_m < MIN_TROCAR_DISTANCE_M {
            return Err(IkError::TooCloseToTrocar {
                what: "wrist pitch axis",
                distance_m: depth_m,
                min_m: MIN_TROCAR_DISTANCE_M,
            });
        }
        if depth_m > geometry.max_insertion_m {
            return Err(IkError::InsertionTooDeep { depth_m, max_m: geometry.max_insertion_m });
        }
        let shaft = e / depth_m;
        let x_roll = yaw_axis.cross(&wrist);
        let y_roll = shaft.cross(&x_roll);
        let pitch = (-wrist.dot(&y_roll)).atan2(wrist.dot(&shaft));
        let yaw = jaw.dot(&x_roll).atan2(jaw.dot(&wrist));
        // (pitch, yaw, extra turn about the shaft) for the asked yaw axis and, maybe, its opposite.
        let wrists = [(pitch, yaw, 0.0), (-pitch, -yaw, PI)];
        let wrist_ok = |(p, y, _): &(f64, f64, f64)| limits.pitch.contains(*p) && limits.yaw.contains(*y);
        let n_wrists = if either_sign { 2 } else { 1 };
        if !wrists[..n_wrists].iter().any(wrist_ok) {
            return Err(if limits.pitch.contains(pitch) {
                limit_error(JointId::WristYaw, yaw, &limits.yaw)
            } else {
                limit_error(JointId::WristPitch, pitch, &limits.pitch)
            });
        }
        // The flange as it would be with zero roll.
        let flange_m = pitch_point - (geometry.coupling_m + geometry.shaft_m) * shaft;
        let world_from_flange = IsometryMatrix3::from_parts(
            Translation3::from(flange_m),
            Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x_roll, y_roll, shaft])),
        );
        let base_from_flange = self.base_from_world * world_from_flange;
        let now = current.tool;
        let mut best: Option<(ArmJoints, f64)> = None;
        let searched =
            visit_branches(&self.geometry, &self.limits, &base_from_flange, &current.arm_rad, |branch| {
                let mut arm = *branch;
                arm[5] = current.arm_rad[5];
                let arm_cost = joint_distance_sq(&arm, &current.arm_rad);
                for (pitch, yaw, turn) in wrists[..n_wrists].iter().filter(|w| wrist_ok(w)) {
                    let Some((q6, roll, split_cost)) = split_shaft_rotation(
                        branch[5] + turn,
                        &self.limits[5],
                        &limits.roll,
                        current.arm_rad[5],
                        now.roll_rad,
                    ) else {
                        continue;
                    };
                    let cost =
                        arm_cost + split_cost + (pitch - now.pitch_rad).powi(2) + (yaw - now.yaw_rad).powi(2);
                    if best.as_ref().is_none_or(|(_, c)| cost < *c) {
                        arm[5] = q6;
                        let tool = ToolJoints {
                            roll_rad: roll,
                            pitch_rad: *pitch,
                            yaw_rad: *yaw,
                            jaw_rad: now.jaw_rad,
                        };
                        best = Some((ArmJoints { arm_rad: arm, tool }, cost));
                    }
                }
                best.as_ref().map_or(f64::INFINITY, |(_, c)| *c)
            });
        match (best, searched) {
            (Some((joints, _)), _) => Ok(joints),
            (None, Err(Some(failure))) => Err(failure),
            (None, _) => Err(limit_error(JointId::Roll, now.roll_rad, &limits.roll)),
        }
    }

    /// The endoscope: the shaft from the trocar to the tip fixes everything but the turn about the
    /// shaft, which stays where axis 6 is.
    fn solve_endoscope(
        &self,
        geometry: &EndoscopeGeometry,
        tip: &Vector3<f64>,
        trocar: &Vector3<f64>,
        current: &ArmJoints,
    ) -> Result<ArmJoints, IkError> {
        let e = tip - trocar;
        let depth_m = e.norm();
        if depth_m > geometry.max_insertion_m {
            return Err(IkError::InsertionTooDeep { depth_m, max_m: geometry.max_insertion_m });
        }
        let shaft = e / depth_m;
        let x = any_perpendicular(&shaft);
        let flange_m = tip - (geometry.coupling_m + geometry.shaft_m) * shaft;
        let world_from_flange = IsometryMatrix3::from_parts(
            Translation3::from(flange_m),
            Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[x, shaft.cross(&x), shaft])),
        );
        let base_from_flange = self.base_from_world * world_from_flange;
        let q6 = current.arm_rad[5].clamp(self.limits[5].lower_rad, self.limits[5].upper_rad);
        let mut best: Option<([f64; 6], f64)> = None;
        let searched =
            visit_branches(&self.geometry, &self.limits, &base_from_flange, &current.arm_rad, |branch| {
                let mut arm = *branch;
                arm[5] = q6;
                let cost = joint_distance_sq(&arm, &current.arm_rad);
                if best.is_none_or(|(_, c)| cost < c) {
                    best = Some((arm, cost));
                }
                best.map_or(f64::INFINITY, |(_, c)| c)
            });
        match (best, searched) {
            (Some((arm_rad, _)), _) => Ok(ArmJoints { arm_rad, tool: ToolJoints::default() }),
            (None, Err(Some(failure))) => Err(failure),
            (None, _) => Err(IkError::NoBranch),
        }
    }
}
