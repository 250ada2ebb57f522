//! The controller on a rig of dummy devices: a skill runs to its end on its targets; the emergency
//! stop halts motion within one cycle and holds; the watchdog faults a run whose device goes stale;
//! force-triggered events open the jaw or hold the tip, and fire with another track's; unreachable
//! targets and unusable skills are refused with typed errors.

use super::rigs;

use knotlab_hw::controller::{ArmSetup, Controller, ControllerError, ControllerParams, RunOutcome, Status};
use knotlab_hw::device::dummy::{
    DummyArmServo, DummyForceSensor, DummyInstrumentDrive, DummyPedals, ForceHandle, VirtualClock,
};
use knotlab_hw::device::{
    ArmDevices, DeviceError, DeviceId, DeviceKind, DeviceSet, ForceReading, ForceSensor,
};
use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceAction, ForceEvent, JawKey, Orientation, PoseKey, Skill, Track};
use nalgebra::Vector3;

use rigs::{dummy_controller, parked, reach_skill, setup, trocar};

const PERIOD_S: f64 = 0.001;

fn max_abs_diff(a: &ArmJoints, b: &ArmJoints) -> f64 {
    a.to_array().iter().zip(b.to_array()).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max)
}

/// A 2 s skill completes in 2001 cycles, no axis stepping faster than half its rated speed and every
/// commanded tip on its target; the arm ends at the last target with the jaw at 0.2 rad.
#[test]
fn a_skill_runs_to_its_end_on_its_targets() {
    let arm = ArmName::Left;
    let (start_joints, start) = parked(arm);
    let (mut controller, _, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let offset = Vector3::new(0.02, -0.01, -0.015);
    let skill = reach_skill(arm, start, offset, 2.0);
    let last_target = skill.tracks[0].target_at(2.0).unwrap();
    controller.load_skill(skill).unwrap();
    let model = rigs::rig().arm(arm).model;
    let limits = model.limits;
    let mut previous = start_joints;
    let mut cycles = 0;
    let mut worst_tracking_m: f64 = 0.0;
    let summary = controller
        .run_to_end(|record| {
            let a = record.arm(arm).expect("the arm's record");
            // Never faster than half the rated speed (the default speed_scale).
            for (i, limit) in limits.iter().enumerate() {
                let step = (a.commanded.arm_rad[i] - previous.arm_rad[i]).abs();
                assert!(
                    step <= 0.5 * limit.max_velocity_rad_s * PERIOD_S + 1e-12,
                    "axis {} stepped {step}",
                    i + 1
                );
            }
            previous = a.commanded;
            if let Some(target) = a.target {
                // The tip the command puts there is on the target (no clamping on this gentle path).
                let tip = model.world_from_tip(&a.commanded).translation.vector;
                worst_tracking_m = worst_tracking_m.max((tip - target.world_position_m).norm());
            }
            cycles += 1;
        })
        .unwrap();
    assert_eq!(summary.outcome, RunOutcome::Completed);
    assert_eq!(summary.cycles, 2001, "2 s at 1 ms: cycles at 0, 1, ..., 2000 ms");
    assert!(worst_tracking_m < 1e-9, "commanded tips stray {worst_tracking_m} m from the targets");
    // The dummy arm reached the last target, jaw closed to 0.2 rad.
    let record = controller.step().unwrap();
    let a = record.arm(arm).unwrap();
    assert_eq!(record.status, Status::Finished);
    assert!((a.world_from_tip.translation.vector - last_target.world_position_m).norm() < 1e-9);
    assert!((a.measured.tool.jaw_rad - 0.2).abs() < 1e-12, "{}", a.measured.tool.jaw_rad);
    assert!((a.world_from_tip.translation.vector - (start + offset)).norm() < 1e-9);
}

/// The emergency stop writes no new set-point in the cycle after the press and holds the arm still even
/// with the pedal released; new skills are refused until it is reset, and the arm then holds.
#[test]
fn the_emergency_stop_halts_motion_within_one_cycle_and_holds() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, pedals, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    controller.load_skill(reach_skill(arm, start, Vector3::new(0.03, 0.0, -0.02), 1.0)).unwrap();
    let mut moving = 0.0;
    for _ in 0..400 {
        let before = controller.record().arm(arm).unwrap().measured;
        let record = controller.step().unwrap();
        moving = max_abs_diff(&record.arm(arm).unwrap().measured, &before);
    }
    assert!(moving > 1e-5, "the arm is moving when the pedal is pressed ({moving} rad per cycle)");
    let held = controller.record().arm(arm).unwrap().commanded;
    pedals.set_emergency_stop(true);
    // The first cycle after the press writes nothing new: the set-point is the one before.
    let record = controller.step().unwrap();
    assert_eq!(record.status, Status::EmergencyStopped);
    let a = record.arm(arm).unwrap();
    assert!(!a.wrote);
    assert_eq!(a.commanded, held);
    // From the next reading on the arm stands still, and stays so even with the pedal released.
    let stopped = controller.step().unwrap().arm(arm).unwrap().measured;
    assert_eq!(stopped, held, "the dummy arm stands at the last set-point");
    pedals.set_emergency_stop(false);
    for _ in 0..200 {
        let record = controller.step().unwrap();
        assert_eq!(record.status, Status::EmergencyStopped, "the stop is latched");
        assert_eq!(record.arm(arm).unwrap().measured, stopped);
    }
    // A new skill is refused while stopped.
    let error = controller.load_skill(reach_skill(arm, start, Vector3::zeros(), 0.1)).unwrap_err();
    assert!(matches!(error, ControllerError::NotRunning { status: Status::EmergencyStopped }), "{error}");
    // Released, the stop can be cleared; the arm holds until a new skill comes.
    controller.reset_emergency_stop().unwrap();
    assert_eq!(controller.status(), Status::Idle);
    let record = controller.step().unwrap();
    assert_eq!((record.status, record.arm(arm).unwrap().measured), (Status::Idle, stopped));
    controller.load_skill(reach_skill(arm, start, Vector3::zeros(), 0.1)).unwrap();
    assert_eq!(controller.status(), Status::Running);
}

