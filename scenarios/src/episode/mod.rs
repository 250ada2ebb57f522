//! A trial driven step by step from outside (a policy; the Gymnasium environment of the Python
//! package): each step commands every instrument's tip velocity, turn rate and jaw opening for one
//! control period, moving the tip's target from where the controller's arm model puts the tip at
//! the start (the scene's tips stand off it by the arms' calibration and play, as real ones do); the controller runs them on the simulated rig exactly as it runs a skill (the
//! targets interpolated at every 1 ms cycle, the arm's inverse kinematics with the shaft through the
//! trocar, the joints' speed limits). A step's target the arm cannot reach through its trocar is not
//! taken: that tip's target stays where it was, and the step says so.
//!
//! The episode ends at the time limit, when no instrument holds the thread or the needle any more
//! (what the thread does then is its own: the knot's verdict is final), or on a device fault; then the
//! knot is judged as a trial's is, with the holding test.
//!
//! - [`settings`]: the control rate, the time limit and the bounds of a command.
//! - [`observation`]: what a policy sees after each step.
//! - [`replay`]: a demonstration as an episode's commands.

pub mod observation;
pub mod replay;
pub mod settings;

pub use observation::{Grasp, Observation};
pub use replay::demonstration_commands;
pub use settings::EpisodeSettings;

use knotlab_hw::controller::{Controller, Status};
use knotlab_hw::kinematics::{TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::{build_rig, parse_rig_config};
use knotlab_hw::skill::{JawKey, Orientation, PoseKey, Skill, Track};
use knotlab_sim::backend::SimBackend;
use knotlab_sim::evaluate::{KnotEvaluation, evaluate_knot, fault_evaluation};
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::{UnitQuaternion, Vector3};

use crate::expert::record::SIM_RIG_TOML;

/// The instruments an episode commands, in the order of commands and observations.
pub const ARMS: [ArmName; 3] = [ArmName::Left, ArmName::Right, ArmName::Assist];

/// One instrument's command for one step (world frame).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TipCommand {
    /// The tip's velocity, m/s.
    pub world_velocity_mps: Vector3<f64>,
    /// The tip's rate of turn (the axis, scaled by the rate), rad/s.
    pub world_turn_rad_s: Vector3<f64>,
    /// The jaw's opening to reach by the step's end, rad.
    pub jaw_rad: f64,
}

/// Why an episode ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Ending {
    /// It reached its time limit.
    TimeLimit,
    /// No instrument holds the thread or the needle any more.
    Released,
    /// A device faulted (the controller stopped).
    Fault(String),
}

/// What one step did.
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// The instruments whose new target was out of reach (their targets stayed where they were).
    pub out_of_reach: Vec<ArmName>,
    /// Why the episode ended, if this step ended it.
    pub ended: Option<Ending>,
}

/// Why an episode cannot be made or stepped.
#[derive(Debug, thiserror::Error)]
pub enum EpisodeError {
    /// A setting is out of range.
    #[error("{field}: {reason}")]
    Settings {
        /// The setting.
        field: &'static str,
        /// Why.
        reason: String,
    },
    /// A command is out of its bounds.
    #[error("the {arm} instrument's {field} {value}: {reason}")]
    Command {
        /// The instrument.
        arm: ArmName,
        /// The command's field.
        field: &'static str,
        /// Its value.
        value: String,
        /// What is allowed.
        reason: String,
    },
    /// The simulated rig could not be built.
    #[error("the simulated rig: {0}")]
    Rig(String),
    /// The episode has ended; make a new one.
    #[error("the episode has ended ({0:?}); reset it")]
    Ended(Ending),
}

/// A trial run step by step.
pub struct Episode {
    backend: SimBackend,
    controller: Controller,
    settings: EpisodeSettings,
    cycles_per_step: u64,
    period_s: f64,
    steps: u64,
    /// Each tip's target at the end of the last step.
    targets: [(Vector3<f64>, UnitQuaternion<f64>); 3],
    jaws_rad: [f64; 3],
    observation: Observation,
    ending: Option<Ending>,
    evaluation: Option<KnotEvaluation>,
}

