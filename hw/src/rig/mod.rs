//! The rig read from URDF with urdf-rs: validated into a [`JointTree`], and one closed-form
//! [`ArmModel`] per arm whose mounting and limits come from the URDF. Loading also checks that the
//! URDF chain and the closed-form model describe the same robot (to 1e-9 m), so the two can never drift
//! apart unnoticed. Trocar points are not part of the rig: they belong to the scene.

mod arm_name;
mod diagnose;
mod error;
mod tree;

pub use arm_name::{ArmName, UnknownArm};
pub use error::{Problem, RigError};
pub use tree::{CollisionShape, JointKind, JointTree, Shape, TreeJoint, TreeLink};

use std::path::Path;

use nalgebra::IsometryMatrix3;

use crate::kinematics::residuals::rotation_distance_rad;

use crate::kinematics::{
    ArmJoints, ArmModel, EndoscopeGeometry, InstrumentGeometry, InstrumentLimits, JointLimit, Rv6slGeometry,
    Tool,
};

/// The rig shipped with knotlab.
pub const DEFAULT_URDF: &str = include_str!("../../urdf/knotlab_rig.urdf");
/// How errors name the shipped rig.
pub const DEFAULT_URDF_NAME: &str = "hw/urdf/knotlab_rig.urdf";
/// Largest disagreement allowed between the URDF chain and the closed-form model, m (and rad).
pub const MODEL_AGREEMENT_TOL: f64 = 1e-9;

/// One arm of the rig: its closed-form model and where its joints sit in the URDF tree.
#[derive(Clone, Debug, PartialEq)]
pub struct RigArm {
    /// Which arm.
    pub name: ArmName,
    /// Closed-form kinematics, mounted and limited as the URDF says.
    pub model: ArmModel,
    /// Tree indices of axes 1..=6, then roll, pitch, yaw, jaw 1, jaw 2 for an instrument.
    pub tree_joints: Vec<usize>,
    /// Tree index of the flange link.
    pub flange_link: usize,
    /// Tree index of the tip link.
    pub tip_link: usize,
}

impl RigArm {
    /// The arm's joint positions as a full tree position vector (other arms' joints at zero).
    pub fn tree_positions(&self, tree: &JointTree, joints: &ArmJoints) -> Vec<f64> {
        let mut positions = vec![0.0; tree.joints.len()];
        self.write_tree_positions(joints, &mut positions);
        positions
    }

    /// Writes the arm's joint positions into a tree position vector.
    pub fn write_tree_positions(&self, joints: &ArmJoints, positions: &mut [f64]) {
        let v = joints.to_array();
        for (k, &j) in self.tree_joints.iter().enumerate() {
            positions[j] = match k {
                0..=8 => v[k],
                _ => 0.5 * joints.tool.jaw_rad, // each jaw turns half the opening
            };
        }
    }
}

/// The whole rig.
#[derive(Clone, Debug, PartialEq)]
pub struct Rig {
    /// Where it came from (for messages).
    pub source: String,
    /// The validated URDF.
    pub tree: JointTree,
    /// The four arms, in [`ArmName::ALL`] order.
    pub arms: Vec<RigArm>,
}

impl Rig {
    /// The radius of `arm`'s link `link` (`wrist`, `jaw_1`: the URDF's `<arm>_<link>`), its first
    /// capsule's, m; `None` if it has no capsule.
    pub fn link_radius_m(&self, arm: ArmName, link: &str) -> Option<f64> {
        let name = format!("{}_{link}", arm.as_str());
        self.tree.links.iter().filter(|l| l.name == name).find_map(|l| {
            l.collisions.iter().find_map(|c| match c.shape {
                Shape::Capsule { radius_m, .. } => Some(radius_m),
                _ => None,
            })
        })
    }

    /// The rig shipped with knotlab.
    pub fn shipped() -> Result<Self, RigError> {
        Self::from_urdf_str(DEFAULT_URDF, DEFAULT_URDF_NAME)
    }

    /// Reads a rig from a URDF file.
    pub fn from_file(path: &Path) -> Result<Self, RigError> {
        let file = path.display().to_string();
        let text =
            std::fs::read_to_string(path).map_err(|error| RigError::Read { file: file.clone(), error })?;
        Self::from_urdf_str(&text, &file)
    }

