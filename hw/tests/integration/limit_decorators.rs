//! Limit decorators refuse out-of-range commands with typed errors, and the wrapped driver never sees
//! them: position limits, velocity over one cycle, a fixed per-cycle step, non-finite values, a write
//! before any read. Through a controller, a refusal faults the run.

use super::rigs;

use knotlab_hw::controller::{ControllerError, ControllerParams};
use knotlab_hw::device::dummy::{DummyArmServo, DummyInstrumentDrive};
use knotlab_hw::device::{
    ArmServo, DeviceError, DeviceId, DeviceKind, InstrumentDrive, LimitError, PositionLimit, StepLimit,
    VelocityLimit,
};
use knotlab_hw::kinematics::{JointId, JointLimit, Tool, ToolJoints};
use knotlab_hw::rig::ArmName;
use knotlab_hw::rig_config::{build_rig, parse_rig_config};
use nalgebra::Vector3;

const ARM: DeviceId = DeviceId::of_arm(DeviceKind::ArmServo, ArmName::Left);
const TOOL: DeviceId = DeviceId::of_arm(DeviceKind::InstrumentDrive, ArmName::Left);

fn limits() -> [JointLimit; 6] {
    [JointLimit::new(-1.0, 1.0, 2.0); 6]
}

fn limit_error(result: Result<(), DeviceError>) -> LimitError {
    match result {
        Err(DeviceError::Limit(e)) => e,
        other => panic!("expected a limit error, got {other:?}"),
    }
}

/// A position-limited servo refuses a command outside a joint's range, naming the joint and bounds, or a
/// NaN, without passing either to the driver; commands inside, bounds included, pass.
#[test]
fn position_limits_refuse_commands_outside_and_pass_those_inside() {
    let mut servo = PositionLimit::arm(DummyArmServo::new([0.0; 6]), ARM, limits());
    let error = limit_error(servo.write(&[0.0, 1.2, 0.0, 0.0, 0.0, 0.0]));
    assert_eq!(
        error,
        LimitError::Position {
            device: ARM,
            joint: JointId::Arm(2),
            value_rad: 1.2,
            lower_rad: -1.0,
            upper_rad: 1.0
        }
    );
    assert!(
        error.to_string().starts_with("left arm servo: joint2 command 1.200000 rad is outside"),
        "{error}"
    );
    assert_eq!(servo.read().unwrap().joints_rad, [0.0; 6], "the driver never saw it");
    servo.write(&[0.5, -1.0, 1.0, 0.0, 0.0, 0.0]).unwrap();
    assert_eq!(servo.read().unwrap().joints_rad, [0.5, -1.0, 1.0, 0.0, 0.0, 0.0]);
    let error = limit_error(servo.write(&[0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0]));
    assert_eq!(error, LimitError::NotFinite { device: ARM, joint: JointId::Arm(3) });
}

/// A velocity-limited servo refuses a step faster than the joint's speed, naming the joint and speeds, and
/// measures the next step from the last accepted command, not the refused one.
#[test]
fn velocity_limits_refuse_steps_faster_than_the_speed_limit() {
    // 2 rad/s over 10 ms cycles: at most 0.02 rad per cycle.
    let mut servo = VelocityLimit::arm(DummyArmServo::new([0.0; 6]), ARM, limits(), 0.01);
    servo.read().unwrap();
    servo.write(&[0.019, 0.0, 0.0, 0.0, 0.0, -0.02]).unwrap();
    let error = limit_error(servo.write(&[0.019, 0.0, 0.0, 0.025, 0.0, -0.02]));
    match error {
        LimitError::Velocity { device, joint, velocity_rad_s, max_rad_s } => {
            assert_eq!((device, joint), (ARM, JointId::Arm(4)));
            assert!((velocity_rad_s - 2.5).abs() < 1e-9 && max_rad_s == 2.0, "{error}");
        }
        other => panic!("{other:?}"),
    }
    // Measured from the last accepted command, not the refused one.
    servo.write(&[0.039, 0.0, 0.0, 0.02, 0.0, -0.04]).unwrap();
    assert_eq!(servo.read().unwrap().joints_rad, [0.039, 0.0, 0.0, 0.02, 0.0, -0.04]);
}

