//! The rigid bodies of one arm that its collision boxes hang on ("anchors"), and their world poses for
//! given joints: the RV-6SL's DH frames from `hw`'s closed-form forward kinematics, then the
//! instrument's shaft, wrist and clevis frames.

use nalgebra::{IsometryMatrix3, Matrix3, Rotation3, Translation3};

use knotlab_hw::kinematics::rv6sl::DhRow;
use knotlab_hw::kinematics::{ArmJoints, ArmModel, Tool};

/// Number of anchors: base, links 1-6, shaft, wrist, clevis.
pub const ANCHORS: usize = 10;

/// A rigid body of an arm that collision boxes move with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Anchor {
    /// The base, fixed to the gantry.
    Base,
    /// The body turned by arm axis 1..=6 (its DH frame); link 6 carries the flange and the tool's
    /// housing (and the whole endoscope).
    Link(u8),
    /// The instrument shaft, after the roll.
    Shaft,
    /// The wrist link, after the pitch.
    Wrist,
    /// The clevis, after the yaw; the jaws hang on it at the arm's jaw opening.
    Clevis,
}

impl Anchor {
    /// Index into [`world_from_anchors`]' array: base 0, links 1-6, shaft 7, wrist 8, clevis 9.
    pub fn index(self) -> usize {
        match self {
            Anchor::Base => 0,
            Anchor::Link(i) => usize::from(i.clamp(1, 6)),
            Anchor::Shaft => 7,
            Anchor::Wrist => 8,
            Anchor::Clevis => 9,
        }
    }
}

/// World poses of all anchors of an arm at `joints`, indexed by [`Anchor::index`]. For the endoscope
/// the tool anchors repeat link 6.
pub fn world_from_anchors(model: &ArmModel, joints: &ArmJoints) -> [IsometryMatrix3<f64>; ANCHORS] {
    let mut out = [model.world_from_base; ANCHORS];
    let frames = model.geometry.base_from_frames(&joints.arm_rad);
    for (k, frame) in frames.iter().enumerate() {
        out[k + 1] = model.world_from_base * frame;
    }
    tool_anchors(model, joints, &mut out);
    out
}

/// One arm's forward kinematics to its anchors for many joint vectors: the DH rows' fixed parts
/// (`Rz(offset) Tz(d) Tx(a) Rx(alpha)`, from `hw`'s [`DhRow::fixed_part`]) computed once, so each call
/// needs one `sin_cos` per joint. Gives [`world_from_anchors`]' poses (tests hold them within 1e-12).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnchorKinematics {
    model: ArmModel,
    fixed: [IsometryMatrix3<f64>; 6],
}

impl AnchorKinematics {
    /// Precomputes an arm's fixed parts.
    pub fn new(model: &ArmModel) -> Self {
        Self { model: *model, fixed: model.geometry.rows().map(|row: DhRow| row.fixed_part()) }
    }

    /// World poses of all anchors at `joints`, indexed by [`Anchor::index`].
    pub fn world_from_anchors(&self, joints: &ArmJoints) -> [IsometryMatrix3<f64>; ANCHORS] {
        self.world_from_anchors_sin_cos(joints, &chain_angles(joints).map(f64::sin_cos))
    }

    /// [`AnchorKinematics::world_from_anchors`] with the chain joints' sines and cosines taken from
    /// `near`'s (see [`SinCosNear`]): no `sin_cos` call for joints close to `near`'s.
    pub fn world_from_anchors_near(
        &self,
        joints: &ArmJoints,
        near: &SinCosNear,
    ) -> [IsometryMatrix3<f64>; ANCHORS] {
        self.world_from_anchors_sin_cos(joints, &near.at(&chain_angles(joints)))
    }

    /// The poses from the chain joints' `(sin, cos)` (arm axes 1-6, roll, pitch, yaw).
    fn world_from_anchors_sin_cos(
        &self,
        joints: &ArmJoints,
        sin_cos: &[(f64, f64); CHAIN_JOINTS],
    ) -> [IsometryMatrix3<f64>; ANCHORS] {
        let model = &self.model;
        let mut out = [model.world_from_base; ANCHORS];
        let mut acc = model.world_from_base;
        for (k, (fixed, &(s, c))) in self.fixed.iter().zip(sin_cos).enumerate() {
            // acc Rz(q): only the first two rotation columns mix.
            let r = acc.rotation.matrix();
            let (c0, c1) = (r.column(0), r.column(1));
            let turned = Matrix3::from_columns(&[c0 * c + c1 * s, c1 * c - c0 * s, r.column(2).into_owned()]);
            acc = IsometryMatrix3::from_parts(
                Translation3::from(turned * fixed.translation.vector + acc.translation.vector),
                Rotation3::from_matrix_unchecked(turned * fixed.rotation.matrix()),
            );
            out[k + 1] = acc;
        }
        if let Tool::Instrument { geometry, .. } = &model.tool {
            out[7] = out[6] * turn_after_sin_cos(geometry.coupling_m, 2, sin_cos[6]);
            out[8] = out[7] * turn_after_sin_cos(geometry.shaft_m, 0, sin_cos[7]);
            out[9] = out[8] * turn_after_sin_cos(geometry.wrist_m, 1, sin_cos[8]);
        } else {
            tool_anchors(model, joints, &mut out);
        }
        out
    }
}

/// Joints of the chain to the anchors: arm axes 1-6, then the instrument's roll, pitch and yaw. Anchor
/// `a` moves with chain joints `0..a`.
pub const CHAIN_JOINTS: usize = 9;

