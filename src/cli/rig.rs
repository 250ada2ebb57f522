//! `knotlab rig`: validate the rig, forward kinematics, trocar-constrained inverse kinematics.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, Subcommand};
use nalgebra::{IsometryMatrix3, UnitQuaternion, Vector3};
use serde::Serialize;

use knotlab_hw::kinematics::{ArmJoints, IkResiduals, JointLimit, TipOrientation, TipTarget, Tool};
use knotlab_hw::rig::{ArmName, JointKind, Rig};

use super::numbers::{Numbers, parse_list, parse_vector3};
use super::output::{Output, outln};

/// A comma-separated list as one argument (an alias, so clap does not read it as a repeated flag).

#[derive(Debug, Subcommand)]
pub enum RigCommand {
    /// Validate the rig's URDF and print its arms, joints and limits.
    Check {
        #[command(flatten)]
        common: Common,
    },
    /// Forward kinematics: every link's world pose and the tip pose for one arm's joints.
    Fk {
        #[command(flatten)]
        common: Common,
        /// left, right, assist or camera.
        #[arg(long)]
        arm: ArmName,
        /// Joint angles in radians: the six arm axes, then (instruments) roll, pitch, yaw, jaw opening.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_list)]
        joints: Numbers,
    },
    /// Inverse kinematics: joints that put the tip on a target with the shaft through a trocar.
    Ik {
        #[command(flatten)]
        common: Common,
        /// left, right, assist or camera.
        #[arg(long)]
        arm: ArmName,
        /// Trocar point x,y,z in the world, metres.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3)]
        trocar: Vector3<f64>,
        /// Tip target x,y,z in the world, metres.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3)]
        tip: Vector3<f64>,
        /// Jaw direction x,y,z (instruments only); default: along the line from the trocar to the tip.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3)]
        jaw_dir: Option<Vector3<f64>>,
        /// Current joints (radians, 6 or 10 values); the solution nearest to them is chosen.
        /// Default: the arm's ready pose.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_list)]
        current: Option<Numbers>,
    },
}

