//! The CiA 402 instrument drive against emulated drives on an in-process CAN bus: configured by SDO
//! and walked to Operation Enabled; joints through the coupling matrix to counts and back over the
//! PDOs; a node that drops out (heartbeat lost), a following-error EMCY and a refused SDO transfer
//! each fault the device naming the node; shutdown takes the drives down.

use std::time::{Duration, Instant};

use knotlab_hw::canopen::bus::MemoryBus;
use knotlab_hw::canopen::cia402::DriveState;
use knotlab_hw::canopen::drive::{CanopenConfig, CanopenDrive};
use knotlab_hw::canopen::emulator::{CanopenEmulator, CanopenEmulatorConfig, NodeConfig};
use knotlab_hw::device::{DeviceError, InstrumentDrive};
use knotlab_hw::kinematics::ToolJoints;
use knotlab_hw::rig::ArmName;
use nalgebra::Matrix4;

const NODES: [u8; 4] = [11, 12, 13, 14];
const COUNTS_PER_RAD: f64 = 10_000.0;

fn drives(nodes: Vec<NodeConfig>) -> (MemoryBus, CanopenEmulator) {
    let bus = MemoryBus::new();
    let emulator = CanopenEmulator::start(
        Box::new(bus.endpoint()),
        CanopenEmulatorConfig { nodes, sync_period_s: 0.002 },
    );
    (bus, emulator)
}

fn config() -> CanopenConfig {
    // The jaw's motor also turns with the yaw (a cable coupling): motor 4 = jaw + 0.5 yaw.
    let mut coupling = Matrix4::identity();
    coupling[(3, 2)] = 0.5;
    CanopenConfig { coupling, ..CanopenConfig::new(ArmName::Left, NODES, COUNTS_PER_RAD) }
}

/// Writes `joints` and reads every 2 ms for `ms`, returning the last reading (or the first error).
fn run(drive: &mut CanopenDrive, joints: &ToolJoints, ms: u64) -> Result<ToolJoints, DeviceError> {
    let mut last = ToolJoints::default();
    let start = Instant::now();
    while start.elapsed() < Duration::from_millis(ms) {
        drive.write(joints)?;
        std::thread::sleep(Duration::from_millis(2));
        last = drive.read()?.joints;
    }
    Ok(last)
}

/// Guards the state machine and the PDO exchange: every drive reaches Operation Enabled, the joints
/// reach the motors through the coupling and come back, and shutdown leaves the drives disabled.
#[test]
fn the_drives_are_enabled_and_follow_the_joints() {
    let (bus, emulator) = drives(NODES.iter().map(|n| NodeConfig::new(*n)).collect());
    let mut drive = CanopenDrive::connect(Box::new(bus.endpoint()), config()).expect("connected");
    assert!(
        emulator.nodes().iter().all(|(_, state, _)| *state == DriveState::OperationEnabled),
        "{:?}",
        emulator.nodes()
    );
    assert_eq!(drive.limits_counts()[2], [-1_000_000, 1_000_000]);
    let target = ToolJoints { roll_rad: 0.1, pitch_rad: -0.05, yaw_rad: 0.02, jaw_rad: 0.3 };
    let read = run(&mut drive, &target, 300).expect("the drives follow");
    for (got, want) in
        [(read.roll_rad, 0.1), (read.pitch_rad, -0.05), (read.yaw_rad, 0.02), (read.jaw_rad, 0.3)]
    {
        assert!((got - want).abs() < 2e-4, "{read:?}");
    }
    let counts: Vec<i32> = emulator.nodes().iter().map(|(_, _, p)| *p).collect();
    assert_eq!(counts, vec![1000, -500, 200, 3100], "the jaw's motor turns 0.3 + 0.5 x 0.02 rad");
    drive.shutdown().expect("taken down");
    assert!(emulator.nodes().iter().all(|(_, state, _)| *state == DriveState::SwitchOnDisabled));
    assert!(matches!(drive.read(), Err(DeviceError::Closed { .. })));
}