    /// Reads a rig from URDF text; `source` names it in errors.
    pub fn from_urdf_str(text: &str, source: &str) -> Result<Self, RigError> {
        let invalid = |problems| RigError::Invalid { file: source.to_owned(), problems };
        if let Some(problem) = diagnose::too_deep(text) {
            return Err(invalid(vec![problem]));
        }
        let robot = match urdf_rs::read_from_string(text) {
            Ok(robot) => robot,
            Err(e) => {
                let problems = diagnose::diagnose(text);
                return Err(if problems.is_empty() {
                    RigError::Parse { file: source.to_owned(), reason: e.to_string() }
                } else {
                    invalid(problems)
                });
            }
        };
        let tree = JointTree::from_urdf(&robot).map_err(invalid)?;
        let mut problems = Vec::new();
        let mut arms = Vec::new();
        for name in ArmName::ALL {
            if let Some(arm) = extract_arm(&tree, name, &mut problems) {
                arms.push(arm);
            }
        }
        if !problems.is_empty() {
            return Err(invalid(problems));
        }
        let rig = Self { source: source.to_owned(), tree, arms };
        let problems: Vec<Problem> = ArmName::ALL
            .into_iter()
            .filter_map(|name| {
                let (deviation, at) = rig.model_disagreement(name, &agreement_probes());
                (deviation > MODEL_AGREEMENT_TOL).then(|| {
                    Problem::new(
                        format!("arm '{name}'"),
                        "kinematics",
                        format!(
                            "the URDF chain and knotlab's closed-form RV-6SL model disagree by {deviation:.3e} \
                             (m or rad) at joints {:?}: lengths, twists or offsets differ from the model",
                            at.to_array()
                        ),
                    )
                })
            })
            .collect();
        if !problems.is_empty() {
            return Err(invalid(problems));
        }
        Ok(rig)
    }

    /// One arm.
    pub fn arm(&self, name: ArmName) -> &RigArm {
        let i = ArmName::ALL.iter().position(|a| *a == name).unwrap_or(0);
        &self.arms[i]
    }

    /// Every link's world pose by walking the URDF with `name` at `joints` (other arms at zero).
    pub fn link_poses(&self, name: ArmName, joints: &ArmJoints) -> Vec<IsometryMatrix3<f64>> {
        let arm = self.arm(name);
        self.tree.root_from_links(&arm.tree_positions(&self.tree, joints))
    }

    /// Largest disagreement, over `probes`, between the closed-form model and the URDF walk: flange and
    /// tip positions (m) and orientations (rad). Returns it and the joints where it occurred.
    pub fn model_disagreement(&self, name: ArmName, probes: &[ArmJoints]) -> (f64, ArmJoints) {
        let arm = self.arm(name);
        let mut worst = (0.0, ArmJoints::default());
        for joints in probes {
            let walked = self.link_poses(name, joints);
            let pairs = [
                (walked[arm.flange_link], arm.model.world_from_flange(joints)),
                (walked[arm.tip_link], arm.model.world_from_tip(joints)),
            ];
            for (a, b) in pairs {
                let d = (a.translation.vector - b.translation.vector)
                    .norm()
                    .max(rotation_distance_rad(&a.rotation, &b.rotation));
                if d > worst.0 || d.is_nan() {
                    worst = (if d.is_nan() { f64::INFINITY } else { d }, *joints);
                }
            }
        }
        worst
    }
}

/// Joint vectors the loader compares the two models at: zero and a spread of fixed poses.
fn agreement_probes() -> Vec<ArmJoints> {
    let mut probes = vec![ArmJoints::default()];
    for k in 1..=6 {
        let t = f64::from(k);
        let v: [f64; 10] = std::array::from_fn(|i| 0.4 * (1.7 * t + 0.9 * i as f64).sin());
        probes.push(ArmJoints::from_array(v));
    }
    probes
}

