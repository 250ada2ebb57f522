//! The lab's workflow, in the simulator (the paper's, section II): the surgeon teleoperates the
//! instruments through the master devices (clutch and motion scaling) and establishes the initial
//! condition; pressing the skill pedal instantiates the learned skill at the stitch as it is now, blocks
//! manual input, previews the skill (every target reachable within the joints' limits, no link
//! collision along the way) and executes it;
//! afterwards manual control resumes. The emergency pedal stops everything at any time.
//!
//! The surgeon is a script of handle poses and pedal presses on the simulated rig's dummy masters and
//! pedals, or a person with a gamepad (`scenarios/rigs/sim-gamepad.toml`, the `gamepad` feature).

use knotlab_hw::controller::{ControllerError, Status, TeleopSettings};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::{RigConfig, build_rig};
use knotlab_learner::synthesis::Method;
use knotlab_sim::backend::SimBackend;
use knotlab_sim::world::SimWorld;
use nalgebra::{IsometryMatrix3, Translation3, Vector3};

use knotlab_learner::demonstration::Demonstration;

use crate::expert::record::{RecordError, empty_records, expert_metadata, sample_instruments};
use crate::trial::{Learned, collision_check, kinematic_check, synthesize_for};

/// The assignable pedal that instantiates and executes the skill (0 is the clutch).
pub const SKILL_PEDAL: usize = 1;

/// What the surgeon does at a moment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Action {
    /// Puts a master's handle here (console frame, m) with the gripper this open (rad).
    Handle {
        /// The arm the master steers.
        arm: ArmName,
        /// The handle's position in the console, m.
        position_m: [f64; 3],
        /// The gripper's opening, rad.
        gripper_rad: f64,
    },
    /// Presses (true) or releases the clutch pedal.
    Clutch(bool),
    /// Presses or releases the skill pedal.
    SkillPedal(bool),
    /// Presses or releases the emergency stop.
    EmergencyStop(bool),
}

/// The script: actions at times, s from the session's start (in increasing time).
pub type Script = Vec<(f64, Action)>;

/// What happened in a session.
#[derive(Clone, Debug, PartialEq)]
pub struct SessionReport {
    /// Notable moments, in order: `(time_s, what)`.
    pub log: Vec<(f64, String)>,
    /// When the skill was loaded (after its preview passed), s.
    pub skill_started_s: Option<f64>,
    /// When it finished, s.
    pub skill_finished_s: Option<f64>,
    /// Why a preview refused the skill, if one did.
    pub refused: Option<String>,
    /// The controller's status at the end.
    pub status: Status,
    /// Every instrument's tip every 10 ms: `(time_s, arm, position)`.
    pub tips: Vec<(f64, ArmName, Vector3<f64>)>,
    /// What the devices read at 100 Hz, teleoperation and skill alike: a demonstration in the format
    /// the scripted expert's are written in (a teleoperated recording).
    pub demonstration: Demonstration,
}

