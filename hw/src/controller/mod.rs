//! The controller (skill executor): runs a [`Skill`] on any rig of devices, one cycle at a time.
//!
//! Each cycle, in the ros2_control manner:
//! 1. read every device: pedals, each arm's servo, instrument drive and force sensor, the masters. A
//!    stale reading keeps the last value; a device stale for `watchdog_cycles` in a row, or any device
//!    error, faults the run;
//! 2. the emergency stop pedal latches [`Status::EmergencyStopped`]: from this very cycle no new
//!    set-point is written, so every arm holds the set-point it had (motion stops within one cycle);
//! 3. while running, per arm with a track: force-triggered events, the interpolated tip target, IK
//!    with the shaft through the trocar (seeded with the last set-point, so the solution is the one
//!    nearest the path so far), the step clamped to `speed_scale` of each joint's rated speed, and the
//!    writes (through whatever limit decorators wrap the drivers);
//! 4. the clock ends the cycle (a simulation step; nothing for a MELFA rig, whose reply waits pace it).
//!
//! After a fault the controller writes nothing more: every device holds its last set-point, a MELFA
//! controller keeps its last command. The cycle's period is the clock's (1 ms in simulation, 7.11 or
//! 3.5 ms on MELFA controllers); skill time advances one period per cycle.
//!
//! Use it step-wise ([`Controller::step`], returning each cycle's [`CycleRecord`] for a recorder) or to
//! the end ([`Controller::run_to_end`] with an observer).

mod arm;
pub mod error;
pub mod params;
pub mod record;
pub mod teleop;

pub use crate::arm_setup::ArmSetup;
pub use error::ControllerError;
pub use params::ControllerParams;
pub use record::{ArmRecord, CycleRecord, FiredEvent, RunOutcome, RunSummary, Status};
pub use teleop::TeleopSettings;

use crate::device::{
    CycleClock, DeviceError, DeviceId, DeviceKind, DeviceSet, ForceFeedback, MasterDevice, MasterState,
    PedalState, Pedals,
};
use crate::rig::ArmName;
use crate::skill::Skill;

use arm::ArmRuntime;

/// A master device and what it last read.
struct Master {
    arm: ArmName,
    device: Box<dyn MasterDevice>,
    state: MasterState,
    stale: u32,
    /// Where the handle and the tip were when teleoperation last engaged (none: disengaged).
    engaged: Option<teleop::Engagement>,
}

/// Runs skills on a set of devices.
pub struct Controller {
    arms: Vec<ArmRuntime>,
    pedals: Box<dyn Pedals>,
    pedals_stale: u32,
    masters: Vec<Master>,
    clock: Box<dyn CycleClock>,
    params: ControllerParams,
    period_s: f64,
    skill: Option<Skill>,
    skill_time_s: f64,
    /// Cycles since the skill started (skill time is this times the period, without drift).
    skill_cycle: u64,
    duration_s: f64,
    cycle: u64,
    status: Status,
    fired: Vec<FiredEvent>,
    record: CycleRecord,
    /// Teleoperation while no skill runs, if on.
    teleop: Option<TeleopSettings>,
}