/// Resetting the emergency stop is refused when none is latched, and while the pedal is still pressed,
/// which leaves the controller stopped.
#[test]
fn an_emergency_stop_is_not_cleared_while_the_pedal_is_pressed() {
    let arm = ArmName::Left;
    let (mut controller, pedals, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let error = controller.reset_emergency_stop().unwrap_err();
    assert!(matches!(error, ControllerError::NotRunning { status: Status::Idle }), "{error}");
    pedals.set_emergency_stop(true);
    assert_eq!(controller.step().unwrap().status, Status::EmergencyStopped);
    let error = controller.reset_emergency_stop().unwrap_err();
    assert!(matches!(error, ControllerError::EmergencyStopHeld), "{error}");
    assert_eq!(controller.status(), Status::EmergencyStopped);
}

/// A run stopped by the pedal reports an emergency stop as its outcome, ending in the cycle after the press.
#[test]
fn run_to_end_reports_an_emergency_stop() {
    let arm = ArmName::Right;
    let (_, start) = parked(arm);
    let (mut controller, pedals, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    controller.load_skill(reach_skill(arm, start, Vector3::new(0.0, 0.02, -0.02), 1.0)).unwrap();
    let mut cycles = 0;
    let summary = controller
        .run_to_end(|_| {
            cycles += 1;
            if cycles == 250 {
                pedals.set_emergency_stop(true);
            }
        })
        .unwrap();
    assert_eq!(summary.outcome, RunOutcome::EmergencyStopped);
    assert_eq!(summary.cycles, 251, "stopped in the cycle after the press");
}

/// A force sensor that answers with stale readings from cycle `fresh_for` on.
struct GoesStale {
    reads: u32,
    fresh_for: u32,
}

impl ForceSensor for GoesStale {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        self.reads += 1;
        Ok(ForceReading { shaft_force_n: Vector3::zeros(), fresh: self.reads <= self.fresh_for })
    }
}

/// A force sensor whose bus times out at read `fail_at`.
struct TimesOut {
    reads: u32,
    fail_at: u32,
}

impl ForceSensor for TimesOut {
    fn read(&mut self) -> Result<ForceReading, DeviceError> {
        self.reads += 1;
        if self.reads >= self.fail_at {
            let device = DeviceId::of_arm(DeviceKind::ForceSensor, ArmName::Left);
            return Err(DeviceError::Timeout { device, waited_s: 0.002 });
        }
        Ok(ForceReading::default())
    }
}

fn controller_with_force(sensor: Box<dyn ForceSensor>, params: ControllerParams) -> Controller {
    let arm = ArmName::Left;
    let (joints, _) = parked(arm);
    let devices = DeviceSet {
        arms: vec![(
            arm,
            ArmDevices {
                servo: Box::new(DummyArmServo::new(joints.arm_rad)),
                instrument: None,
                force: Some(sensor),
            },
        )],
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(PERIOD_S)),
    };
    Controller::new(devices, &[setup(arm)], params).expect("the dummy rig starts")
}

