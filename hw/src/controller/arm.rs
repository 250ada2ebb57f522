//! One arm inside the controller: its devices, set-point, readings, watchdog counters and event
//! states, and the per-cycle work (events, target, IK, step shaping, writes).

use nalgebra::{Rotation3, Vector3};

use crate::device::{ArmDevices, DeviceId, DeviceKind};
use crate::kinematics::{ArmJoints, ArmModel, JointLimit, TipTarget, Tool, ToolJoints};
use crate::rig::ArmName;
use crate::skill::{ForceAction, Track};

use super::error::ControllerError;
use super::record::{ArmRecord, FiredEvent};
use crate::arm_setup::ArmSetup;

/// The state of one event of the arm's track.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct EventState {
    /// Skill time it fired, s.
    fired_at_s: Option<f64>,
    /// Skill time since which the force has stayed at or above the threshold, s.
    above_since_s: Option<f64>,
    /// The tip target when it fired (for [`ForceAction::Hold`]).
    hold: Option<TipTarget>,
    /// How far the tip has given way from its track, world frame, m, and the skill time that was
    /// last updated, s (for [`ForceAction::Give`]).
    given_m: Vector3<f64>,
    given_at_s: Option<f64>,
}

impl EventState {
    /// One cycle of a [`ForceAction::Give`] at `time_s` under `world_force_n`: where the tip's offset
    /// from its track would go, m (taken by [`EventState::gave`] if the arm reaches it).
    fn give(
        &mut self,
        time_s: f64,
        world_force_n: &Vector3<f64>,
        set_force_n: f64,
        rate: f64,
    ) -> Vector3<f64> {
        let dt_s = self.given_at_s.map_or(0.0, |last| (time_s - last).max(0.0));
        self.given_at_s = Some(time_s);
        let force_n = world_force_n.norm();
        if force_n > set_force_n {
            self.given_m + world_force_n / force_n * (rate * (force_n - set_force_n) * dt_s)
        } else {
            let back_m = rate * (set_force_n - force_n) * dt_s;
            let given = self.given_m.norm();
            if given <= back_m { Vector3::zeros() } else { self.given_m * (1.0 - back_m / given) }
        }
    }

    /// The tip gave to `given_m` from its track.
    fn gave(&mut self, given_m: Vector3<f64>) {
        self.given_m = given_m;
    }
}

/// One arm in the controller.
pub(super) struct ArmRuntime {
    pub(super) setup: ArmSetup,
    pub(super) devices: ArmDevices,
    /// Largest step per cycle, per joint in [`ArmJoints::ORDER`], rad.
    max_step_rad: [f64; 10],
    /// Position limits per joint in [`ArmJoints::ORDER`].
    limits: [JointLimit; 10],
    pub(super) command: ArmJoints,
    pub(super) measured: ArmJoints,
    shaft_force_n: Vector3<f64>,
    /// Stale readings in a row: servo, instrument, force sensor.
    stale: [u32; 3],
    /// Index of the arm's track in the loaded skill.
    pub(super) track: Option<usize>,
    pub(super) events: Vec<EventState>,
    last_target: Option<TipTarget>,
    pub(super) record: ArmRecord,
}

fn joint_limits(model: &ArmModel) -> [JointLimit; 10] {
    let free = JointLimit::new(f64::NEG_INFINITY, f64::INFINITY, f64::INFINITY);
    let tool = match &model.tool {
        Tool::Instrument { limits, .. } => [limits.roll, limits.pitch, limits.yaw, limits.jaw],
        Tool::Endoscope { .. } => [free; 4],
    };
    std::array::from_fn(|i| if i < 6 { model.limits[i] } else { tool[i - 6] })
}

impl ArmRuntime {
    pub(super) fn new(setup: ArmSetup, devices: ArmDevices, period_s: f64, speed_scale: f64) -> Self {
        let limits = joint_limits(&setup.model);
        let max_step_rad = limits.map(|l| l.max_velocity_rad_s * speed_scale * period_s);
        let record = ArmRecord {
            arm: setup.arm,
            measured: ArmJoints::default(),
            commanded: ArmJoints::default(),
            wrote: false,
            world_from_tip: setup.model.world_from_tip(&ArmJoints::default()),
            target: None,
            shaft_force_n: Vector3::zeros(),
            world_force_n: Vector3::zeros(),
            fresh: true,
            clamped: false,
        };
        Self {
            setup,
            devices,
            max_step_rad,
            limits,
            command: ArmJoints::default(),
            measured: ArmJoints::default(),
            shaft_force_n: Vector3::zeros(),
            stale: [0; 3],
            track: None,
            events: Vec::new(),
            last_target: None,
            record,
        }
    }