/// Guards the heartbeat consumer: a node that drops out faults the device, naming it.
#[test]
fn a_node_that_drops_out_faults_the_drive() {
    let (bus, emulator) = drives(NODES.iter().map(|n| NodeConfig::new(*n)).collect());
    let mut drive = CanopenDrive::connect(Box::new(bus.endpoint()), config()).expect("connected");
    let still = ToolJoints::default();
    run(&mut drive, &still, 50).expect("running");
    emulator.drop_out(12);
    let error = run(&mut drive, &still, 1000).expect_err("the pitch's node is gone");
    assert!(matches!(error, DeviceError::LinkDown { .. }), "{error}");
    assert!(error.to_string().contains("node 12 (pitch): heartbeat lost"), "{error}");
}

/// Guards EMCY: a following error on the yaw's drive faults the device with the node and the code.
#[test]
fn a_following_error_emcy_faults_the_drive() {
    let (bus, emulator) = drives(NODES.iter().map(|n| NodeConfig::new(*n)).collect());
    let mut drive = CanopenDrive::connect(Box::new(bus.endpoint()), config()).expect("connected");
    let still = ToolJoints::default();
    run(&mut drive, &still, 20).expect("running");
    emulator.following_error(13);
    let error = run(&mut drive, &still, 1000).expect_err("the yaw's drive faulted");
    let text = error.to_string();
    assert!(
        text.contains("node 13 (yaw)") && text.contains("0x8611") && text.contains("following error"),
        "{text}"
    );
}

/// Guards configuration: a drive that refuses the mode is named with the object and CiA 301's
/// reason; a node that never answers is named too.
#[test]
fn a_refused_or_missing_sdo_answer_is_named() {
    let mut nodes: Vec<NodeConfig> = NODES.iter().map(|n| NodeConfig::new(*n)).collect();
    nodes[1].supports_csp = false;
    let (bus, _emulator) = drives(nodes);
    let error = CanopenDrive::connect(Box::new(bus.endpoint()), config()).err().expect("refused");
    let text = error.to_string();
    assert!(
        text.contains("node 12 (pitch) object 0x6060:00") && text.contains("invalid value for parameter"),
        "{text}"
    );
    let (bus, _emulator) = drives(NODES[..3].iter().map(|n| NodeConfig::new(*n)).collect());
    let error = CanopenDrive::connect(Box::new(bus.endpoint()), config()).err().expect("no jaw node");
    assert!(
        error.to_string().contains("node 14 (jaw)") && error.to_string().contains("no SDO answer"),
        "{error}"
    );
}

/// Guards the CAN-over-UDP transport: the same drives, their emulator listening on loopback UDP (as
/// `knotlab canopen-emulator` runs them), are enabled and follow.
#[test]
fn the_drives_answer_over_loopback_udp() {
    use knotlab_hw::canopen::udp::UdpCan;
    let any: std::net::SocketAddr = "127.0.0.1:0".parse().expect("an address");
    let listener = UdpCan::listen(any).expect("bound");
    let addr = listener.local_addr().expect("its address");
    let nodes = NODES.iter().map(|n| NodeConfig::new(*n)).collect();
    let emulator =
        CanopenEmulator::start(Box::new(listener), CanopenEmulatorConfig { nodes, sync_period_s: 0.002 });
    let transport = UdpCan::connect(any, addr).expect("bound");
    let mut drive = CanopenDrive::connect(Box::new(transport), config()).expect("connected over UDP");
    let target = ToolJoints { roll_rad: -0.2, pitch_rad: 0.1, yaw_rad: 0.0, jaw_rad: 0.5 };
    let read = run(&mut drive, &target, 300).expect("the drives follow");
    assert!((read.roll_rad + 0.2).abs() < 2e-4 && (read.jaw_rad - 0.5).abs() < 2e-4, "{read:?}");
    drive.shutdown().expect("taken down");
    assert!(emulator.nodes().iter().all(|(_, state, _)| *state == DriveState::SwitchOnDisabled));
}