/// A force sensor whose readings go stale faults the run at the watchdog's 25th stale cycle, naming the
/// device, cycles and seconds; the faulted controller refuses further steps.
#[test]
fn the_watchdog_faults_a_run_whose_device_goes_stale() {
    let params = ControllerParams { watchdog_cycles: 25, ..ControllerParams::default() };
    // Fresh for the first read (at start) and 10 cycles, then stale.
    let mut controller = controller_with_force(Box::new(GoesStale { reads: 0, fresh_for: 11 }), params);
    let mut cycles = 0;
    let error = loop {
        match controller.step() {
            Ok(record) => {
                assert!(record.arm(ArmName::Left).unwrap().fresh == (cycles < 10), "cycle {cycles}");
                cycles += 1;
            }
            Err(e) => break e,
        }
    };
    assert_eq!(cycles, 10 + 24, "24 stale cycles pass, the 25th faults");
    match error {
        ControllerError::Watchdog { device, cycles, seconds } => {
            assert_eq!(device, DeviceId::of_arm(DeviceKind::ForceSensor, ArmName::Left));
            assert_eq!(cycles, 25);
            assert!((seconds - 0.025).abs() < 1e-12);
        }
        other => panic!("expected the watchdog, got {other}"),
    }
    assert_eq!(controller.status(), Status::Faulted);
    assert!(matches!(controller.step(), Err(ControllerError::NotRunning { status: Status::Faulted })));
}

/// A force sensor's bus time-out faults the run in that same cycle, the error naming the left force sensor.
#[test]
fn a_device_time_out_faults_the_run_at_once() {
    let mut controller =
        controller_with_force(Box::new(TimesOut { reads: 0, fail_at: 6 }), ControllerParams::default());
    for _ in 0..4 {
        controller.step().unwrap();
    }
    let error = controller.step().unwrap_err();
    assert!(matches!(error, ControllerError::Device(DeviceError::Timeout { .. })), "{error}");
    assert!(error.to_string().contains("left force sensor: no answer within"), "{error}");
    assert_eq!(controller.status(), Status::Faulted);
}

fn hold_still_skill(arm: ArmName, start: Vector3<f64>, events: Vec<ForceEvent>) -> Skill {
    let (_, _) = parked(arm);
    let key = |time_s: f64, p: Vector3<f64>| PoseKey {
        time_s,
        world_position_m: p.into(),
        orientation: Orientation::AlongShaft,
    };
    Skill {
        name: "press and release".into(),
        tracks: vec![Track {
            arm,
            poses: vec![key(0.0, start), key(1.0, start + Vector3::new(0.0, 0.0, -0.02))],
            jaw: vec![JawKey { time_s: 0.0, jaw_rad: 0.0 }],
            events,
        }],
    }
}

