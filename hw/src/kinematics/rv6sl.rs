//! The Mitsubishi RV-6SL in standard Denavit-Hartenberg form, and its closed-form forward kinematics.
//!
//! Joint i turns `Rz(q_i + offset_i) Tz(d_i) Tx(a_i) Rx(alpha_i)` (figures in shared/reference/rig.md).
//! Zero conventions, ours once and for all: at q = 0 the upper arm and the forearm are in line along the
//! base z axis (the "candle"), the 0.1 m elbow offset points back along -x, and the wrist is folded
//! flat (q5 = 0 is the wrist singularity, axes 4 and 6 in line). Positive q2 leans the upper arm towards
//! the base x axis.

use nalgebra::{IsometryMatrix3, Matrix3, Rotation3, Translation3, Vector3};
use std::f64::consts::FRAC_PI_2;

use super::limits::JointLimit;

/// One row of a standard DH table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DhRow {
    /// Offset along the previous z, m.
    pub d_m: f64,
    /// Added to the joint angle, rad.
    pub theta_offset_rad: f64,
    /// Length along the new x, m.
    pub a_m: f64,
    /// Twist about the new x, rad.
    pub alpha_rad: f64,
}

impl DhRow {
    /// `Rz(q + offset) Tz(d) Tx(a) Rx(alpha)`.
    pub fn transform(&self, q_rad: f64) -> IsometryMatrix3<f64> {
        let (st, ct) = (q_rad + self.theta_offset_rad).sin_cos();
        let (sa, ca) = self.alpha_rad.sin_cos();
        let r = Matrix3::new(ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca);
        let p = Vector3::new(self.a_m * ct, self.a_m * st, self.d_m);
        IsometryMatrix3::from_parts(Translation3::from(p), Rotation3::from_matrix_unchecked(r))
    }

    /// The part that does not move: `Rz(offset) Tz(d) Tx(a) Rx(alpha)`, i.e. [`DhRow::transform`] at 0.
    pub fn fixed_part(&self) -> IsometryMatrix3<f64> {
        self.transform(0.0)
    }
}

/// The RV-6SL's link lengths. The structure (which lengths are zero, the twists and the offsets) is
/// fixed: the closed-form inverse kinematics depends on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rv6slGeometry {
    /// Base to shoulder height, m.
    pub d1_m: f64,
    /// Shoulder offset from axis 1, m.
    pub a1_m: f64,
    /// Upper arm, m.
    pub a2_m: f64,
    /// Elbow offset, m.
    pub a3_m: f64,
    /// Forearm (elbow to wrist centre along axis 4), m.
    pub d4_m: f64,
    /// Wrist centre to flange, m.
    pub d6_m: f64,
}

/// `atan2(0.100, 0.425)`, the RV-6SL's [`Rv6slGeometry::elbow_offset_rad`] (a test checks it bit for bit).
const RV6SL_ELBOW_OFFSET_RAD: f64 = 0.2310906671958971;

/// Degrees to radians, usable in constants.
const fn deg(x: f64) -> f64 {
    x * (std::f64::consts::PI / 180.0)
}

impl Rv6slGeometry {
    /// The RV-6SL of shared/reference/rig.md.
    pub const RV6SL: Self =
        Self { d1_m: 0.350, a1_m: 0.085, a2_m: 0.380, a3_m: 0.100, d4_m: 0.425, d6_m: 0.085 };

    /// Its joint limits: positions from the data sheet table, speeds from the maximum speeds.
    pub const RV6SL_LIMITS: [JointLimit; 6] = [
        JointLimit::new(deg(-170.0), deg(170.0), deg(250.0)),
        JointLimit::new(deg(-92.0), deg(135.0), deg(267.0)),
        JointLimit::new(deg(-129.0), deg(166.0), deg(267.0)),
        JointLimit::new(deg(-160.0), deg(160.0), deg(352.0)),
        JointLimit::new(deg(-120.0), deg(120.0), deg(450.0)),
        JointLimit::new(deg(-360.0), deg(360.0), deg(660.0)),
    ];

    /// The six DH rows.
    pub fn rows(&self) -> [DhRow; 6] {
        let row = |d_m, theta_offset_rad, a_m, alpha_rad| DhRow { d_m, theta_offset_rad, a_m, alpha_rad };
        [
            row(self.d1_m, 0.0, self.a1_m, -FRAC_PI_2),
            row(0.0, -FRAC_PI_2, self.a2_m, 0.0),
            row(0.0, -FRAC_PI_2, self.a3_m, -FRAC_PI_2),
            row(self.d4_m, 0.0, 0.0, FRAC_PI_2),
            row(0.0, std::f64::consts::PI, 0.0, FRAC_PI_2),
            row(self.d6_m, 0.0, 0.0, 0.0),
        ]
    }

    /// The angle at the elbow between the upper arm's line and the elbow-to-wrist-centre line at q3 = 0,
    /// `atan2(a3, d4)`, rad. The RV-6SL's value is a constant (the inverse kinematics needs it at every
    /// solve, and `atan2` is a library call); any other geometry computes it.
    #[inline]
    pub fn elbow_offset_rad(&self) -> f64 {
        if *self == Self::RV6SL { RV6SL_ELBOW_OFFSET_RAD } else { self.a3_m.atan2(self.d4_m) }
    }

    /// Elbow-to-wrist-centre distance, m.
    pub fn forearm_m(&self) -> f64 {
        (self.a3_m * self.a3_m + self.d4_m * self.d4_m).sqrt()
    }

    /// Shortest and longest shoulder-to-wrist-centre distances, m.
    pub fn reach_m(&self) -> (f64, f64) {
        let l3 = self.forearm_m();
        ((self.a2_m - l3).abs(), self.a2_m + l3)
    }

    /// The DH frames 1..=6 in the base frame; the last is the flange.
    pub fn base_from_frames(&self, q_rad: &[f64; 6]) -> [IsometryMatrix3<f64>; 6] {
        let rows = self.rows();
        let mut frames = [IsometryMatrix3::identity(); 6];
        let mut acc = IsometryMatrix3::identity();
        for (i, (row, q)) in rows.iter().zip(q_rad).enumerate() {
            acc *= row.transform(*q);
            frames[i] = acc;
        }
        frames
    }

    /// The flange in the base frame.
    pub fn base_from_flange(&self, q_rad: &[f64; 6]) -> IsometryMatrix3<f64> {
        self.base_from_frames(q_rad)[5]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The RV-6SL's precomputed elbow offset is bit for bit the atan2 it stands for, and other geometries
    /// compute theirs.
    #[test]
    fn rv6sl_elbow_offset_constant_is_atan2_bit_for_bit() {
        let g = Rv6slGeometry::RV6SL;
        assert_eq!(g.elbow_offset_rad().to_bits(), g.a3_m.atan2(g.d4_m).to_bits());
        let other = Rv6slGeometry { a3_m: 0.12, ..g };
        assert_eq!(other.elbow_offset_rad(), 0.12f64.atan2(g.d4_m));
    }
}
