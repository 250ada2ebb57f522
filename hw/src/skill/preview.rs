//! The kinematic part of a skill's preview: every track's target, every `step_s` of the skill, solved
//! with the shaft through its trocar from the joints before (as the controller will), so a target out of
//! reach, past a joint limit or through the trocar is found before anything moves, with the arm and the
//! time.

use crate::arm_setup::ArmSetup;
use crate::kinematics::{ArmJoints, IkError};
use crate::rig::ArmName;

use super::Skill;

/// A target the arm cannot take.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("the {arm} arm at {time_s:.2} s of the skill: {source}")]
pub struct KinematicProblem {
    /// The arm.
    pub arm: ArmName,
    /// Skill time, s.
    pub time_s: f64,
    /// Why.
    pub source: IkError,
}

/// Checks every track of `skill` whose arm has a setup, from the arms' `current` joints.
pub fn kinematic_preview(
    skill: &Skill,
    setups: &[ArmSetup],
    current: &[(ArmName, ArmJoints)],
    step_s: f64,
) -> Result<(), KinematicProblem> {
    kinematic_trajectory(skill, setups, current, step_s).map(|_| ())
}

/// The joints every track of `skill` whose arm has a setup takes, every `step_s` of the skill from 0 to
/// its end (a track that ends earlier holds its last joints), solved as [`kinematic_preview`] does; each
/// arm's list has one entry per step.
pub fn kinematic_trajectory(
    skill: &Skill,
    setups: &[ArmSetup],
    current: &[(ArmName, ArmJoints)],
    step_s: f64,
) -> Result<Vec<(ArmName, Vec<ArmJoints>)>, KinematicProblem> {
    let step_s = if step_s.is_finite() && step_s > 0.0 { step_s } else { 0.01 };
    let end_s = skill.duration_s();
    let steps = (end_s / step_s).ceil() as usize;
    let mut out = Vec::new();
    for track in &skill.tracks {
        let (Some(setup), Some((_, joints))) =
            (setups.iter().find(|s| s.arm == track.arm), current.iter().find(|(a, _)| *a == track.arm))
        else {
            continue;
        };
        let mut joints = *joints;
        let mut along = Vec::with_capacity(steps + 1);
        for k in 0..=steps {
            let time_s = (k as f64 * step_s).min(end_s);
            if let Some(target) = track.target_at(time_s) {
                joints = setup
                    .model
                    .solve_tip(&target, &setup.world_trocar_m, &joints)
                    .map_err(|source| KinematicProblem { arm: track.arm, time_s, source })?;
            }
            along.push(joints);
        }
        out.push((track.arm, along));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::{TipOrientation, TipTarget};
    use crate::rig::Rig;
    use crate::skill::{Orientation, PoseKey, Track};
    use nalgebra::Vector3;

    /// A target beyond the instrument's reach is found on the way to it, naming the arm and a time inside
    /// the skill, while a nearby target passes.
    #[test]
    fn a_target_out_of_reach_is_found_with_its_arm_and_time() {
        let rig = Rig::shipped().expect("the shipped rig");
        let arm = ArmName::Left;
        let model = rig.arm(arm).model;
        let trocar = Vector3::new(-0.08, 0.12, 1.02);
        let tip = trocar + Vector3::new(0.02, -0.03, -0.07);
        let target = TipTarget { world_position_m: tip, orientation: TipOrientation::AlongShaft };
        let joints = model.solve_tip(&target, &trocar, &arm.ready_joints()).expect("reachable");
        let setups = [ArmSetup { arm, model, world_trocar_m: trocar }];
        let key = |time_s: f64, p: Vector3<f64>| PoseKey {
            time_s,
            world_position_m: p.into(),
            orientation: Orientation::AlongShaft,
        };
        let skill = |far: Vector3<f64>| Skill {
            name: "reach".into(),
            tracks: vec![Track {
                arm,
                poses: vec![key(0.0, tip), key(1.0, far)],
                jaw: Vec::new(),
                events: Vec::new(),
            }],
        };
        let near = tip + Vector3::new(0.01, 0.0, -0.01);
        assert!(kinematic_preview(&skill(near), &setups, &[(arm, joints)], 0.01).is_ok());
        // 2 m below the trocar: deeper than the instrument reaches, found on the way there.
        let problem =
            kinematic_preview(&skill(tip - Vector3::new(0.0, 0.0, 2.0)), &setups, &[(arm, joints)], 0.01)
                .expect_err("out of reach");
        assert_eq!(problem.arm, arm);
        assert!(problem.time_s > 0.0 && problem.time_s < 1.0, "{problem}");
        assert!(problem.to_string().starts_with("the left arm at"), "{problem}");
    }
}