/// An open-jaw force event opens the jaw within a cycle or two of the pull reaching its threshold, fires
/// once, and the jaw track takes over again once the event's window closes.
#[test]
fn a_force_event_opens_the_jaw_when_the_threshold_is_crossed() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let event = ForceEvent {
        name: "release on pull".into(),
        from_s: 0.2,
        until_s: 0.8,
        threshold_n: 1.5,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::OpenJaw { jaw_rad: 0.5 },
    };
    controller.load_skill(hold_still_skill(arm, start, vec![event])).unwrap();
    let mut opened_at = None;
    let mut last_jaw = f64::INFINITY;
    for cycle in 0..=1000 {
        // The pull grows from 0 N at 0.1 s by 5 N/s: it reaches 1.5 N at 0.4 s.
        let t = cycle as f64 * PERIOD_S;
        force.set(Vector3::new(0.0, 0.0, (5.0 * (t - 0.1)).max(0.0)));
        let record = controller.step().unwrap();
        let jaw = record.arm(arm).unwrap().commanded.tool.jaw_rad;
        // The jaw closes from the parked 0.6 rad; the event turns it round.
        if opened_at.is_none() && jaw > last_jaw {
            opened_at = Some(record.skill_time_s);
        }
        last_jaw = jaw;
        if record.skill_time_s > 0.8 + 1e-9 {
            // The window closed: the jaw track (closed) takes over again.
            assert!(jaw < 0.5, "jaw {jaw} at {}", record.skill_time_s);
        }
    }
    let opened_at = opened_at.expect("the jaw opened");
    assert!((opened_at - 0.4).abs() < 1.5 * PERIOD_S, "opened at {opened_at} s");
    let fired = controller.fired_events();
    assert_eq!(fired.len(), 1, "fires once");
    assert_eq!((fired[0].arm, fired[0].event), (arm, 0));
    assert!(fired[0].force_n >= 1.5 && fired[0].force_n < 1.5 + 5.0 * PERIOD_S + 1e-9);
}

/// An event linked by `fires_with` to another of its own track fires in the first cycle of its
/// window after that one fired (a pull held at its force lets go later): the hold at 1.2 N from
/// 0.3 s, the opening at 0.6 s, its window's start; without the hold it does not fire at all.
#[test]
fn an_event_that_fires_with_one_of_its_own_track_fires_when_its_window_opens() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let events = vec![
        ForceEvent {
            name: "stop".into(),
            from_s: 0.0,
            until_s: 0.9,
            threshold_n: 1.0,
            sustain_s: 0.0,
            fires_with: None,
            action: ForceAction::Hold,
        },
        ForceEvent {
            name: "let go".into(),
            from_s: 0.6,
            until_s: 0.9,
            threshold_n: 100.0,
            sustain_s: 0.0,
            fires_with: Some("stop".into()),
            action: ForceAction::OpenJaw { jaw_rad: 0.5 },
        },
    ];
    let run = |pull_n: f64| {
        let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
        controller.load_skill(hold_still_skill(arm, start, events.clone())).unwrap();
        for cycle in 0..=900 {
            let t = cycle as f64 * PERIOD_S;
            force.set(Vector3::new(0.0, 0.0, if t >= 0.3 { pull_n } else { 0.0 }));
            controller.step().unwrap();
        }
        controller.fired_events().iter().map(|f| (f.event, f.time_s)).collect::<Vec<_>>()
    };
    let fired = run(1.2);
    assert_eq!(fired.len(), 2, "{fired:?}");
    assert_eq!(fired[0].0, 0);
    assert!((fired[0].1 - 0.301).abs() < 1.5 * PERIOD_S, "held at {fired:?}");
    assert_eq!(fired[1].0, 1);
    assert!((fired[1].1 - 0.6).abs() < 1.5 * PERIOD_S, "let go at {fired:?}");
    assert!(run(0.5).is_empty(), "no hold, no letting go");
}

/// A force event with a 50 ms sustain ignores a 30 ms spike over its threshold and fires once, 50 ms into
/// the sustained pull.
#[test]
fn a_force_event_with_a_sustain_ignores_a_shorter_spike() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let event = ForceEvent {
        name: "release on a sustained pull".into(),
        from_s: 0.0,
        until_s: 0.9,
        threshold_n: 1.0,
        sustain_s: 0.05,
        fires_with: None,
        action: ForceAction::OpenJaw { jaw_rad: 0.5 },
    };
    controller.load_skill(hold_still_skill(arm, start, vec![event])).unwrap();
    for cycle in 0..=900 {
        let t = cycle as f64 * PERIOD_S;
        // A 30 ms spike of 2 N at 0.2 s, then 1.2 N from 0.5 s on.
        let f = if (0.2..0.23).contains(&t) {
            2.0
        } else if t >= 0.5 {
            1.2
        } else {
            0.0
        };
        force.set(Vector3::new(f, 0.0, 0.0));
        controller.step().unwrap();
    }
    let fired = controller.fired_events();
    assert_eq!(fired.len(), 1, "fires once: {fired:?}");
    // Not at the spike: 50 ms into the sustained pull (give or take the gauge's one-cycle lag).
    assert!((fired[0].time_s - 0.55).abs() < 2.5 * PERIOD_S, "fired at {} s", fired[0].time_s);
}

