//! Teleoperation on a dummy rig: the master's handle moves the instrument scaled down; the clutch pedal
//! lets the hand move back without moving the instrument, and motion counts from there on release; a
//! running skill blocks manual input and the instrument does not jump when manual control resumes; the
//! emergency stop halts manual motion too.

use super::rigs;

use knotlab_hw::controller::{Controller, ControllerParams, Status, TeleopSettings};
use knotlab_hw::device::dummy::{
    DummyArmServo, DummyForceSensor, DummyInstrumentDrive, DummyMaster, DummyPedals, MasterHandle,
    PedalHandle, VirtualClock,
};
use knotlab_hw::device::{ArmDevices, DeviceSet};
use knotlab_hw::rig::ArmName;
use nalgebra::{IsometryMatrix3, Translation3, Vector3};

use rigs::{parked, reach_skill, setup};

const ARM: ArmName = ArmName::Left;

fn teleop_rig() -> (Controller, PedalHandle, MasterHandle) {
    let (joints, _) = parked(ARM);
    let pedals = DummyPedals::new();
    let master = DummyMaster::new();
    let (pedal_handle, master_handle) = (pedals.handle(), master.handle());
    let devices = DeviceSet {
        arms: vec![(
            ARM,
            ArmDevices {
                servo: Box::new(DummyArmServo::new(joints.arm_rad)),
                instrument: Some(Box::new(DummyInstrumentDrive::new(joints.tool))),
                force: Some(Box::new(DummyForceSensor::new())),
            },
        )],
        pedals: Box::new(pedals),
        masters: vec![(ARM, Box::new(master))],
        clock: Box::new(VirtualClock::new(0.001)),
    };
    let mut controller =
        Controller::new(devices, &[setup(ARM)], ControllerParams::default()).expect("starts");
    controller.set_teleoperation(Some(TeleopSettings::default())).expect("default settings are good");
    (controller, pedal_handle, master_handle)
}

fn handle_at(x: f64, y: f64, z: f64) -> IsometryMatrix3<f64> {
    IsometryMatrix3::from_parts(Translation3::new(x, y, z), nalgebra::Rotation3::identity())
}

/// Runs `cycles` cycles and returns the tip.
fn run(controller: &mut Controller, cycles: usize) -> Vector3<f64> {
    let mut tip = Vector3::zeros();
    for _ in 0..cycles {
        let record = controller.step().expect("a cycle");
        tip = record.arm(ARM).expect("the arm").world_from_tip.translation.vector;
    }
    tip
}

/// The handle moves the tip a third as far and the gripper sets the jaw; clutched, the hand moves back
/// without moving the tip, and on release motion counts from where the tip is.
#[test]
fn the_handle_steers_the_tip_scaled_and_the_clutch_repositions_the_hand() {
    let (mut c, pedals, master) = teleop_rig();
    let start = run(&mut c, 5);
    // 3 cm of handle: 1 cm of tip (1:3), reached in well under a second.
    for k in 1..=300 {
        master.set(handle_at(0.03 * k as f64 / 300.0, 0.0, 0.0), 0.3, 0);
        run(&mut c, 1);
    }
    let moved = run(&mut c, 500);
    assert!((moved - start - Vector3::new(0.01, 0.0, 0.0)).norm() < 1e-6, "{:?}", moved - start);
    let jaw = c.record().arm(ARM).unwrap().measured.tool.jaw_rad;
    assert!((jaw - 0.3).abs() < 1e-9, "the gripper sets the jaw: {jaw}");
    // Clutched, the hand goes back to the console's origin: the tip stays.
    pedals.set_assignable(0, true);
    for k in (0..300).rev() {
        master.set(handle_at(0.03 * k as f64 / 300.0, 0.0, 0.0), 0.3, 0);
        run(&mut c, 1);
    }
    let held = run(&mut c, 100);
    assert!((held - moved).norm() < 1e-9, "clutched, the tip moved {:?}", held - moved);
    // Released, 3 cm of handle along y moves the tip 1 cm from where it is.
    pedals.set_assignable(0, false);
    run(&mut c, 5);
    for k in 1..=300 {
        master.set(handle_at(0.0, 0.03 * k as f64 / 300.0, 0.0), 0.3, 0);
        run(&mut c, 1);
    }
    let again = run(&mut c, 500);
    assert!((again - held - Vector3::new(0.0, 0.01, 0.0)).norm() < 1e-6, "{:?}", again - held);
}

/// The handle is ignored while a skill runs, and manual control resumes from the skill's end without a
/// jump towards the hand, following the hand's moves from there.
#[test]
fn a_running_skill_blocks_manual_input_and_control_resumes_without_a_jump() {
    let (mut c, _, master) = teleop_rig();
    let start = run(&mut c, 5);
    c.load_skill(reach_skill(ARM, start, Vector3::new(0.0, 0.01, -0.01), 1.0)).unwrap();
    // The hand wanders while the skill runs: ignored.
    master.set(handle_at(0.05, -0.04, 0.02), 0.0, 0);
    let mut cycles = 0;
    while c.status() == Status::Running {
        run(&mut c, 1);
        cycles += 1;
        assert!(cycles < 5000, "the skill ends");
    }
    let after_skill = run(&mut c, 1);
    let off = after_skill - start - Vector3::new(0.0, 0.01, -0.01);
    assert!(off.norm() < 1e-6, "the skill's end: {off:?}");
    // Manual control resumes from here: no jump towards where the hand is.
    let resumed = run(&mut c, 200);
    assert!((resumed - after_skill).norm() < 1e-6, "jumped by {:?}", resumed - after_skill);
    master.set(handle_at(0.05 - 0.015, -0.04, 0.02), 0.0, 0);
    let nudged = run(&mut c, 500);
    assert!((nudged - resumed - Vector3::new(-0.005, 0.0, 0.0)).norm() < 1e-6, "{:?}", nudged - resumed);
}

/// Under the emergency stop the handle's motion does not move the tip.
#[test]
fn the_emergency_stop_halts_manual_motion() {
    let (mut c, pedals, master) = teleop_rig();
    let start = run(&mut c, 5);
    pedals.set_emergency_stop(true);
    master.set(handle_at(0.03, 0.0, 0.0), 0.0, 0);
    let stopped = run(&mut c, 500);
    assert_eq!(c.status(), Status::EmergencyStopped);
    assert!((stopped - start).norm() < 1e-9, "moved {:?} under the emergency stop", stopped - start);
}

/// Teleoperation settings with a negative scale are refused naming `teleoperation.scale`.
#[test]
fn bad_settings_are_refused() {
    let (mut c, _, _) = teleop_rig();
    let e =
        c.set_teleoperation(Some(TeleopSettings { scale: -1.0, ..TeleopSettings::default() })).unwrap_err();
    assert!(e.to_string().contains("teleoperation.scale"), "{e}");
}