#[derive(Debug, Args)]
pub struct Common {
    /// The rig's URDF; default: the rig shipped with knotlab.
    #[arg(long)]
    urdf: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

fn load(common: &Common) -> anyhow::Result<Rig> {
    Ok(match &common.urdf {
        Some(path) => Rig::from_file(path)?,
        None => Rig::shipped()?,
    })
}

pub fn run(command: RigCommand, out: &mut Output) -> anyhow::Result<ExitCode> {
    match command {
        RigCommand::Check { common } => check(&common, out),
        RigCommand::Fk { common, arm, joints } => fk(&common, arm, &joints, out),
        RigCommand::Ik { common, arm, trocar, tip, jaw_dir, current } => {
            ik(&common, arm, trocar, tip, jaw_dir, current.as_deref(), out)
        }
    }
}

fn print_json<T: Serialize>(out: &mut Output, value: &T) -> anyhow::Result<()> {
    out.line(serde_json::to_string_pretty(value).context("writing JSON")?);
    Ok(())
}

#[derive(Serialize)]
struct Pose {
    position_m: [f64; 3],
    /// URDF roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll).
    rpy_rad: [f64; 3],
    quaternion_xyzw: [f64; 4],
}

impl From<&IsometryMatrix3<f64>> for Pose {
    fn from(pose: &IsometryMatrix3<f64>) -> Self {
        let (r, p, y) = pose.rotation.euler_angles();
        let q = UnitQuaternion::from_rotation_matrix(&pose.rotation);
        let t = pose.translation.vector;
        Self { position_m: [t.x, t.y, t.z], rpy_rad: [r, p, y], quaternion_xyzw: [q.i, q.j, q.k, q.w] }
    }
}

#[derive(Serialize)]
struct JointReport {
    name: String,
    urdf_joint: String,
    lower_rad: f64,
    upper_rad: f64,
    max_velocity_rad_s: f64,
}

#[derive(Serialize)]
struct ArmReport {
    name: String,
    tool: &'static str,
    world_from_base: Pose,
    joints: Vec<JointReport>,
}

#[derive(Serialize)]
struct CheckReport {
    ok: bool,
    source: String,
    robot: String,
    links: usize,
    joints: usize,
    movable_joints: usize,
    arms: Vec<ArmReport>,
    /// Worst disagreement between the closed-form model and the URDF walk, m or rad.
    model_agreement: f64,
    model_agreement_samples_per_arm: usize,
}

/// Deterministic spread of joint vectors for the agreement report.
fn agreement_samples(n: usize) -> Vec<ArmJoints> {
    (0..n)
        .map(|k| {
            ArmJoints::from_array(std::array::from_fn(|i| {
                3.0 * ((k as f64 + 1.0) * 0.618_033_988_749_895 * (i as f64 + 1.3)).sin()
            }))
        })
        .collect()
}

fn check(common: &Common, out: &mut Output) -> anyhow::Result<ExitCode> {
    let rig = match load(common) {
        Ok(rig) => rig,
        Err(error) if common.json => {
            print_json(out, &serde_json::json!({ "ok": false, "error": format!("{error:#}") }))?;
            return Ok(ExitCode::FAILURE);
        }
        Err(error) => return Err(error),
    };
    const SAMPLES: usize = 1000;
    let samples = agreement_samples(SAMPLES);
    let agreement = ArmName::ALL.iter().map(|a| rig.model_disagreement(*a, &samples).0).fold(0.0, f64::max);
    let arms = rig
        .arms
        .iter()
        .map(|arm| {
            let names = [
                "joint1",
                "joint2",
                "joint3",
                "joint4",
                "joint5",
                "joint6",
                "roll",
                "wrist_pitch",
                "wrist_yaw",
                "jaw",
            ];
            let joints = arm
                .tree_joints
                .iter()
                .take(9)
                .zip(names)
                .map(|(&j, name)| (name, &rig.tree.joints[j].name, rig.tree.joints[j].limit))
                .chain(match &arm.model.tool {
                    Tool::Instrument { limits, .. } => {
                        Some(("jaw", &rig.tree.joints[arm.tree_joints[9]].name, Some(limits.jaw)))
                    }
                    Tool::Endoscope { .. } => None,
                })
                .filter_map(|(name, urdf, limit)| {
                    limit.map(|l| JointReport {
                        name: name.to_owned(),
                        urdf_joint: urdf.clone(),
                        lower_rad: l.lower_rad,
                        upper_rad: l.upper_rad,
                        max_velocity_rad_s: l.max_velocity_rad_s,
                    })
                })
                .collect();
            ArmReport {
                name: arm.name.to_string(),
                tool: match arm.model.tool {
                    Tool::Instrument { .. } => "instrument",
                    Tool::Endoscope { .. } => "endoscope",
                },
                world_from_base: Pose::from(&arm.model.world_from_base),
                joints,
            }
        })
        .collect();
    let report = CheckReport {
        ok: true,
        source: rig.source.clone(),
        robot: rig.tree.name.clone(),
        links: rig.tree.links.len(),
        joints: rig.tree.joints.len(),
        movable_joints: rig.tree.joints.iter().filter(|j| j.kind != JointKind::Fixed).count(),
        arms,
        model_agreement: agreement,
        model_agreement_samples_per_arm: SAMPLES,
    };
    if common.json {
        print_json(out, &report)?;
        return Ok(ExitCode::SUCCESS);
    }
    outln!(out, "rig '{}' from {}: OK", report.robot, report.source);
    outln!(out, "{} links, {} joints ({} movable)", report.links, report.joints, report.movable_joints);
    for arm in &report.arms {
        let p = arm.world_from_base.position_m;
        outln!(out, "\narm {} ({}), base at ({:.3}, {:.3}, {:.3}) m", arm.name, arm.tool, p[0], p[1], p[2]);
        for j in &arm.joints {
            outln!(
                out,
                "  {:<12} {:<20} {:>8.1} .. {:>6.1} deg  {:>6.1} deg/s",
                j.name,
                j.urdf_joint,
                j.lower_rad.to_degrees(),
                j.upper_rad.to_degrees(),
                j.max_velocity_rad_s.to_degrees()
            );
        }
    }
    outln!(
        out,
        "\nclosed-form model vs URDF walk: worst {:.1e} (m or rad) over {SAMPLES} joint vectors per arm",
        report.model_agreement
    );
    Ok(ExitCode::SUCCESS)
}

/// The joints given on the command line, each inside its limit (the arm's axes, then the instrument's
/// roll, pitch, yaw and jaw).
fn joints_from(values: &[f64], arm: ArmName, rig: &Rig, what: &str) -> anyhow::Result<ArmJoints> {
    let model = &rig.arm(arm).model;
    let mut limits: Vec<(String, JointLimit)> =
        model.limits.iter().enumerate().map(|(i, l)| (format!("axis {}", i + 1), *l)).collect();
    if let Tool::Instrument { limits: tool, .. } = &model.tool {
        limits.extend(
            [("roll", tool.roll), ("pitch", tool.pitch), ("yaw", tool.yaw), ("jaw", tool.jaw)]
                .map(|(n, l)| (n.to_owned(), l)),
        );
    }
    for ((name, limit), &value) in limits.iter().zip(values) {
        if !limit.contains(value) {
            anyhow::bail!(
                "{what}: {name} = {value} rad is outside its limits, {:.4} to {:.4} rad",
                limit.lower_rad,
                limit.upper_rad
            );
        }
    }
    match (values.len(), arm.carries_instrument()) {
        (6, _) => Ok(ArmJoints::from_arm(std::array::from_fn(|i| values[i]))),
        (10, true) => Ok(ArmJoints::from_array(std::array::from_fn(|i| values[i]))),
        (n, true) => anyhow::bail!(
            "{what}: the {arm} arm takes 6 values (axes 1-6) or 10 (with roll, pitch, yaw, jaw), got {n}"
        ),
        (n, false) => anyhow::bail!("{what}: the camera arm takes 6 values (axes 1-6), got {n}"),
    }
}

#[derive(Serialize)]
struct LinkPose {
    name: String,
    #[serde(flatten)]
    pose: Pose,
}

#[derive(Serialize)]
struct FkReport {
    arm: String,
    joints_rad: Numbers,
    links: Vec<LinkPose>,
    tip: Pose,
}

fn fk(common: &Common, arm: ArmName, values: &[f64], out: &mut Output) -> anyhow::Result<ExitCode> {
    let rig = load(common)?;
    let joints = joints_from(values, arm, &rig, "--joints")?;
    let poses = rig.link_poses(arm, &joints);
    let prefix = format!("{arm}_");
    let links = rig
        .tree
        .links
        .iter()
        .enumerate()
        .filter(|(_, l)| l.name.starts_with(&prefix))
        .map(|(i, l)| LinkPose { name: l.name.clone(), pose: Pose::from(&poses[i]) })
        .collect();
    let model = &rig.arm(arm).model;
    let report = FkReport {
        arm: arm.to_string(),
        joints_rad: joints.to_array().to_vec(),
        links,
        tip: Pose::from(&model.world_from_tip(&joints)),
    };
    if common.json {
        print_json(out, &report)?;
        return Ok(ExitCode::SUCCESS);
    }
    outln!(
        out,
        "{:<24} {:>9} {:>9} {:>9}   {:>8} {:>8} {:>8}",
        "link",
        "x m",
        "y m",
        "z m",
        "roll",
        "pitch",
        "yaw"
    );
    let row = |out: &mut Output, name: &str, p: &Pose| {
        let [x, y, z] = p.position_m;
        let [r, pi, ya] = p.rpy_rad;
        outln!(out, "{name:<24} {x:>9.4} {y:>9.4} {z:>9.4}   {r:>8.4} {pi:>8.4} {ya:>8.4}");
    };
    for link in &report.links {
        row(out, &link.name, &link.pose);
    }
    row(out, "tip (closed form)", &report.tip);
    Ok(ExitCode::SUCCESS)
}

#[derive(Serialize)]
struct IkReport {
    ok: bool,
    arm: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    joints_rad: Option<serde_json::Map<String, serde_json::Value>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    residuals: Option<Residuals>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

#[derive(Serialize)]
struct Residuals {
    tip_error_m: f64,
    orientation_error_rad: f64,
    trocar_distance_m: f64,
}

fn ik(
    common: &Common,
    arm: ArmName,
    trocar: Vector3<f64>,
    tip: Vector3<f64>,
    jaw_dir: Option<Vector3<f64>>,
    current: Option<&[f64]>,
    out: &mut Output,
) -> anyhow::Result<ExitCode> {
    let rig = load(common)?;
    if jaw_dir.is_some() && !arm.carries_instrument() {
        anyhow::bail!(
            "--jaw-dir: the camera arm's endoscope looks along its shaft; only its tip can be placed"
        );
    }
    let seed = match current {
        Some(values) => joints_from(values, arm, &rig, "--current")?,
        None => arm.ready_joints(),
    };
    let orientation = jaw_dir.map_or(TipOrientation::AlongShaft, TipOrientation::JawDirection);
    let target = TipTarget { world_position_m: tip, orientation };
    let model = &rig.arm(arm).model;
    let report = match model.solve_tip(&target, &trocar, &seed) {
        Ok(joints) => {
            let r = IkResiduals::measure(model, &joints, &target, &trocar);
            let count = if arm.carries_instrument() { 10 } else { 6 };
            let values = joints.to_array();
            let named = ArmJoints::ORDER
                .iter()
                .zip(values)
                .take(count)
                .map(|(id, v)| (id.to_string(), serde_json::json!(v)))
                .collect();
            IkReport {
                ok: true,
                arm: arm.to_string(),
                joints_rad: Some(named),
                residuals: Some(Residuals {
                    tip_error_m: r.tip_error_m,
                    orientation_error_rad: r.orientation_error_rad,
                    trocar_distance_m: r.trocar_distance_m,
                }),
                error: None,
            }
        }
        Err(e) => IkReport {
            ok: false,
            arm: arm.to_string(),
            joints_rad: None,
            residuals: None,
            error: Some(e.to_string()),
        },
    };
    if common.json {
        print_json(out, &report)?;
    } else if let (Some(joints), Some(r)) = (&report.joints_rad, &report.residuals) {
        for (name, value) in joints {
            let v = value.as_f64().unwrap_or(f64::NAN);
            outln!(out, "{name:<12} {v:>10.6} rad  {:>9.3} deg", v.to_degrees());
        }
        outln!(out, "tip error          {:.3e} m", r.tip_error_m);
        outln!(out, "orientation error  {:.3e} rad", r.orientation_error_rad);
        outln!(out, "shaft to trocar    {:.3e} m", r.trocar_distance_m);
    } else if let Some(error) = &report.error {
        out.error(format!("error: {arm} arm: {error}"));
    }
    Ok(if report.ok { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