impl Episode {
    /// An episode on `world` as it stands (the task's initial condition when it is new), the
    /// instruments' targets where their tips are.
    pub fn new(world: SimWorld, settings: EpisodeSettings) -> Result<Self, EpisodeError> {
        let period_s = world.config().solver.dt_s;
        if let Some((field, reason)) = settings.problems(1.0 / period_s).into_iter().next() {
            return Err(EpisodeError::Settings { field, reason });
        }
        let cycles_per_step = (1.0 / (period_s * settings.control_hz)).round() as u64;
        let rig = Rig::shipped().map_err(|e| EpisodeError::Rig(e.to_string()))?;
        let config = parse_rig_config(SIM_RIG_TOML, "scenarios/rigs/sim.toml")
            .map_err(|e| EpisodeError::Rig(e.to_string()))?;
        let mut backend = SimBackend::new(world);
        let (controller, _handles) = build_rig(&config, &rig, Some(&mut backend))
            .map_err(|e| EpisodeError::Rig(e.to_string()))?
            .into_controller()
            .map_err(|e| EpisodeError::Rig(e.to_string()))?;
        let (targets, jaws_rad, observation) = {
            let world = backend.world();
            // Where the controller's model puts each tip for the joints it commands (the scene's tip
            // stands off it by the arm's calibration and play): steps move the targets from there.
            let targets = ARMS.map(|arm| {
                let tip = world.rig().arm(arm).model.world_from_tip(&world.arm(arm).command);
                (tip.translation.vector, UnitQuaternion::from_rotation_matrix(&tip.rotation))
            });
            let jaws = ARMS.map(|arm| world.arm(arm).command.tool.jaw_rad);
            (targets, jaws, Observation::now(&world, controller.record(), 0.0, settings.thread_points))
        };
        Ok(Self {
            backend,
            controller,
            settings,
            cycles_per_step,
            period_s,
            steps: 0,
            targets,
            jaws_rad,
            observation,
            ending: None,
            evaluation: None,
        })
    }

    /// Its settings.
    pub fn settings(&self) -> &EpisodeSettings {
        &self.settings
    }

    /// What the last step left (the start, before the first).
    pub fn observation(&self) -> &Observation {
        &self.observation
    }

    /// Why it ended, once it has.
    pub fn ending(&self) -> Option<&Ending> {
        self.ending.as_ref()
    }

    /// The knot's evaluation, once it has ended.
    pub fn evaluation(&self) -> Option<&KnotEvaluation> {
        self.evaluation.as_ref()
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The scene, locked (to draw or inspect it).
    pub fn world(&self) -> std::sync::MutexGuard<'_, SimWorld> {
        self.backend.world()
    }

    /// Checks `commands` against the settings' bounds.
    fn check(&self, commands: &[TipCommand; 3]) -> Result<(), EpisodeError> {
        let s = &self.settings;
        for (arm, c) in ARMS.iter().zip(commands) {
            let bad = |field, value: String, reason: String| EpisodeError::Command {
                arm: *arm,
                field,
                value,
                reason,
            };
            let vectors = [
                ("world_velocity_mps", c.world_velocity_mps, s.max_speed_mps, "m/s"),
                ("world_turn_rad_s", c.world_turn_rad_s, s.max_turn_rad_s, "rad/s"),
            ];
            for (field, v, most, unit) in vectors {
                if !v.iter().all(|x| x.is_finite() && x.abs() <= most * (1.0 + 1e-9)) {
                    return Err(bad(
                        field,
                        format!("{:?}", v.as_slice()),
                        format!("at most {most} {unit} along each axis"),
                    ));
                }
            }
            if !(c.jaw_rad.is_finite() && (0.0..=s.max_jaw_rad).contains(&c.jaw_rad)) {
                return Err(bad("jaw_rad", c.jaw_rad.to_string(), format!("0 to {} rad", s.max_jaw_rad)));
            }
        }
        Ok(())
    }

