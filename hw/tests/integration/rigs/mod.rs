//! Rigs, skills and emulators shared by the device, controller and MELFA tests.
#![allow(dead_code)]

use std::net::SocketAddr;
use std::thread::JoinHandle;

use knotlab_hw::controller::{ArmSetup, Controller, ControllerParams};
use knotlab_hw::device::dummy::{
    DummyArmServo, DummyForceSensor, DummyInstrumentDrive, DummyPedals, ForceHandle, PedalHandle,
    VirtualClock,
};
use knotlab_hw::device::{ArmDevices, DeviceSet};
use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget};
use knotlab_hw::melfa::emulator::{DropPolicy, Emulator, EmulatorConfig, EmulatorError, EmulatorReport};
use knotlab_hw::melfa::{CR750_CYCLE_S, Layout};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::profile::min_jerk;
use knotlab_hw::skill::{JawKey, Orientation, PoseKey, Skill, Track};
use nalgebra::{UnitQuaternion, Vector3};

/// The shipped rig.
pub fn rig() -> Rig {
    Rig::shipped().expect("the shipped rig loads")
}

/// The trocars of the shipped scene (scenarios/default.toml).
pub fn trocar(arm: ArmName) -> Vector3<f64> {
    match arm {
        ArmName::Left => Vector3::new(-0.08, 0.12, 1.02),
        ArmName::Right => Vector3::new(-0.08, -0.12, 1.02),
        ArmName::Assist => Vector3::new(0.12, 0.10, 1.02),
        ArmName::Camera => Vector3::new(-0.14, 0.0, 1.02),
    }
}

/// The arm parked as the simulated scene parks it: the tip 4 cm past the trocar towards the tissue
/// centre (0, 0, 0.95), the wrist straight, the jaw open 0.6 rad. Returns the joints and the tip.
pub fn parked(arm: ArmName) -> (ArmJoints, Vector3<f64>) {
    let model = rig().arm(arm).model;
    let c = trocar(arm);
    let tip = c + (Vector3::new(0.0, 0.0, 0.95) - c).normalize() * 0.04;
    let target = TipTarget { world_position_m: tip, orientation: TipOrientation::AlongShaft };
    let mut joints = model.solve_tip(&target, &c, &arm.ready_joints()).expect("the parked pose is reachable");
    if arm.carries_instrument() {
        joints.tool.jaw_rad = 0.6;
    }
    (joints, tip)
}

/// A gentle skill for one instrument: from `start` the tip moves by `offset_m` along a minimum-jerk
/// profile over `duration_s` (keys every 20 ms) while the tip frame turns from the parked one by 0.3 rad
/// about an axis across the jaws, and the jaw closes from 0.6 to 0.2 rad over the second half.
pub fn reach_skill(arm: ArmName, start: Vector3<f64>, offset_m: Vector3<f64>, duration_s: f64) -> Skill {
    let keys = (duration_s / 0.02).round() as usize;
    let model = rig().arm(arm).model;
    let (joints, _) = parked(arm);
    let first = UnitQuaternion::from_rotation_matrix(&model.world_from_tip(&joints).rotation);
    let turn = UnitQuaternion::from_axis_angle(&(first * Vector3::x_axis()), 0.3);
    let poses = (0..=keys)
        .map(|k| {
            let time_s = duration_s * k as f64 / keys as f64;
            let s = min_jerk(time_s / duration_s);
            let q = UnitQuaternion::identity().slerp(&turn, s) * first;
            PoseKey {
                time_s,
                world_position_m: (start + offset_m * s).into(),
                orientation: Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] },
            }
        })
        .collect();
    Skill {
        name: format!("reach {arm}"),
        tracks: vec![Track {
            arm,
            poses,
            jaw: vec![
                JawKey { time_s: 0.5 * duration_s, jaw_rad: 0.6 },
                JawKey { time_s: duration_s, jaw_rad: 0.2 },
            ],
            events: Vec::new(),
        }],
    }
}

/// The setup of one arm on the shipped rig with the shipped trocar.
pub fn setup(arm: ArmName) -> ArmSetup {
    ArmSetup { arm, model: rig().arm(arm).model, world_trocar_m: trocar(arm) }
}

/// A dummy rig with one instrument arm, parked; returns the controller and the pedal and force handles.
pub fn dummy_controller(
    arm: ArmName,
    period_s: f64,
    params: ControllerParams,
) -> (Controller, PedalHandle, ForceHandle) {
    let (joints, _) = parked(arm);
    let pedals = DummyPedals::new();
    let force = DummyForceSensor::new();
    let (pedal_handle, force_handle) = (pedals.handle(), force.handle());
    let devices = DeviceSet {
        arms: vec![(
            arm,
            ArmDevices {
                servo: Box::new(DummyArmServo::new(joints.arm_rad)),
                instrument: Some(Box::new(DummyInstrumentDrive::new(joints.tool))),
                force: Some(Box::new(force)),
            },
        )],
        pedals: Box::new(pedals),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(period_s)),
    };
    let controller = Controller::new(devices, &[setup(arm)], params).expect("the dummy rig starts");
    (controller, pedal_handle, force_handle)
}

/// An unpaced emulator of `arm`'s MELFA controller standing at its parked joints, on 127.0.0.1:0.
pub fn emulator_config(arm: ArmName, layout: Layout, drop: DropPolicy, filter_s: f64) -> EmulatorConfig {
    let (joints, _) = parked(arm);
    EmulatorConfig {
        layout,
        cycle_s: CR750_CYCLE_S,
        filter_s,
        initial_joints_rad: joints.arm_rad,
        limits: rig().arm(arm).model.limits,
        drop,
        pace: false,
        idle_timeout_s: Some(10.0),
    }
}

/// Starts an emulator on a thread; returns its address and the thread.
pub fn spawn_emulator(
    config: EmulatorConfig,
) -> (SocketAddr, JoinHandle<Result<EmulatorReport, EmulatorError>>) {
    let emulator =
        Emulator::bind("127.0.0.1:0".parse().expect("an address"), false, config).expect("binds loopback");
    let addr = emulator.local_addr().expect("bound");
    (addr, emulator.spawn())
}
