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
        let model = &self.model;
        let mut out = [model.world_from_base; ANCHORS];
        let mut acc = model.world_from_base;
        for (k, (fixed, q)) in self.fixed.iter().zip(&joints.arm_rad).enumerate() {
            // acc Rz(q): only the first two rotation columns mix.
            let (s, c) = q.sin_cos();
            let r = acc.rotation.matrix();
            let (c0, c1) = (r.column(0), r.column(1));
            let turned = Matrix3::from_columns(&[c0 * c + c1 * s, c1 * c - c0 * s, r.column(2).into_owned()]);
            acc = IsometryMatrix3::from_parts(
                Translation3::from(turned * fixed.translation.vector + acc.translation.vector),
                Rotation3::from_matrix_unchecked(turned * fixed.rotation.matrix()),
            );
            out[k + 1] = acc;
        }
        tool_anchors(model, joints, &mut out);
        out
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
    let (s, c) = q_rad.sin_cos();
    let m = match axis {
        0 => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        1 => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    };
    IsometryMatrix3::from_parts(Translation3::new(0.0, 0.0, z_m), Rotation3::from_matrix_unchecked(m))
}