    /// One step: every instrument's tip moves by its command for one control period (`1 /
    /// control_hz`), its jaw to the commanded opening.
    pub fn step(&mut self, commands: &[TipCommand; 3]) -> Result<StepReport, EpisodeError> {
        if let Some(ending) = &self.ending {
            return Err(EpisodeError::Ended(ending.clone()));
        }
        self.check(commands)?;
        let dt_s = 1.0 / self.settings.control_hz;
        let mut out_of_reach = Vec::new();
        let mut tracks = Vec::with_capacity(ARMS.len());
        {
            let world = self.backend.world();
            for (k, (arm, c)) in ARMS.iter().zip(commands).enumerate() {
                let (from_p, from_q) = self.targets[k];
                let to_p = from_p + c.world_velocity_mps * dt_s;
                let to_q = UnitQuaternion::from_scaled_axis(c.world_turn_rad_s * dt_s) * from_q;
                let target = TipTarget {
                    world_position_m: to_p,
                    orientation: TipOrientation::Frame(to_q.to_rotation_matrix()),
                };
                let model = &world.rig().arm(*arm).model;
                let reached =
                    model.solve_tip(&target, &trocar_of(world.config(), *arm), &world.arm(*arm).command);
                let (to_p, to_q) = if reached.is_ok() {
                    (to_p, to_q)
                } else {
                    out_of_reach.push(*arm);
                    (from_p, from_q)
                };
                tracks.push(self.track(*arm, (from_p, from_q), (to_p, to_q), (self.jaws_rad[k], c.jaw_rad)));
                self.targets[k] = (to_p, to_q);
                self.jaws_rad[k] = c.jaw_rad;
            }
        }
        let skill = Skill { name: format!("step {}", self.steps), tracks };
        let ended = match self.run(skill) {
            Err(fault) => Some(Ending::Fault(fault)),
            Ok(()) => {
                self.steps += 1;
                let time_s = self.steps as f64 * dt_s;
                let world = self.backend.world();
                if time_s >= self.settings.time_limit_s - 1e-9 {
                    Some(Ending::TimeLimit)
                } else if ARMS.iter().all(|a| !world.arm(*a).holds()) {
                    Some(Ending::Released)
                } else {
                    None
                }
            }
        };
        let time_s = self.steps as f64 * dt_s;
        {
            let world = self.backend.world();
            self.observation =
                Observation::now(&world, self.controller.record(), time_s, self.settings.thread_points);
        }
        if let Some(ending) = &ended {
            let mut world = self.backend.world();
            let evaluation = match ending {
                Ending::Fault(_) => fault_evaluation(&world),
                _ => {
                    let params = world.config().evaluation.clone();
                    evaluate_knot(&mut world, &params)
                }
            };
            self.evaluation = Some(evaluation);
            self.ending = ended.clone();
        }
        Ok(StepReport { out_of_reach, ended })
    }

    /// The track of one step: `cycles_per_step` cycles, the first a cycle's worth along the way, the
    /// last at the new target.
    fn track(
        &self,
        arm: ArmName,
        (from_p, from_q): (Vector3<f64>, UnitQuaternion<f64>),
        (to_p, to_q): (Vector3<f64>, UnitQuaternion<f64>),
        (from_jaw, to_jaw): (f64, f64),
    ) -> Track {
        let n = self.cycles_per_step;
        let first = 1.0 / n as f64;
        let pose = |time_s: f64, f: f64| {
            let q = from_q.slerp(&to_q, f);
            PoseKey {
                time_s,
                world_position_m: from_p.lerp(&to_p, f).into(),
                orientation: Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] },
            }
        };
        let jaw = |time_s: f64, f: f64| JawKey { time_s, jaw_rad: from_jaw + (to_jaw - from_jaw) * f };
        let end_s = (n - 1) as f64 * self.period_s;
        let (poses, jaws) = if n == 1 {
            (vec![pose(0.0, 1.0)], vec![jaw(0.0, 1.0)])
        } else {
            (vec![pose(0.0, first), pose(end_s, 1.0)], vec![jaw(0.0, first), jaw(end_s, 1.0)])
        };
        Track { arm, poses, jaw: jaws, events: Vec::new() }
    }

    /// Runs `skill` to its end; the fault's message if the controller stopped.
    fn run(&mut self, skill: Skill) -> Result<(), String> {
        self.controller.load_skill(skill).map_err(|e| e.to_string())?;
        for _ in 0..self.cycles_per_step {
            let record = self.controller.step().map_err(|e| e.to_string())?;
            if record.status == Status::Finished {
                return Ok(());
            }
        }
        Err(format!("the step's skill did not finish in {} cycles", self.cycles_per_step))
    }
}
