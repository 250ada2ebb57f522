//! Benchmark: the controller's per-cycle cost per arm (target: at most 50 microseconds).
//!
//! `cargo bench -p knotlab-bench --bench controller` times `Controller::step` with divan over 1,000
//! cycles of a 10 s skill (a slow circle with a rocking tip frame): reading the devices, events,
//! interpolation, trocar-constrained IK, step shaping, the limit decorators (position and velocity,
//! as a rig config wraps every driver) and the writes. Two rigs: three arms whose servos encode MXT
//! in memory (the controller's own cost, shown per arm), and one arm through the MELFA driver to the
//! emulator on loopback UDP.

use knotlab_hw::controller::{ArmSetup, Controller, ControllerParams, Status};
use knotlab_hw::device::dummy::{DummyForceSensor, DummyInstrumentDrive, DummyPedals, VirtualClock};
use knotlab_hw::device::{
    ArmDevices, ArmServo, ArmServoState, DeviceError, DeviceId, DeviceKind, DeviceSet, PositionLimit,
    VelocityLimit,
};
use knotlab_hw::kinematics::{ArmJoints, ArmModel, TipOrientation, TipTarget, Tool};
use knotlab_hw::melfa::codec::MAX_LEN;
use knotlab_hw::melfa::emulator::{DropPolicy, Emulator, EmulatorConfig};
use knotlab_hw::melfa::{
    CR750_CYCLE_S, Command, Data, DataType, Layout, MelfaArm, MelfaConfig, Monitor, Packet,
};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::{JawKey, Orientation, PoseKey, Skill, Track};
use nalgebra::{UnitQuaternion, Vector3};

const DURATION_S: f64 = 10.0;

/// An arm servo that speaks MXT into buffers: each write encodes a MOVE, each read decodes the reply a
/// controller would send (the command as the filtered joints, encoder joints in slot 1).
struct EncodingServo {
    joints_rad: [f64; 6],
    c_count: u32,
    tx: [u8; MAX_LEN],
    rx: [u8; MAX_LEN],
}

impl ArmServo for EncodingServo {
    fn read(&mut self) -> Result<ArmServoState, DeviceError> {
        let device = DeviceId::of_arm(DeviceKind::ArmServo, ArmName::Left);
        let reply = Packet::decode(&self.rx, Layout::H7)
            .map_err(|e| DeviceError::Protocol { device, reason: e.to_string() })?;
        let joints_rad = reply.monitor_joints_rad(DataType::FeedbackJoint).unwrap_or(self.joints_rad);
        Ok(ArmServoState { joints_rad, fresh: true })
    }

    fn write(&mut self, joints_rad: &[f64; 6]) -> Result<(), DeviceError> {
        let j = joints_rad.map(|q| q as f32);
        let joints = Data::Joint([j[0], j[1], j[2], j[3], j[4], j[5], 0.0, 0.0]);
        let mut packet = Packet::command(
            Command::Move,
            DataType::FilteredJoint,
            [DataType::FeedbackJoint, DataType::FilteredPose, DataType::FeedbackCurrent],
            self.c_count,
        );
        packet.send_type = DataType::Joint;
        packet.data = joints;
        std::hint::black_box(packet.encode(Layout::H7, &mut self.tx));
        // The reply the controller would send.
        packet.send_type = DataType::FilteredJoint;
        packet.monitors[0] = Monitor { kind: DataType::FeedbackJoint, data: joints };
        packet.encode(Layout::H7, &mut self.rx);
        self.c_count = self.c_count.wrapping_add(1);
        self.joints_rad = *joints_rad;
        Ok(())
    }
}

fn trocar(arm: ArmName) -> Vector3<f64> {
    match arm {
        ArmName::Left => Vector3::new(-0.08, 0.12, 1.02),
        ArmName::Right => Vector3::new(-0.08, -0.12, 1.02),
        ArmName::Assist => Vector3::new(0.12, 0.10, 1.02),
        ArmName::Camera => Vector3::new(-0.14, 0.0, 1.02),
    }
}

/// The arm parked 4 cm past its trocar towards the tissue, jaw open.
fn parked(model: &ArmModel, arm: ArmName) -> Result<ArmJoints, Box<dyn std::error::Error>> {
    let c = trocar(arm);
    let tip = c + (Vector3::new(0.0, 0.0, 0.95) - c).normalize() * 0.04;
    let target = TipTarget { world_position_m: tip, orientation: TipOrientation::AlongShaft };
    let mut joints = model.solve_tip(&target, &c, &arm.ready_joints())?;
    joints.tool.jaw_rad = 0.6;
    Ok(joints)
}

/// A slow circle of 5 mm radius with a rocking tip frame, keys every 20 ms.
fn track(model: &ArmModel, arm: ArmName, start: &ArmJoints) -> Track {
    let tip = model.world_from_tip(start);
    let first = UnitQuaternion::from_rotation_matrix(&tip.rotation);
    let poses = (0..=(DURATION_S / 0.02) as usize)
        .map(|k| {
            let time_s = 0.02 * k as f64;
            let phase = std::f64::consts::TAU * 0.2 * time_s;
            let ramp = (time_s / 2.0).min(1.0);
            let offset = Vector3::new(phase.cos() - 1.0, phase.sin(), 0.0) * 0.005 * ramp;
            let rock =
                UnitQuaternion::from_axis_angle(&(first * Vector3::x_axis()), 0.1 * phase.sin() * ramp);
            let q = rock * first;
            PoseKey {
                time_s,
                world_position_m: (tip.translation.vector + offset).into(),
                orientation: Orientation::Frame { quaternion_xyzw: [q.i, q.j, q.k, q.w] },
            }
        })
        .collect();
    let jaw = vec![JawKey { time_s: 0.0, jaw_rad: 0.6 }, JawKey { time_s: DURATION_S, jaw_rad: 0.1 }];
    Track { arm, poses, jaw, events: Vec::new() }
}