/// A hold event keeps the tip's target where it was when the force crossed the threshold, for the rest
/// of the event's window, instead of following the skill's path on down.
#[test]
fn a_hold_event_stops_the_tip_until_its_window_closes() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let event = ForceEvent {
        name: "stop on contact".into(),
        from_s: 0.0,
        until_s: 0.7,
        threshold_n: 0.5,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::Hold,
    };
    controller.load_skill(hold_still_skill(arm, start, vec![event])).unwrap();
    let mut held_tip = None;
    for cycle in 0..700 {
        if cycle == 300 {
            force.set(Vector3::new(0.8, 0.0, 0.0));
        }
        let record = controller.step().unwrap();
        let target = record.arm(arm).unwrap().target.expect("a target").world_position_m;
        if record.skill_time_s >= 0.301 {
            let held = *held_tip.get_or_insert(target);
            assert_eq!(target, held, "the target stays where it was at {}", record.skill_time_s);
        }
    }
    let held = held_tip.expect("the hold started");
    // Held at the target of 0.3 s: 0.3 of the way down by linear interpolation.
    assert!((held.z - (start.z - 0.02 * 0.3)).abs() < 1e-9 + 0.02 * PERIOD_S, "{held:?}");
}

/// [`hold_still_skill`] held on to `end_s`, with one give event from the start to `until_s`; and
/// where its track holds still from 1 s.
fn give_skill(
    arm: ArmName,
    start: Vector3<f64>,
    set_force_n: f64,
    rate_m_per_n_s: f64,
    until_s: f64,
    end_s: f64,
) -> (Skill, Vector3<f64>) {
    let event = ForceEvent {
        name: "keep the tension".into(),
        from_s: 0.0,
        until_s,
        threshold_n: set_force_n,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::Give { set_force_n, rate_m_per_n_s },
    };
    let mut skill = hold_still_skill(arm, start, vec![event]);
    let last = skill.tracks[0].poses[1];
    skill.tracks[0].poses.push(PoseKey { time_s: end_s, ..last });
    (skill, start + Vector3::new(0.0, 0.0, -0.02))
}

/// A give event moves the tip off its track along the force while the gauge reads more than the set
/// force, at the rate per newton over it, and back towards the track while it reads less; once the
/// window closes, or the offset is spent, the target is the track's again. (The track holds still
/// from 1 s; the pull is 1.5 N from 1.0 to 1.3 s against a set force of 0.5 N.)
#[test]
fn a_give_event_yields_along_the_pull_over_its_set_force_and_comes_back_under_it() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let (set_force_n, rate_m_per_n_s) = (0.5, 0.01);
    let (skill, track) = give_skill(arm, start, set_force_n, rate_m_per_n_s, 2.5, 3.0);
    controller.load_skill(skill).unwrap();
    let mut pull_world = None;
    // How far the tip is off its track along the last pull read, and across it, m.
    let along_pull = |given_m: Vector3<f64>, pull: Option<Vector3<f64>>| {
        let pull = pull.expect("the pull was read").normalize();
        let along = given_m.dot(&pull);
        (along, (given_m - pull * along).norm())
    };
    let mut checked = 0;
    for cycle in 0..=3000 {
        let t = cycle as f64 * PERIOD_S;
        let pulling = (1.0..1.3).contains(&(t + 1e-9));
        force.set(if pulling { Vector3::new(1.5, 0.0, 0.0) } else { Vector3::zeros() });
        let record = controller.step().unwrap();
        let arm_record = record.arm(arm).unwrap();
        if pulling {
            pull_world = Some(arm_record.world_force_n);
        }
        let given_m = arm_record.target.expect("a target").world_position_m - track;
        let time_s = record.skill_time_s;
        if (time_s - 1.3).abs() < 1e-9 {
            // 0.3 s at 1.0 N over: 3 mm along the pull (the first cycle's pull starts the clock).
            let (along, across) = along_pull(given_m, pull_world);
            assert!((along - 0.003).abs() < 2.0 * rate_m_per_n_s * PERIOD_S, "{along} m at {time_s} s");
            // (The shaft pivots in its trocar as the tip gives: the pull, fixed in the shaft's
            // frame, turns with it, a few percent over 3 mm.)
            assert!(across < 0.05 * along, "{across} m across the pull");
            checked += 1;
        }
        if (time_s - 1.6).abs() < 1e-9 {
            // Coming back at 0.5 N under: 5 mm/s, half way after 0.3 s.
            let (along, _) = along_pull(given_m, pull_world);
            assert!((along - 0.0015).abs() < 2.0 * rate_m_per_n_s * PERIOD_S, "{along} m at {time_s} s");
            checked += 1;
        }
        if time_s > 1.95 {
            // Back on its track, inside the window and after it.
            assert!(given_m.norm() < 1e-9, "{} m off at {time_s} s", given_m.norm());
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} cycles checked");
    assert_eq!(controller.fired_events().len(), 1, "fires once");
}