/// Guards the rig config: an instrument of backend `canopen` is checked key by key, and a rig with one
/// drives the emulated drives through the controller: a skill that opens the jaw turns the jaw's
/// motor (and, by the coupling, nothing else of it), and shutdown takes the drives down.
#[test]
fn a_rig_drives_canopen_instruments_through_the_controller() {
    use knotlab_hw::canopen::udp::UdpCan;
    use knotlab_hw::rig::Rig;
    use knotlab_hw::rig_config::{RigConfigError, build_rig, parse_rig_config};
    use knotlab_hw::skill::{JawKey, PoseKey, Skill, Track};
    let bad = "description = \"x\"\n[arms.left]\ntrocar_m = [0.0, 0.1, 1.0]\nservo = { backend = \"dummy\" }\n\
               instrument = { backend = \"canopen\", nodes = [11, 11, 12, 0], counts_per_rad = [1.0, 0.0, 1.0, 1.0], \
               coupling = [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]] }\n\
               [arms.right]\ntrocar_m = [0.0, -0.1, 1.0]\nservo = { backend = \"dummy\" }\n\
               instrument = { backend = \"dummy\", nodes = [1, 2, 3, 4] }\n";
    let Err(RigConfigError::Invalid { problems, .. }) = parse_rig_config(bad, "rig.toml") else {
        panic!("problems expected")
    };
    let has = |key: &str, words: &str| problems.iter().any(|(k, r)| k == key && r.contains(words));
    assert!(has("arms.left.instrument.udp", "ip:port"), "{problems:?}");
    assert!(has("arms.left.instrument.nodes", "node 0"), "{problems:?}");
    assert!(has("arms.left.instrument.nodes", "each drive its own node"), "{problems:?}");
    assert!(has("arms.left.instrument.counts_per_rad", "not 0"), "{problems:?}");
    assert!(has("arms.left.instrument.coupling", "invertible"), "{problems:?}");
    assert!(has("arms.right.instrument.nodes", "only for backend \"canopen\""), "{problems:?}");

    let any: std::net::SocketAddr = "127.0.0.1:0".parse().expect("an address");
    let listener = UdpCan::listen(any).expect("bound");
    let addr = listener.local_addr().expect("its address");
    let nodes = NODES.iter().map(|n| NodeConfig::new(*n)).collect();
    let emulator =
        CanopenEmulator::start(Box::new(listener), CanopenEmulatorConfig { nodes, sync_period_s: 0.002 });
    let text = format!(
        "description = \"a dummy arm with CANopen drives\"\n[controller]\nperiod_s = 0.002\nreal_time = true\n\
         [arms.left]\ntrocar_m = [-0.08, 0.12, 1.02]\nservo = {{ backend = \"dummy\" }}\n\
         instrument = {{ backend = \"canopen\", udp = \"{addr}\", nodes = [11, 12, 13, 14], counts_per_rad = [10000.0, 10000.0, 10000.0, 10000.0], \
         coupling = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.5, 1.0]] }}\n\
         [pedals]\nbackend = \"dummy\"\n"
    );
    let config = parse_rig_config(&text, "canopen.toml").expect("a rig with CANopen drives");
    let rig = Rig::shipped().expect("the shipped rig");
    let (mut controller, _handles) =
        build_rig(&config, &rig, None).expect("built").into_controller().expect("a controller");
    let start = controller.record().arm(ArmName::Left).expect("the left arm").measured;
    let tip = rig.arm(ArmName::Left).model.world_from_tip(&start);
    let pose = |t: f64| PoseKey {
        time_s: t,
        world_position_m: tip.translation.vector.into(),
        orientation: knotlab_hw::skill::Orientation::AlongShaft,
    };
    let skill = Skill {
        name: "open the jaw".into(),
        tracks: vec![Track {
            arm: ArmName::Left,
            poses: vec![pose(0.0), pose(0.4)],
            jaw: vec![
                JawKey { time_s: 0.0, jaw_rad: start.tool.jaw_rad },
                JawKey { time_s: 0.2, jaw_rad: 0.4 },
            ],
            events: Vec::new(),
        }],
    };
    controller.load_skill(skill).expect("loaded");
    let summary = controller.run_to_end(|_| {}).expect("run");
    assert_eq!(summary.outcome, knotlab_hw::controller::RunOutcome::Completed);
    std::thread::sleep(Duration::from_millis(20));
    let measured = controller.record().arm(ArmName::Left).expect("the left arm").measured;
    assert!((measured.tool.jaw_rad - 0.4).abs() < 0.01, "{:?}", measured.tool);
    let jaw_motor = emulator.nodes()[3].2;
    let expected = ((0.4 + 0.5 * measured.tool.yaw_rad) * 10_000.0).round() as i32;
    assert!((jaw_motor - expected).abs() <= 60, "the jaw's motor at {jaw_motor} counts, {expected} expected");
    controller.shutdown().expect("the devices' sessions ended");
    assert!(emulator.nodes().iter().all(|(_, state, _)| *state == DriveState::SwitchOnDisabled));
}
