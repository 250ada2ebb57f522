//! Joint identifiers and joint limits, shared by the kinematics and the rig loader.

use std::f64::consts::TAU;
use std::fmt;

/// Slack allowed when testing a computed angle against a limit; values within it are clamped onto the
/// limit. Far below any tolerance the kinematics promises (1e-6), far above round-off (1e-15).
pub const LIMIT_SLACK_RAD: f64 = 1e-12;

/// 1 / (2 pi): turn counts by a multiplication (a division is several times slower; the count is
/// rounded, so the last bit of the quotient only matters exactly half way between two turns).
const INV_TAU: f64 = 1.0 / TAU;

/// Names one joint of an arm and its tool.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointId {
    /// Arm axis 1..=6 of the RV-6SL.
    Arm(u8),
    /// Instrument roll about the shaft.
    Roll,
    /// Instrument wrist pitch.
    WristPitch,
    /// Instrument wrist yaw.
    WristYaw,
    /// Instrument jaw opening (both jaws together).
    Jaw,
}

impl fmt::Display for JointId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JointId::Arm(i) => write!(f, "joint{i}"),
            JointId::Roll => f.write_str("roll"),
            JointId::WristPitch => f.write_str("wrist_pitch"),
            JointId::WristYaw => f.write_str("wrist_yaw"),
            JointId::Jaw => f.write_str("jaw"),
        }
    }
}

/// Position and velocity limits of one joint, radians and radians per second.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JointLimit {
    /// Lowest position, rad.
    pub lower_rad: f64,
    /// Highest position, rad.
    pub upper_rad: f64,
    /// Largest speed, rad/s.
    pub max_velocity_rad_s: f64,
}

impl JointLimit {
    /// A limit from bounds and a speed.
    pub const fn new(lower_rad: f64, upper_rad: f64, max_velocity_rad_s: f64) -> Self {
        Self { lower_rad, upper_rad, max_velocity_rad_s }
    }

    /// Whether `q_rad` lies inside the limit (with [`LIMIT_SLACK_RAD`]).
    pub fn contains(&self, q_rad: f64) -> bool {
        q_rad >= self.lower_rad - LIMIT_SLACK_RAD && q_rad <= self.upper_rad + LIMIT_SLACK_RAD
    }

    /// How far `q_rad` lies outside the limit; zero inside.
    pub fn violation(&self, q_rad: f64) -> f64 {
        (self.lower_rad - q_rad).max(q_rad - self.upper_rad).max(0.0)
    }

    /// Among the angles `q_rad + 2 pi k`, the one inside the limit nearest to `near_rad`, if any.
    /// (Limits up to two turns wide, as on this rig: candidates further out are not looked at.)
    #[inline]
    pub fn nearest_equivalent(&self, q_rad: f64, near_rad: f64) -> Option<f64> {
        // The equivalent nearest `near` is the answer whenever it is inside the limit.
        let base = q_rad + TAU * round_small((near_rad - q_rad) * INV_TAU);
        if self.contains(base) {
            return Some(base.clamp(self.lower_rad, self.upper_rad));
        }
        let (up, down) = (base + TAU, base - TAU);
        let pick = match (self.contains(up), self.contains(down)) {
            (true, true) => Some(if (up - near_rad).abs() <= (down - near_rad).abs() { up } else { down }),
            (true, false) => Some(up),
            (false, true) => Some(down),
            (false, false) => None,
        };
        pick.map(|q| q.clamp(self.lower_rad, self.upper_rad))
    }
}

/// Rounds to the nearest integer, for the small values (turn counts) of the kinematics: a cast the
/// compiler inlines, where `f64::round` is a library call on baseline x86-64. Exact for |x| < 2^52.
#[inline]
pub fn round_small(x: f64) -> f64 {
    (x + 0.5_f64.copysign(x)) as i64 as f64
}

/// Wraps an angle into (-pi, pi].
#[inline]
pub fn wrap_angle(q_rad: f64) -> f64 {
    let w = q_rad - TAU * round_small(q_rad * INV_TAU);
    if w <= -std::f64::consts::PI { w + TAU } else { w }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The whole-turn equivalent nearest the reference is picked, but never one outside the limit.
    #[test]
    fn nearest_equivalent_prefers_the_turn_near_the_reference() {
        let wide = JointLimit::new(-2.0 * PI, 2.0 * PI, 1.0);
        let q = wide.nearest_equivalent(-0.1, 6.0).unwrap();
        assert!((q - (TAU - 0.1)).abs() < 1e-12, "{q}");
        // 0.1 + 2 pi would be nearer 6.3 but lies outside the limit.
        let q = wide.nearest_equivalent(0.1, 6.3).unwrap();
        assert!((q - 0.1).abs() < 1e-12, "{q}");
        let q = wide.nearest_equivalent(0.1, -0.2).unwrap();
        assert!((q - 0.1).abs() < 1e-12, "{q}");
    }

    /// An angle with no equivalent inside a narrow limit gets none, and one past a bound by less than the
    /// slack is clamped onto it.
    #[test]
    fn nearest_equivalent_rejects_angles_outside_a_narrow_limit() {
        let narrow = JointLimit::new(-1.0, 1.0, 1.0);
        assert_eq!(narrow.nearest_equivalent(2.0, 0.0), None);
        assert_eq!(narrow.nearest_equivalent(-1.0 - 1e-13, 0.0), Some(-1.0));
    }

    /// The inlined rounding agrees with `f64::round` at halves, near halves, zero and large values.
    #[test]
    fn round_small_matches_round() {
        for x in [-2.5, -1.5, -0.6, -0.4, 0.0, 0.4, 0.5, 0.6, 1.49, 2.5, 1e9 + 0.3] {
            assert_eq!(round_small(x), f64::round(x), "{x}");
        }
    }

    /// Angles wrap into (-pi, pi]: -pi lands on pi, and several turns on the equivalent angle.
    #[test]
    fn wrap_angle_lands_in_half_open_interval() {
        assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(0.5 + 4.0 * PI) - 0.5).abs() < 1e-12);
    }
}