/// A give never takes the tip past the arm's reach: pulled deeper along its shaft far harder than its
/// set force while its track goes down too, the tip gives as deep as the instrument reaches and stops
/// there, its track held as well, instead of faulting the run; once the pull stops it comes back up
/// to its track.
#[test]
fn a_give_stops_at_the_arms_reach_and_comes_back() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, force) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    // The track goes 2 cm down in the first second, then holds.
    let (skill, track) = give_skill(arm, start, 2.0, 0.05, 6.0, 6.0);
    controller.load_skill(skill).unwrap();
    let deeper = (track - trocar(arm)).normalize();
    let mut deepest_m: f64 = 0.0;
    for cycle in 0..=6000 {
        let t = cycle as f64 * PERIOD_S;
        // 10 N along the shaft from 0.1 s to 2 s: 0.4 m/s of give, 0.76 m in all were it free, at
        // the reach's end while the track still goes down.
        let pulling = (0.1..2.0).contains(&(t + 1e-9));
        force.set(if pulling { Vector3::new(0.0, 0.0, 10.0) } else { Vector3::zeros() });
        let record = controller.step().expect("no fault: the give stops at the reach");
        let arm_record = record.arm(arm).unwrap();
        let target = arm_record.target.expect("a target").world_position_m;
        if pulling && t > 0.2 {
            let shaft = (arm_record.world_from_tip.translation.vector - trocar(arm)).normalize();
            let along = arm_record.world_force_n.normalize().dot(&shaft);
            assert!(along > 0.9, "the pull is along the shaft, deeper ({along} at {t} s)");
        }
        if t > 1.0 {
            deepest_m = deepest_m.max((target - track).dot(&deeper));
        }
        if t > 5.9 {
            // 2 N under the set force: 0.1 m/s back, on the track within 2 s.
            assert!((target - track).norm() < 1e-9, "{} m off its track at {t} s", (target - track).norm());
        }
    }
    assert!(deepest_m > 0.05, "gave only {deepest_m} m");
}

/// Both instruments of the surgeon's pulls on dummy devices, each with its own force handle.
fn two_arm_controller() -> (Controller, [ForceHandle; 2]) {
    let sensors = [DummyForceSensor::new(), DummyForceSensor::new()];
    let handles = [sensors[0].handle(), sensors[1].handle()];
    let arms = [ArmName::Left, ArmName::Right];
    let devices = DeviceSet {
        arms: arms
            .into_iter()
            .zip(sensors)
            .map(|(arm, force)| {
                let (joints, _) = parked(arm);
                let devices = ArmDevices {
                    servo: Box::new(DummyArmServo::new(joints.arm_rad)),
                    instrument: Some(Box::new(DummyInstrumentDrive::new(joints.tool))),
                    force: Some(Box::new(force) as Box<dyn ForceSensor>),
                };
                (arm, devices)
            })
            .collect(),
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(PERIOD_S)),
    };
    let setups = arms.map(setup);
    let controller =
        Controller::new(devices, &setups, ControllerParams::default()).expect("the dummy rig starts");
    (controller, handles)
}