/// Why a session could not run.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// The rig does not build or start.
    #[error(transparent)]
    Record(#[from] RecordError),
    /// The controller faulted.
    #[error("the controller")]
    Controller(#[from] ControllerError),
    /// The rig has no dummy masters or pedals to script.
    #[error("the rig config has no dummy {0} to script")]
    NotScriptable(&'static str),
}

/// Runs a session of `duration_s` on `world` with the rig `config` (a script needs dummy pedals and
/// masters; a gamepad rig takes its input from the gamepad), teleoperation as `teleop`, the skill from `learned` by `method` when the skill pedal goes
/// down; with `real_time` the simulation is paced to the wall clock (for a person at a gamepad).
#[allow(clippy::too_many_arguments)]
pub fn run_session(
    world: SimWorld,
    rig: &Rig,
    config: &RigConfig,
    learned: &Learned,
    method: Method,
    teleop: TeleopSettings,
    script: &Script,
    duration_s: f64,
    real_time: bool,
) -> Result<SessionReport, SessionError> {
    let started = std::time::Instant::now();
    let rate_hz = 1.0 / (world.config().solver.dt_s * 10.0);
    let mut metadata = expert_metadata(&world, "", None, rate_hz);
    metadata.source = "teleoperation".into();
    metadata.description = "a teleoperated session: manual control, the skill pedal, the skill".into();
    let mut backend = SimBackend::new(world);
    let built = build_rig(config, rig, Some(&mut backend)).map_err(RecordError::from)?;
    let (mut controller, handles) = built.into_controller().map_err(RecordError::from)?;
    controller.set_teleoperation(Some(teleop))?;
    let pedals = handles.pedals.clone();
    let press = |set: &dyn Fn(&knotlab_hw::device::dummy::PedalHandle)| -> Result<(), SessionError> {
        set(pedals.as_ref().ok_or(SessionError::NotScriptable("pedals"))?);
        Ok(())
    };
    let mut report = SessionReport {
        log: Vec::new(),
        skill_started_s: None,
        skill_finished_s: None,
        refused: None,
        status: Status::Idle,
        tips: Vec::new(),
        demonstration: Demonstration { metadata, instruments: empty_records() },
    };
    let mut next = 0;
    let mut skill_pedal_was_down = false;
    loop {
        let time_s = controller.record().time_s;
        while let Some((at, action)) = script.get(next).filter(|(at, _)| *at <= time_s) {
            let _ = at;
            match *action {
                Action::Handle { arm, position_m, gripper_rad } => {
                    let Some((_, h)) = handles.masters.iter().find(|(a, _)| *a == arm) else {
                        return Err(SessionError::NotScriptable("master for that arm"));
                    };
                    let pose = IsometryMatrix3::from_parts(
                        Translation3::from(Vector3::from(position_m)),
                        nalgebra::Rotation3::identity(),
                    );
                    h.set(pose, gripper_rad, 0);
                }
                Action::Clutch(down) => press(&|p| p.set_assignable(teleop.clutch_pedal, down))?,
                Action::SkillPedal(down) => press(&|p| p.set_assignable(SKILL_PEDAL, down))?,
                Action::EmergencyStop(down) => press(&|p| p.set_emergency_stop(down))?,
            }
            next += 1;
        }
        let record = match controller.step() {
            Ok(record) => record.clone(),
            Err(error) => {
                report.log.push((time_s, format!("fault: {error}")));
                report.status = Status::Faulted;
                return Ok(report);
            }
        };
        if record.cycle % 10 == 0 {
            for arm in [ArmName::Left, ArmName::Right, ArmName::Assist] {
                if let Some(a) = record.arm(arm) {
                    report.tips.push((record.time_s, arm, a.world_from_tip.translation.vector));
                }
            }
            sample_instruments(&record, &backend.world(), &mut report.demonstration.instruments);
        }
        if record.status == Status::Finished
            && report.skill_started_s.is_some()
            && report.skill_finished_s.is_none()
        {
            report.skill_finished_s = Some(record.time_s);
            report.log.push((record.time_s, "skill finished: manual control resumes".into()));
        }
        if record.status == Status::EmergencyStopped
            && report.log.last().is_none_or(|(_, w)| w != "emergency stop")
        {
            report.log.push((record.time_s, "emergency stop".into()));
        }
        let pedal_down = record.pedals.assignable[SKILL_PEDAL];
        let rising = pedal_down && !skill_pedal_was_down;
        skill_pedal_was_down = pedal_down;
        if rising && matches!(record.status, Status::Idle | Status::Finished) {
            let world = backend.world();
            let made = synthesize_for(&world, learned, method).map(|m| {
                // Reachability, then link collisions along the joints that takes.
                let preview = kinematic_check(&world, &m.skill).map_err(|p| p.to_string()).and_then(|()| {
                    match collision_check(&world, &m.skill) {
                        Ok(None) => Ok(()),
                        Ok(Some(collision)) => Err(format!("link collision: {collision}")),
                        Err(e) => Err(format!("collision check: {e}")),
                    }
                });
                (m, preview)
            });
            drop(world);
            match made {
                Err(e) => {
                    report.refused = Some(format!("synthesis: {e}"));
                    report.log.push((record.time_s, format!("skill refused: synthesis: {e}")));
                }
                Ok((made, preview)) => match preview {
                    Err(problem) => {
                        report.refused = Some(problem.clone());
                        report.log.push((record.time_s, format!("skill refused by the preview: {problem}")));
                    }
                    Ok(()) => {
                        controller.load_skill(made.skill)?;
                        report.skill_started_s = Some(record.time_s);
                        report.log.push((
                            record.time_s,
                            "skill instantiated at the stitch, previewed, executing".into(),
                        ));
                    }
                },
            }
        }
        if real_time {
            // A person at the console: simulated time does not run ahead of the clock on the wall.
            let ahead = record.time_s - started.elapsed().as_secs_f64();
            if ahead > 0.002 {
                std::thread::sleep(std::time::Duration::from_secs_f64(ahead));
            }
        }
        if record.time_s >= duration_s {
            report.status = record.status;
            return Ok(report);
        }
    }
}