/// The chain joints' angles, rad.
pub fn chain_angles(j: &ArmJoints) -> [f64; CHAIN_JOINTS] {
    let a = &j.arm_rad;
    [a[0], a[1], a[2], a[3], a[4], a[5], j.tool.roll_rad, j.tool.pitch_rad, j.tool.yaw_rad]
}

/// Sines and cosines of angles near known ones, from the angle sum: `sin(q0 + d) = sin q0 cos d + cos
/// q0 sin d` with `sin d` and `cos d` from their Taylor series, exact to round-off (the first term
/// left out is below 3e-20 for `|d| <= 0.1`); farther angles get a `sin_cos` call. Neighbouring
/// subcells of a cell pose the arm nearly alike, so this spares most of forward kinematics' calls.
#[derive(Clone, Copy, Debug)]
pub struct SinCosNear {
    angles: [f64; CHAIN_JOINTS],
    sin_cos: [(f64, f64); CHAIN_JOINTS],
}

/// Largest angle difference the series is used for, rad.
const SERIES_REACH_RAD: f64 = 0.1;

impl SinCosNear {
    /// Around the chain angles of `joints`.
    pub fn new(joints: &ArmJoints) -> Self {
        let angles = chain_angles(joints);
        Self { angles, sin_cos: angles.map(f64::sin_cos) }
    }

    /// `(sin, cos)` of each of `angles`.
    pub fn at(&self, angles: &[f64; CHAIN_JOINTS]) -> [(f64, f64); CHAIN_JOINTS] {
        std::array::from_fn(|j| {
            let d = angles[j] - self.angles[j];
            if d.abs() > SERIES_REACH_RAD {
                return angles[j].sin_cos();
            }
            let d2 = d * d;
            // sin d = d (1 - d^2/6 (1 - d^2/20 (1 - d^2/42 (1 - d^2/72)))), cos d likewise.
            let sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0))));
            let cd = 1.0
                - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0 * (1.0 - d2 / 56.0 * (1.0 - d2 / 90.0))));
            let (s0, c0) = self.sin_cos[j];
            (s0 * cd + c0 * sd, c0 * cd - s0 * sd)
        })
    }
}

/// Anchors 7-9 from the flange (anchor 6).
fn tool_anchors(model: &ArmModel, joints: &ArmJoints, out: &mut [IsometryMatrix3<f64>; ANCHORS]) {
    let flange = out[6];
    match &model.tool {
        Tool::Instrument { geometry, .. } => {
            let tool = &joints.tool;
            out[7] = flange * turn_after(geometry.coupling_m, 2, tool.roll_rad);
            out[8] = out[7] * turn_after(geometry.shaft_m, 0, tool.pitch_rad);
            out[9] = out[8] * turn_after(geometry.wrist_m, 1, tool.yaw_rad);
        }
        Tool::Endoscope { .. } => {
            out[7] = flange;
            out[8] = flange;
            out[9] = flange;
        }
    }
}

/// `Tz(z_m) R(axis, q_rad)`, the axis 0 (x), 1 (y) or 2 (z): one step of the instrument's chain
/// (`InstrumentGeometry::flange_from_tip`), built from one `sin_cos`.
fn turn_after(z_m: f64, axis: usize, q_rad: f64) -> IsometryMatrix3<f64> {
    turn_after_sin_cos(z_m, axis, q_rad.sin_cos())
}

/// [`turn_after`] from the angle's sine and cosine.
fn turn_after_sin_cos(z_m: f64, axis: usize, (s, c): (f64, f64)) -> IsometryMatrix3<f64> {
    let m = match axis {
        0 => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    };
    IsometryMatrix3::from_parts(Translation3::new(0.0, 0.0, z_m), Rotation3::from_matrix_unchecked(m))
}

#[cfg(test)]
mod tests {
    use super::*;
    use knotlab_hw::rig::{ArmName, Rig};

    /// Sines and cosines stepped from known ones match `sin_cos` within 4e-16 for changes up to 0.5 rad,
    /// and the anchor poses built from them match the directly computed ones within 1e-14.
    #[test]
    fn sines_near_known_ones_match_sin_cos_and_so_do_the_poses() {
        let rig = Rig::shipped().expect("the shipped rig");
        let kinematics = AnchorKinematics::new(&rig.arm(ArmName::Left).model);
        let tool =
            knotlab_hw::kinematics::ToolJoints { roll_rad: -0.7, pitch_rad: 0.4, yaw_rad: 0.1, jaw_rad: 0.0 };
        let joints = ArmJoints { arm_rad: [0.3, -0.4, 1.9, 0.2, -1.1, 2.5], tool };
        let near = SinCosNear::new(&joints);
        // Differences up to the series' reach, and one beyond it (a sin_cos call).
        for d in [0.0, 1e-9, -3e-4, 0.02, -0.0999, 0.1, 0.5] {
            let mut other = joints;
            for q in other.arm_rad.iter_mut() {
                *q += d;
            }
            other.tool.pitch_rad -= d;
            let angles = chain_angles(&other);
            for ((s, c), q) in near.at(&angles).iter().zip(angles) {
                let (s_ref, c_ref) = q.sin_cos();
                assert!(
                    (s - s_ref).abs() < 4e-16 && (c - c_ref).abs() < 4e-16,
                    "d {d}: {s} {c} vs {s_ref} {c_ref}"
                );
            }
            let (a, b) =
                (kinematics.world_from_anchors_near(&other, &near), kinematics.world_from_anchors(&other));
            for (x, y) in a.iter().zip(&b) {
                assert!((x.to_homogeneous() - y.to_homogeneous()).abs().max() < 1e-14, "d {d}");
            }
        }
    }
}