impl Controller {
    /// A controller for `devices`, with one setup per arm that has devices. Reads every device once:
    /// the arms' measured joints become their first set-points.
    pub fn new(
        devices: DeviceSet,
        setups: &[ArmSetup],
        params: ControllerParams,
    ) -> Result<Self, ControllerError> {
        let problems = params.problems();
        if let Some((field, reason)) = problems.first() {
            return Err(ControllerError::Setup(format!("{field}: {reason}")));
        }
        let period_s = devices.clock.period_s();
        if !(period_s.is_finite() && period_s > 0.0) {
            return Err(ControllerError::Setup(format!("the clock's period {period_s} s is not a period")));
        }
        let mut arms = Vec::with_capacity(devices.arms.len());
        for (name, arm_devices) in devices.arms {
            if arms.iter().any(|a: &ArmRuntime| a.name() == name) {
                return Err(ControllerError::Setup(format!("the {name} arm has two sets of devices")));
            }
            let setup = setups.iter().find(|s| s.arm == name).ok_or_else(|| {
                ControllerError::Setup(format!("the {name} arm has devices but no model and trocar"))
            })?;
            if !setup.world_trocar_m.iter().all(|x| x.is_finite()) {
                return Err(ControllerError::Setup(format!("the {name} arm's trocar is not finite")));
            }
            arms.push(ArmRuntime::new(*setup, arm_devices, period_s, params.speed_scale));
        }
        let masters = devices
            .masters
            .into_iter()
            .map(|(arm, device)| Master {
                arm,
                device,
                state: MasterState::default(),
                stale: 0,
                engaged: None,
            })
            .collect();
        let record = CycleRecord {
            cycle: 0,
            time_s: 0.0,
            skill_time_s: 0.0,
            status: Status::Idle,
            pedals: PedalState::default(),
            arms: arms.iter().map(|a| a.record).collect(),
        };
        let mut controller = Self {
            arms,
            pedals: devices.pedals,
            pedals_stale: 0,
            masters,
            clock: devices.clock,
            params,
            period_s,
            skill: None,
            skill_time_s: 0.0,
            skill_cycle: 0,
            duration_s: 0.0,
            cycle: 0,
            status: Status::Idle,
            fired: Vec::new(),
            record,
            teleop: None,
        };
        controller.read_all()?;
        for arm in &mut controller.arms {
            arm.adopt_measured();
        }
        controller.publish();
        Ok(controller)
    }

    /// The cycle's period, s.
    pub fn period_s(&self) -> f64 {
        self.period_s
    }

    /// Where the controller stands.
    pub fn status(&self) -> Status {
        self.status
    }

    /// The last cycle's record (after [`Controller::new`], the first readings).
    pub fn record(&self) -> &CycleRecord {
        &self.record
    }

    /// Every event fired since the skill was loaded.
    pub fn fired_events(&self) -> &[FiredEvent] {
        &self.fired
    }