fn decorated(servo: Box<dyn ArmServo>, arm: ArmName, model: &ArmModel, period_s: f64) -> Box<dyn ArmServo> {
    let id = DeviceId::of_arm(DeviceKind::ArmServo, arm);
    let servo = Box::new(VelocityLimit::arm(servo, id, model.limits, period_s));
    Box::new(PositionLimit::arm(servo, id, model.limits))
}

/// Three instrument arms whose servos speak MXT in memory, with their setups and the skill.
fn encoding_rig(
    rig: &Rig,
    names: &[ArmName],
    period_s: f64,
) -> Result<(Controller, Vec<ArmSetup>, Skill), Box<dyn std::error::Error>> {
    let mut arms = Vec::new();
    let mut setups = Vec::new();
    let mut tracks = Vec::new();
    for &name in names {
        let model = rig.arm(name).model;
        let start = parked(&model, name)?;
        let Tool::Instrument { limits, .. } = model.tool else { return Err("an instrument arm".into()) };
        let servo =
            EncodingServo { joints_rad: start.arm_rad, c_count: 0, tx: [0; MAX_LEN], rx: [0; MAX_LEN] };
        let drive_id = DeviceId::of_arm(DeviceKind::InstrumentDrive, name);
        let drive =
            VelocityLimit::instrument(DummyInstrumentDrive::new(start.tool), drive_id, &limits, period_s);
        arms.push((
            name,
            ArmDevices {
                servo: decorated(Box::new(servo), name, &model, period_s),
                instrument: Some(Box::new(PositionLimit::instrument(drive, drive_id, &limits))),
                force: Some(Box::new(DummyForceSensor::new())),
            },
        ));
        setups.push(ArmSetup { arm: name, model, world_trocar_m: trocar(name) });
        tracks.push(track(&model, name, &start));
    }
    let devices = DeviceSet {
        arms,
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(period_s)),
    };
    let controller = Controller::new(devices, &setups, ControllerParams::default())?;
    Ok((controller, setups, Skill { name: "circles".into(), tracks }))
}

fn main() {
    divan::main();
}

/// Cycles timed per run: within the skill's 10 s (1,408 cycles at the CR750's 7.1 ms).
const SAMPLES: u32 = 10;
const CYCLES_PER_SAMPLE: u32 = 100;

/// One controller cycle of three instrument arms whose servos encode their MOVE into an MXT packet
/// and decode a reply in memory, as the MELFA driver does without a socket: the controller's own
/// cost, counted per arm.
#[divan::bench(sample_count = SAMPLES, sample_size = CYCLES_PER_SAMPLE)]
fn cycle_three_arms_mxt_in_memory(bencher: divan::Bencher) {
    let rig = Rig::shipped().expect("the shipped rig");
    let names = [ArmName::Left, ArmName::Right, ArmName::Assist];
    let (mut controller, _, skill) = encoding_rig(&rig, &names, CR750_CYCLE_S).expect("the rig builds");
    controller.load_skill(skill).expect("the skill loads");
    bencher.counter(divan::counter::ItemsCount::new(names.len())).bench_local(|| {
        let report = controller.step().expect("a healthy cycle");
        assert_eq!(report.status, Status::Running, "the skill runs through every timed cycle");
    });
}

/// One controller cycle of one arm through the real MELFA driver to the emulator on loopback UDP
/// (unpaced, on a thread of its own): adds two system calls a side and the emulator's work, which
/// share the machine's cores.
#[divan::bench(sample_count = SAMPLES, sample_size = CYCLES_PER_SAMPLE)]
fn cycle_one_arm_melfa_over_udp(bencher: divan::Bencher) {
    let rig = Rig::shipped().expect("the shipped rig");
    let (name, period_s) = (ArmName::Left, CR750_CYCLE_S);
    let model = rig.arm(name).model;
    let start = parked(&model, name).expect("the arm parks");
    let emulator = Emulator::bind(
        "127.0.0.1:0".parse().expect("an address"),
        false,
        EmulatorConfig {
            layout: Layout::H7,
            cycle_s: period_s,
            filter_s: 0.0,
            initial_joints_rad: start.arm_rad,
            limits: model.limits,
            drop: DropPolicy::Never,
            pace: false,
            idle_timeout_s: Some(10.0),
        },
    )
    .expect("the emulator binds");
    let addr = emulator.local_addr().expect("its address");
    let thread = emulator.spawn();
    let melfa = MelfaArm::connect(MelfaConfig::new(name, addr, &model.limits)).expect("the driver connects");
    let devices = DeviceSet {
        arms: vec![(
            name,
            ArmDevices {
                servo: decorated(Box::new(melfa), name, &model, period_s),
                instrument: Some(Box::new(DummyInstrumentDrive::new(start.tool))),
                force: None,
            },
        )],
        pedals: Box::new(DummyPedals::new()),
        masters: Vec::new(),
        clock: Box::new(VirtualClock::new(period_s)),
    };
    let setups = [ArmSetup { arm: name, model, world_trocar_m: trocar(name) }];
    let mut controller =
        Controller::new(devices, &setups, ControllerParams::default()).expect("a controller");
    let skill = Skill { name: "circle".into(), tracks: vec![track(&model, name, &start)] };
    controller.load_skill(skill).expect("the skill loads");
    bencher.bench_local(|| {
        let report = controller.step().expect("a healthy cycle");
        assert_eq!(report.status, Status::Running, "the skill runs through every timed cycle");
    });
    controller.shutdown().expect("a clean shutdown");
    thread.join().expect("the emulator thread").expect("the emulator");
}