/// A step-limited servo refuses a write before its first read, and a step over the per-cycle limit naming
/// the joint, the step and the limit.
#[test]
fn step_limits_refuse_large_steps_and_writes_before_any_read() {
    let mut servo = StepLimit::arm(DummyArmServo::new([0.1; 6]), ARM, [0.05; 6]);
    let error = limit_error(servo.write(&[0.1; 6]));
    assert!(matches!(error, LimitError::Step { step_rad, .. } if step_rad.is_infinite()), "{error:?}");
    assert_eq!(servo.read().unwrap().joints_rad, [0.1; 6]);
    servo.write(&[0.15, 0.1, 0.1, 0.1, 0.1, 0.05]).unwrap();
    let error = limit_error(servo.write(&[0.15, 0.1, 0.1, 0.1, 0.1, -0.01]));
    match error {
        LimitError::Step { device, joint, step_rad, max_step_rad } => {
            assert_eq!((device, joint), (ARM, JointId::Arm(6)));
            assert!((step_rad - 0.06).abs() < 1e-12 && max_step_rad == 0.05);
        }
        other => panic!("{other:?}"),
    }
}

/// Limits on an instrument drive refuse a wrist pitch past its range and a jaw moving too fast, naming the
/// instrument joint, and pass a jaw step within its speed.
#[test]
fn instrument_limits_name_the_instrument_joint() {
    let rig = rigs::rig();
    let Tool::Instrument { limits, .. } = rig.arm(ArmName::Left).model.tool else { panic!("an instrument") };
    let inner =
        VelocityLimit::instrument(DummyInstrumentDrive::new(ToolJoints::default()), TOOL, &limits, 0.001);
    let mut drive = PositionLimit::instrument(inner, TOOL, &limits);
    drive.read().unwrap();
    let too_far = ToolJoints { pitch_rad: limits.pitch.upper_rad + 0.01, ..ToolJoints::default() };
    let error = limit_error(drive.write(&too_far));
    assert!(matches!(error, LimitError::Position { joint: JointId::WristPitch, .. }), "{error:?}");
    let too_fast =
        ToolJoints { jaw_rad: limits.jaw.max_velocity_rad_s * 0.001 * 1.5, ..ToolJoints::default() };
    let error = limit_error(drive.write(&too_fast));
    assert!(matches!(error, LimitError::Velocity { joint: JointId::Jaw, device: TOOL, .. }), "{error:?}");
    let fine = ToolJoints { jaw_rad: limits.jaw.max_velocity_rad_s * 0.001 * 0.5, ..ToolJoints::default() };
    drive.write(&fine).unwrap();
    assert_eq!(drive.read().unwrap().joints, fine);
}

/// A rig config asking for a per-cycle step limit tighter than the controller's own shaping: the
/// decorator refuses the first large step and the controller faults with the typed error.
#[test]
fn a_refused_command_faults_the_controller_with_the_limit_error() {
    let (_, start) = rigs::parked(ArmName::Left);
    let t = rigs::trocar(ArmName::Left);
    let config = parse_rig_config(
        &format!(
            "description = \"tight steps\"\n\
             [arms.left]\n\
             trocar_m = [{}, {}, {}]\n\
             max_step_rad = 0.0001\n\
             servo = {{ backend = \"dummy\" }}\n\
             instrument = {{ backend = \"dummy\" }}\n",
            t.x, t.y, t.z
        ),
        "tight.toml",
    )
    .unwrap();
    let built = build_rig(&config, &rigs::rig(), None).unwrap();
    assert_eq!(built.params, ControllerParams::default());
    let (mut controller, _) = built.into_controller().unwrap();
    controller
        .load_skill(rigs::reach_skill(ArmName::Left, start, Vector3::new(0.02, 0.0, -0.02), 2.0))
        .unwrap();
    let error = controller.run_to_end(|_| {}).unwrap_err();
    match error {
        ControllerError::Device(DeviceError::Limit(LimitError::Step { device, max_step_rad, .. })) => {
            assert_eq!(device, ARM);
            assert_eq!(max_step_rad, 0.0001);
        }
        other => panic!("expected a step refusal, got {other}"),
    }
}