    pub(super) fn name(&self) -> ArmName {
        self.setup.arm
    }

    fn watchdog(
        stale: &mut u32,
        fresh: bool,
        device: DeviceId,
        limit: u32,
        period_s: f64,
    ) -> Result<(), ControllerError> {
        if fresh {
            *stale = 0;
            return Ok(());
        }
        *stale += 1;
        if *stale >= limit {
            return Err(ControllerError::Watchdog {
                device,
                cycles: *stale,
                seconds: f64::from(*stale) * period_s,
            });
        }
        Ok(())
    }

    /// Reads every device of the arm; stale readings keep the previous values and count towards the
    /// watchdog.
    pub(super) fn read(&mut self, watchdog: u32, period_s: f64) -> Result<(), ControllerError> {
        let arm = self.name();
        let servo = self.devices.servo.read()?;
        if servo.fresh {
            self.measured.arm_rad = servo.joints_rad;
        }
        let mut fresh = servo.fresh;
        let id = |kind| DeviceId::of_arm(kind, arm);
        Self::watchdog(&mut self.stale[0], servo.fresh, id(DeviceKind::ArmServo), watchdog, period_s)?;
        if let Some(drive) = &mut self.devices.instrument {
            let state = drive.read()?;
            if state.fresh {
                self.measured.tool = state.joints;
            }
            fresh &= state.fresh;
            Self::watchdog(
                &mut self.stale[1],
                state.fresh,
                id(DeviceKind::InstrumentDrive),
                watchdog,
                period_s,
            )?;
        }
        if let Some(sensor) = &mut self.devices.force {
            let reading = sensor.read()?;
            if reading.fresh {
                self.shaft_force_n = reading.shaft_force_n;
            }
            fresh &= reading.fresh;
            Self::watchdog(
                &mut self.stale[2],
                reading.fresh,
                id(DeviceKind::ForceSensor),
                watchdog,
                period_s,
            )?;
        }
        let model = &self.setup.model;
        let world_from_shaft_rotation = model.world_from_flange(&self.measured).rotation
            * Rotation3::from_axis_angle(&Vector3::z_axis(), self.measured.tool.roll_rad);
        let r = &mut self.record;
        r.measured = self.measured;
        r.world_from_tip = model.world_from_tip(&self.measured);
        r.shaft_force_n = self.shaft_force_n;
        r.world_force_n = world_from_shaft_rotation * self.shaft_force_n;
        r.fresh = fresh;
        r.wrote = false;
        r.clamped = false;
        r.target = None;
        r.commanded = self.command;
        Ok(())
    }

    /// Takes the measured joints as the set-point (at start, before any command).
    pub(super) fn adopt_measured(&mut self) {
        self.command = self.measured;
        if self.devices.instrument.is_none() {
            self.command.tool = ToolJoints::default();
        }
        self.record.commanded = self.command;
    }