/// An event linked by `fires_with` holds the other arm a cycle after the first arm's force fires it;
/// unlinked, the other pulls on to its end; a link to a name no other track has is refused naming the field.
#[test]
fn an_event_that_fires_with_another_stops_both_pulls_at_the_first_force() {
    let set_force = |fires_with: &str| ForceEvent {
        name: "set force".into(),
        from_s: 0.0,
        until_s: 0.9,
        threshold_n: 1.0,
        sustain_s: 0.0,
        fires_with: Some(fires_with.into()),
        action: ForceAction::Hold,
    };
    let track = |arm: ArmName| {
        let (_, start) = parked(arm);
        let mut skill = hold_still_skill(arm, start, vec![set_force("set force")]);
        skill.tracks.remove(0)
    };
    let skill =
        Skill { name: "pull apart".into(), tracks: vec![track(ArmName::Left), track(ArmName::Right)] };
    let (mut controller, [left_force, right_force]) = two_arm_controller();
    controller.load_skill(skill.clone()).unwrap();
    let mut held = [None, None];
    for cycle in 0..900 {
        // The left's thread tightens at 0.3 s; the right's never reads more than 0.2 N.
        if cycle == 300 {
            left_force.set(Vector3::new(1.2, 0.0, 0.0));
        }
        right_force.set(Vector3::new(0.0, 0.2, 0.0));
        let record = controller.step().unwrap();
        for (k, arm) in [ArmName::Left, ArmName::Right].into_iter().enumerate() {
            let target = record.arm(arm).unwrap().target.expect("a target").world_position_m;
            // The left holds from the cycle it reads its force (0.301 s, the gauge a cycle behind), the
            // right from the next.
            if record.skill_time_s >= 0.302 + k as f64 * PERIOD_S - 1e-9 {
                assert_eq!(target, *held[k].get_or_insert(target), "{arm} at {}", record.skill_time_s);
            }
        }
    }
    let fired: Vec<_> = controller.fired_events().iter().map(|f| (f.arm, f.time_s)).collect();
    assert_eq!(fired.len(), 2, "{fired:?}");
    assert_eq!(fired[0].0, ArmName::Left);
    assert_eq!(fired[1].0, ArmName::Right);
    assert!((fired[1].1 - fired[0].1 - PERIOD_S).abs() < 1e-9, "the right a cycle after the left: {fired:?}");
    // Without the link the right pulls on to its target.
    let (mut controller, [left_force, _]) = two_arm_controller();
    let mut alone = skill;
    alone.tracks[1].events[0].fires_with = None;
    controller.load_skill(alone).unwrap();
    left_force.set(Vector3::new(1.2, 0.0, 0.0));
    let summary = controller.run_to_end(|_| ()).unwrap();
    assert_eq!(summary.outcome, RunOutcome::Completed);
    assert_eq!(controller.fired_events().len(), 1);
    // A link to a name no other track has is refused, naming the field.
    let (mut controller, _) = two_arm_controller();
    let mut dangling =
        Skill { name: "pull apart".into(), tracks: vec![track(ArmName::Left), track(ArmName::Right)] };
    dangling.tracks[0].events[0].fires_with = Some("set farce".into());
    let text = controller.load_skill(dangling).unwrap_err().to_string();
    assert!(
        text.contains(
            "tracks[0].events[0].fires_with: no other event (of this track or another) is named \"set farce\""
        ),
        "{text}"
    );
}

/// A target deeper than the instrument reaches faults the run with an IK error naming the arm and a time
/// on the way there, blaming the insertion depth or a joint's limits.
#[test]
fn an_unreachable_target_faults_the_run_with_the_arm_and_time() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    let mut skill = reach_skill(arm, start, Vector3::zeros(), 0.1);
    // 0.5 m below the trocar: deeper than the instrument's 0.24 m insertion.
    skill.tracks[0].poses.push(PoseKey {
        time_s: 0.2,
        world_position_m: (trocar(arm) + Vector3::new(0.0, 0.0, -0.5)).into(),
        orientation: Orientation::AlongShaft,
    });
    controller.load_skill(skill).unwrap();
    let error = controller.run_to_end(|_| {}).unwrap_err();
    match &error {
        ControllerError::Ik { arm: a, time_s, .. } => {
            assert_eq!(*a, arm);
            assert!(*time_s > 0.1 && *time_s <= 0.2, "{time_s}");
        }
        other => panic!("expected an IK fault, got {other}"),
    }
    // On the way down, the arm runs out of a joint's range or the tool out of insertion first.
    let text = error.to_string();
    assert!(text.contains("insertion depth") || text.contains("outside its limits"), "{error}");
}