fn extract_arm(tree: &JointTree, name: ArmName, problems: &mut Vec<Problem>) -> Option<RigArm> {
    let before = problems.len();
    let element = format!("arm '{name}'");
    let joint = |suffix: &str, problems: &mut Vec<Problem>| {
        let jname = format!("{name}_{suffix}");
        let found = tree.joint(&jname);
        if found.is_none() {
            problems.push(Problem::new(&element, "joints", format!("no joint '{jname}'")));
        }
        found
    };
    let link = |suffix: &str, problems: &mut Vec<Problem>| {
        let lname = format!("{name}_{suffix}");
        let found = tree.link(&lname);
        if found.is_none() {
            problems.push(Problem::new(&element, "links", format!("no link '{lname}'")));
        }
        found
    };

    let base = link("base", problems)?;
    // The base must hang rigidly from the root.
    let world_from_base = tree.root_from_links(&vec![0.0; tree.joints.len()])[base];
    for j in tree.path_to(base) {
        if tree.joints[j].kind != JointKind::Fixed {
            problems.push(Problem::new(
                format!("joint '{}'", tree.joints[j].name),
                "type",
                format!("must be fixed: it lies between the root and {name}_base"),
            ));
        }
    }

    let mut tree_joints = Vec::new();
    let mut limits = [JointLimit::new(0.0, 0.0, 0.0); 6];
    let mut parent = base;
    for i in 1..=6 {
        let j = joint(&format!("joint{i}"), problems)?;
        let tj = &tree.joints[j];
        let je = format!("joint '{}'", tj.name);
        if tj.parent != parent {
            problems.push(Problem::new(&je, "parent", format!("must be link '{}'", tree.links[parent].name)));
        }
        if tj.kind != JointKind::Revolute {
            problems.push(Problem::new(&je, "type", "must be revolute"));
        }
        if (tj.axis.into_inner() - nalgebra::Vector3::z()).norm() > 1e-12 {
            problems.push(Problem::new(&je, "axis.xyz", "must be 0 0 1 (a DH joint turns about its z)"));
        }
        if let Some(limit) = tj.limit {
            limits[i - 1] = limit;
        }
        tree_joints.push(j);
        parent = tj.child;
    }
    let flange = link("flange", problems)?;
    if tree.links[flange].parent_joint.map(|j| tree.joints[j].parent) != Some(parent) {
        problems.push(Problem::new(
            format!("link '{name}_flange'"),
            "parent",
            format!("must hang from link '{}'", tree.links[parent].name),
        ));
    }
    let tip_link = link("tip", problems)?;

    let tool = if name.carries_instrument() {
        let mut tool_limit = |suffix: &str, problems: &mut Vec<Problem>| -> Option<JointLimit> {
            let j = joint(suffix, problems)?;
            tree_joints.push(j);
            tree.joints[j].limit.or_else(|| {
                problems.push(Problem::new(
                    format!("joint '{name}_{suffix}'"),
                    "limit",
                    "must be a revolute joint with limits",
                ));
                None
            })
        };
        let roll = tool_limit("roll", problems);
        let pitch = tool_limit("wrist_pitch", problems);
        let yaw = tool_limit("wrist_yaw", problems);
        let jaw_1 = tool_limit("jaw_1", problems);
        let jaw_2 = tool_limit("jaw_2", problems);
        let (roll, pitch, yaw, jaw_1, _) = (roll?, pitch?, yaw?, jaw_1?, jaw_2?);
        let jaw =
            JointLimit::new(2.0 * jaw_1.lower_rad, 2.0 * jaw_1.upper_rad, 2.0 * jaw_1.max_velocity_rad_s);
        Tool::Instrument {
            geometry: InstrumentGeometry::LARGE_NEEDLE_DRIVER,
            limits: InstrumentLimits { roll, pitch, yaw, jaw },
        }
    } else {
        link("endoscope", problems)?;
        Tool::Endoscope { geometry: EndoscopeGeometry::STEREO_10MM }
    };
    if problems.len() > before {
        return None;
    }
    Some(RigArm {
        name,
        model: ArmModel::new(world_from_base, Rv6slGeometry::RV6SL, limits, tool),
        tree_joints,
        flange_link: flange,
        tip_link,
    })
}