    /// The set-point for skill time `time_s` from the arm's track: events, interpolated target, IK
    /// seeded with the last set-point, the step clamped to the joints' speed. Fired events are pushed;
    /// `fired_names` holds the names of the events other tracks fired before this cycle (for
    /// [`crate::skill::ForceEvent::fires_with`]).
    pub(super) fn compute(
        &mut self,
        track: &Track,
        time_s: f64,
        fired: &mut Vec<FiredEvent>,
        fired_names: &[(ArmName, String)],
    ) -> Result<(), ControllerError> {
        let arm = self.name();
        let force_n = self.shaft_force_n.norm();
        let world_force_n = self.record.world_force_n;
        let mut target = track.target_at(time_s);
        let mut jaw = track.jaw_at(time_s);
        for (i, (event, state)) in track.events.iter().zip(&mut self.events).enumerate() {
            let inside = event.from_s <= time_s && time_s <= event.until_s;
            state.above_since_s = if inside && force_n >= event.threshold_n {
                state.above_since_s.or(Some(time_s))
            } else {
                None
            };
            let sustained =
                state.above_since_s.is_some_and(|since| time_s - since >= event.sustain_s - 1e-12);
            let joined = inside
                && event.fires_with.as_ref().is_some_and(|name| {
                    fired_names
                        .iter()
                        .any(|(other, fired)| fired == name && (*other != arm || *name != event.name))
                });
            if state.fired_at_s.is_none() && (sustained || joined) {
                state.fired_at_s = Some(time_s);
                state.hold = self.last_target.or(target);
                fired.push(FiredEvent { arm, event: i, time_s, force_n });
            }
            if state.fired_at_s.is_some() && inside {
                match event.action {
                    ForceAction::OpenJaw { jaw_rad } => jaw = Some(jaw_rad),
                    ForceAction::Hold => target = state.hold.or(target),
                    ForceAction::Give { set_force_n, rate_m_per_n_s } => {
                        // The tip gives only as far as the arm reaches: where the track and the
                        // offset wanted lie beyond, it stops where it was (giving no further and
                        // going no further along its track) until the pull eases.
                        let wanted_m = state.give(time_s, &world_force_n, set_force_n, rate_m_per_n_s);
                        if let Some(t) = &mut target {
                            let mut given = *t;
                            given.world_position_m += wanted_m;
                            let reaches = self
                                .setup
                                .model
                                .solve_tip(&given, &self.setup.world_trocar_m, &self.command)
                                .is_ok();
                            match self.last_target {
                                Some(last) if !reaches => {
                                    state.gave(last.world_position_m - t.world_position_m)
                                }
                                _ => state.gave(wanted_m),
                            }
                            t.world_position_m += state.given_m;
                        }
                    }
                }
            }
        }
        let Some(target) = target else { return Ok(()) };
        self.command_target(target, jaw, time_s)
    }

    /// Solves the IK for `target` (the jaw at `jaw`, or as it is) and takes one speed-limited step
    /// towards it as the new set-point (written by [`ArmRuntime::write`]).
    pub(super) fn command_target(
        &mut self,
        target: TipTarget,
        jaw: Option<f64>,
        time_s: f64,
    ) -> Result<(), ControllerError> {
        let arm = self.name();
        let mut solved = self
            .setup
            .model
            .solve_tip(&target, &self.setup.world_trocar_m, &self.command)
            .map_err(|source| ControllerError::Ik { arm, time_s, source })?;
        if self.devices.instrument.is_some() {
            solved.tool.jaw_rad = jaw.unwrap_or(self.command.tool.jaw_rad);
        } else {
            solved.tool = ToolJoints::default();
        }
        let (shaped, clamped) = self.shape(&solved);
        self.command = shaped;
        self.last_target = Some(target);
        self.record.target = Some(target);
        self.record.clamped = clamped;
        Ok(())
    }

    /// Moves from the set-point towards `wanted` by at most one cycle's step per joint, inside the
    /// position limits. Returns the new set-point and whether any joint was held back.
    fn shape(&self, wanted: &ArmJoints) -> (ArmJoints, bool) {
        let now = self.command.to_array();
        let want = wanted.to_array();
        let mut clamped = false;
        let next: [f64; 10] = std::array::from_fn(|i| {
            let step = want[i] - now[i];
            let max = self.max_step_rad[i];
            let limited = step.clamp(-max, max);
            clamped |= limited != step;
            (now[i] + limited).clamp(self.limits[i].lower_rad, self.limits[i].upper_rad)
        });
        (ArmJoints::from_array(next), clamped)
    }

    /// Writes the set-point to the arm's servo and instrument drive.
    pub(super) fn write(&mut self) -> Result<(), ControllerError> {
        self.devices.servo.write(&self.command.arm_rad)?;
        if let Some(drive) = &mut self.devices.instrument {
            drive.write(&self.command.tool)?;
        }
        self.record.wrote = true;
        self.record.commanded = self.command;
        Ok(())
    }

    /// Forgets the events and target of a previous skill.
    pub(super) fn reset_skill(&mut self, track: Option<usize>, events: usize) {
        self.track = track;
        self.events = vec![EventState::default(); events];
        self.last_target = None;
    }
}