/// Skills needing an arm or a force sensor the rig lacks are refused naming the device, and a negative
/// sustain or keys out of order are refused naming the bad field's path.
#[test]
fn skills_the_rig_cannot_run_are_refused() {
    let arm = ArmName::Left;
    let (_, start) = parked(arm);
    let (mut controller, _, _) = dummy_controller(arm, PERIOD_S, ControllerParams::default());
    // A track for an arm without devices.
    let other = reach_skill(ArmName::Right, parked(ArmName::Right).1, Vector3::zeros(), 0.1);
    let error = controller.load_skill(other).unwrap_err();
    assert!(matches!(
        error,
        ControllerError::SkillNeedsDevice { arm: ArmName::Right, device: DeviceKind::ArmServo, .. }
    ));
    // A force event that must hold for a negative time: named.
    let event = ForceEvent {
        name: String::new(),
        from_s: 0.0,
        until_s: 0.5,
        threshold_n: 1.0,
        sustain_s: -0.1,
        fires_with: None,
        action: ForceAction::Hold,
    };
    let text = controller.load_skill(hold_still_skill(arm, start, vec![event])).unwrap_err().to_string();
    assert!(text.contains("tracks[0].events[0].sustain_s: -0.1 is not a duration"), "{text}");
    // A give that never gives: its rate named.
    let event = ForceEvent {
        name: String::new(),
        from_s: 0.0,
        until_s: 0.5,
        threshold_n: 1.0,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::Give { set_force_n: 1.0, rate_m_per_n_s: 0.0 },
    };
    let text = controller.load_skill(hold_still_skill(arm, start, vec![event])).unwrap_err().to_string();
    assert!(text.contains("tracks[0].events[0].action.rate_m_per_n_s: 0 is not a rate above zero"), "{text}");
    // Keys out of order: the path of the bad field is named.
    let mut bad = reach_skill(arm, start, Vector3::zeros(), 0.1);
    bad.tracks[0].poses[3].time_s = 0.0;
    let error = controller.load_skill(bad).unwrap_err();
    let text = error.to_string();
    assert!(text.contains("tracks[0].poses[3].time_s: 0 s is not after the previous key"), "{text}");
    // An event on an arm without a force sensor.
    let (joints, _) = parked(arm);
    let devices = DeviceSet {
        arms: vec![(
            arm,
            ArmDevices { servo: Box::new(DummyArmServo::new(joints.arm_rad)), instrument: None, force: None },
        )],
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(PERIOD_S)),
    };
    let mut bare = Controller::new(devices, &[setup(arm)], ControllerParams::default()).unwrap();
    let event = ForceEvent {
        name: String::new(),
        from_s: 0.0,
        until_s: 1.0,
        threshold_n: 1.0,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::Hold,
    };
    let mut skill = hold_still_skill(arm, start, vec![event]);
    skill.tracks[0].jaw.clear();
    let error = bare.load_skill(skill).unwrap_err();
    assert!(
        matches!(error, ControllerError::SkillNeedsDevice { device: DeviceKind::ForceSensor, .. }),
        "{error}"
    );
}

/// Devices for an arm with no model and trocar are refused when the controller is built, naming the arm.
#[test]
fn devices_without_a_setup_are_refused() {
    let (joints, _) = parked(ArmName::Left);
    let devices = DeviceSet {
        arms: vec![(
            ArmName::Assist,
            ArmDevices { servo: Box::new(DummyArmServo::new(joints.arm_rad)), instrument: None, force: None },
        )],
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(PERIOD_S)),
    };
    let setups = [ArmSetup {
        arm: ArmName::Left,
        model: rigs::rig().arm(ArmName::Left).model,
        world_trocar_m: trocar(ArmName::Left),
    }];
    let error = Controller::new(devices, &setups, ControllerParams::default()).err().expect("refused");
    assert!(error.to_string().contains("the assist arm has devices but no model and trocar"), "{error}");
}