    /// The arms the controller drives, in order.
    pub fn arms(&self) -> impl Iterator<Item = ArmName> + '_ {
        self.arms.iter().map(ArmRuntime::name)
    }

    /// Turns teleoperation on (or off with `None`): while no skill runs and no emergency stop holds,
    /// each master steers its arm's instrument ([`teleop`]). Refuses bad settings.
    pub fn set_teleoperation(&mut self, settings: Option<TeleopSettings>) -> Result<(), ControllerError> {
        if let Some((field, reason)) = settings.as_ref().and_then(TeleopSettings::problem) {
            return Err(ControllerError::Setup(format!("teleoperation.{field}: {reason}")));
        }
        self.teleop = settings;
        for master in &mut self.masters {
            master.engaged = None;
        }
        Ok(())
    }

    /// Checks `skill` against the rig and makes it the one to run from skill time 0. Arms without a
    /// track hold. Refused while emergency-stopped or faulted.
    pub fn load_skill(&mut self, skill: Skill) -> Result<(), ControllerError> {
        if matches!(self.status, Status::EmergencyStopped | Status::Faulted) {
            return Err(ControllerError::NotRunning { status: self.status });
        }
        skill.check()?;
        for track in &skill.tracks {
            let Some(arm) = self.arms.iter().find(|a| a.name() == track.arm) else {
                return Err(ControllerError::SkillNeedsDevice {
                    arm: track.arm,
                    device: DeviceKind::ArmServo,
                    why: "the rig has no devices for this arm",
                });
            };
            if !track.jaw.is_empty() && arm.devices.instrument.is_none() {
                return Err(ControllerError::SkillNeedsDevice {
                    arm: track.arm,
                    device: DeviceKind::InstrumentDrive,
                    why: "the track moves the jaw",
                });
            }
            if !track.events.is_empty() && arm.devices.force.is_none() {
                return Err(ControllerError::SkillNeedsDevice {
                    arm: track.arm,
                    device: DeviceKind::ForceSensor,
                    why: "the track has force-triggered events",
                });
            }
        }
        for arm in &mut self.arms {
            let track = skill.tracks.iter().position(|t| t.arm == arm.name());
            let events = track.map_or(0, |t| skill.tracks[t].events.len());
            arm.reset_skill(track, events);
        }
        self.duration_s = skill.duration_s();
        self.skill = Some(skill);
        self.skill_time_s = 0.0;
        self.skill_cycle = 0;
        self.fired.clear();
        self.status = Status::Running;
        Ok(())
    }

    /// Clears a latched emergency stop once the pedal has been released (as the last cycle read it): the
    /// controller goes idle, the skill is dropped, every arm holds its set-point. Load a skill to move
    /// again.
    pub fn reset_emergency_stop(&mut self) -> Result<(), ControllerError> {
        if self.status != Status::EmergencyStopped {
            return Err(ControllerError::NotRunning { status: self.status });
        }
        if self.record.pedals.emergency_stop {
            return Err(ControllerError::EmergencyStopHeld);
        }
        self.skill = None;
        self.status = Status::Idle;
        self.record.status = Status::Idle;
        Ok(())
    }

    /// Runs one cycle and returns its record. After a fault the error is returned once and every later
    /// call returns [`ControllerError::NotRunning`].
    pub fn step(&mut self) -> Result<&CycleRecord, ControllerError> {
        if self.status == Status::Faulted {
            return Err(ControllerError::NotRunning { status: self.status });
        }
        match self.cycle_once() {
            Ok(()) => Ok(&self.record),
            Err(error) => {
                self.status = Status::Faulted;
                self.record.status = Status::Faulted;
                Err(error)
            }
        }
    }

    /// Runs cycles until the skill ends or the emergency stop halts it, showing each cycle's record to
    /// `observer`.
    pub fn run_to_end(
        &mut self,
        mut observer: impl FnMut(&CycleRecord),
    ) -> Result<RunSummary, ControllerError> {
        if self.skill.is_none() {
            return Err(ControllerError::NoSkill);
        }
        let start = self.cycle;
        loop {
            let record = self.step()?;
            observer(record);
            let outcome = match record.status {
                Status::Finished => RunOutcome::Completed,
                Status::EmergencyStopped => RunOutcome::EmergencyStopped,
                _ => continue,
            };
            return Ok(RunSummary { outcome, cycles: self.cycle - start, skill_time_s: self.skill_time_s });
        }
    }

    /// Ends every device's session (a MELFA driver sends END, a Net F/T driver stops its stream). The first error is returned after every
    /// device has been asked.
    pub fn shutdown(&mut self) -> Result<(), DeviceError> {
        let mut first = None;
        for arm in &mut self.arms {
            if let Err(e) = arm.devices.servo.shutdown() {
                first.get_or_insert(e);
            }
            if let Some(drive) = &mut arm.devices.instrument
                && let Err(e) = drive.shutdown()
            {
                first.get_or_insert(e);
            }
            if let Some(force) = &mut arm.devices.force
                && let Err(e) = force.shutdown()
            {
                first.get_or_insert(e);
            }
        }
        first.map_or(Ok(()), Err)
    }

    /// Link counters of an arm's servo, if its driver keeps them.
    pub fn link_stats(&self, arm: ArmName) -> Option<crate::device::LinkStats> {
        self.arms.iter().find(|a| a.name() == arm).and_then(|a| a.devices.servo.link_stats())
    }

    fn read_all(&mut self) -> Result<(), ControllerError> {
        let watchdog = self.params.watchdog_cycles;
        let pedals = self.pedals.read()?;
        if pedals.fresh {
            self.pedals_stale = 0;
            self.record.pedals = pedals;
        } else {
            self.pedals_stale += 1;
            if self.pedals_stale >= watchdog {
                return Err(ControllerError::Watchdog {
                    device: DeviceId::shared(DeviceKind::Pedals),
                    cycles: self.pedals_stale,
                    seconds: f64::from(self.pedals_stale) * self.period_s,
                });
            }
        }
        for arm in &mut self.arms {
            arm.read(watchdog, self.period_s)?;
        }
        for master in &mut self.masters {
            let state = master.device.read()?;
            if state.fresh {
                master.state = state;
                master.stale = 0;
            } else {
                master.stale += 1;
                if master.stale >= watchdog {
                    return Err(ControllerError::Watchdog {
                        device: DeviceId::of_arm(DeviceKind::Master, master.arm),
                        cycles: master.stale,
                        seconds: f64::from(master.stale) * self.period_s,
                    });
                }
            }
        }
        Ok(())
    }

    fn cycle_once(&mut self) -> Result<(), ControllerError> {
        self.read_all()?;
        self.record.time_s = self.cycle as f64 * self.period_s;
        // The pedal is honoured before anything is computed: this cycle writes nothing new.
        if self.record.pedals.emergency_stop {
            self.status = Status::EmergencyStopped;
        }
        let skill_cycle = self.status == Status::Running;
        if self.status == Status::Running
            && let Some(skill) = &self.skill
        {
            let time_s = self.skill_cycle as f64 * self.period_s;
            self.skill_time_s = time_s;
            // Events see the names fired in earlier cycles only: every arm's this cycle alike.
            let fired_names: Vec<(ArmName, String)> = self
                .fired
                .iter()
                .filter_map(|f| {
                    let track = skill.tracks.iter().find(|t| t.arm == f.arm)?;
                    Some((f.arm, track.events.get(f.event)?.name.clone()))
                })
                .collect();
            for arm in &mut self.arms {
                if let Some(t) = arm.track {
                    arm.compute(&skill.tracks[t], time_s, &mut self.fired, &fired_names)?;
                    arm.write()?;
                }
            }
            self.record.skill_time_s = time_s;
            // The last cycle is the first at or past the end (within round-off of the period).
            if time_s >= self.duration_s - 1e-9 * self.period_s {
                self.status = Status::Finished;
            } else {
                self.skill_cycle += 1;
            }
        }
        // The cycle that ends a skill is still the skill's: manual control takes over from the next.
        if skill_cycle {
            for master in &mut self.masters {
                master.engaged = None;
            }
        } else {
            self.teleoperate()?;
        }
        for master in &mut self.masters {
            let force = self
                .arms
                .iter()
                .find(|a| a.name() == master.arm)
                .map_or(nalgebra::Vector3::zeros(), |a| a.record.world_force_n);
            master
                .device
                .write(&ForceFeedback { console_force_n: force * self.params.force_feedback_scale })?;
        }
        self.clock.tick()?;
        self.cycle += 1;
        self.publish();
        Ok(())
    }

    /// One cycle of teleoperation: nothing while a skill runs or the emergency stop holds (the masters
    /// disengage, to engage afresh afterwards); otherwise each master steers its arm, held still while
    /// the clutch is pressed.
    fn teleoperate(&mut self) -> Result<(), ControllerError> {
        let Some(settings) = self.teleop else { return Ok(()) };
        let manual = matches!(self.status, Status::Idle | Status::Finished);
        let clutch = self.record.pedals.assignable[settings.clutch_pedal];
        let time_s = self.cycle as f64 * self.period_s;
        for master in &mut self.masters {
            let Some(arm) = self.arms.iter_mut().find(|a| a.name() == master.arm) else { continue };
            if !manual || clutch {
                master.engaged = None;
                continue;
            }
            let engaged = *master.engaged.get_or_insert(teleop::Engagement {
                console_from_handle: master.state.console_from_handle,
                world_from_tip: arm.record.world_from_tip,
            });
            let target = engaged.target(&settings, &master.state.console_from_handle);
            arm.command_target(target, Some(master.state.gripper_rad * settings.jaw_per_gripper), time_s)?;
            arm.write()?;
        }
        Ok(())
    }

    /// Copies the arms' records and the status into the cycle record.
    fn publish(&mut self) {
        for (slot, arm) in self.record.arms.iter_mut().zip(&self.arms) {
            *slot = arm.record;
        }
        self.record.cycle = self.cycle.saturating_sub(1);
        self.record.status = self.status;
    }
}
