//! The CiA 402 instrument drive against emulated drives on an in-process CAN bus: configured by SDO
//! and walked to Operation Enabled; joints through the coupling matrix to counts and back over the
//! PDOs; a node that drops out (heartbeat lost), a following-error EMCY and a refused SDO transfer
//! each fault the device naming the node; shutdown takes the drives down. Then the transports (CAN
//! over UDP; SocketCAN on a virtual interface where the machine has one) and rigs through the
//! controller: a node dropping out mid-run faults the run while every other device holds.

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

/// Emulated drives of `nodes` listening on loopback UDP (as `knotlab canopen-emulator` runs them), and
/// their address.
fn udp_drives(nodes: &[u8]) -> (CanopenEmulator, std::net::SocketAddr) {
    use knotlab_hw::canopen::udp::UdpCan;
    let listener = UdpCan::listen("127.0.0.1:0".parse().expect("an address")).expect("bound");
    let addr = listener.local_addr().expect("its address");
    let nodes = nodes.iter().map(|n| NodeConfig::new(*n)).collect();
    let emulator =
        CanopenEmulator::start(Box::new(listener), CanopenEmulatorConfig { nodes, sync_period_s: 0.002 });
    (emulator, addr)
}

/// An arm's `instrument` line of a rig config: CiA 402 drives `nodes` on `bus` (`udp = "..."` or
/// `interface = "..."`), 10,000 counts per radian, the jaw's motor turning with half the yaw.
fn canopen_line(bus: &str, nodes: [u8; 4]) -> String {
    format!(
        "instrument = {{ backend = \"canopen\", {bus}, nodes = {nodes:?}, counts_per_rad = [10000.0, 10000.0, 10000.0, 10000.0], \
         coupling = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.5, 1.0]] }}\n"
    )
}

/// A controller over one dummy arm (the left) whose instrument is CiA 402 drives `NODES` on `bus`
/// ([`canopen_line`]), at a 2 ms cycle in real time; and the shipped rig. Its heartbeat time-out is
/// 0.5 s: these runs are not about the heartbeat, and a loaded machine has kept the emulator's
/// thread from beating for the default's 50 ms.
fn left_arm_on(bus: &str) -> (knotlab_hw::controller::Controller, knotlab_hw::rig::Rig) {
    use knotlab_hw::rig::Rig;
    use knotlab_hw::rig_config::{build_rig, parse_rig_config};
    let text = format!(
        "description = \"a dummy arm with CANopen drives\"\n[controller]\nperiod_s = 0.002\nreal_time = true\n\
         [arms.left]\ntrocar_m = [-0.08, 0.12, 1.02]\nservo = {{ backend = \"dummy\" }}\n{}\
         [pedals]\nbackend = \"dummy\"\n",
        canopen_line(&format!("{bus}, heartbeat_timeout_s = 0.5"), NODES)
    );
    let config = parse_rig_config(&text, "canopen.toml").expect("a rig with CANopen drives");
    let rig = Rig::shipped().expect("the shipped rig");
    let (controller, _handles) =
        build_rig(&config, &rig, None).expect("built").into_controller().expect("a controller");
    (controller, rig)
}

/// A skill that opens `arm`'s jaw to `jaw_rad` over `open_s` while its tip stays where the controller's
/// record has it, ending at `end_s`.
fn open_jaw(
    controller: &knotlab_hw::controller::Controller,
    rig: &knotlab_hw::rig::Rig,
    arm: ArmName,
    jaw_rad: f64,
    open_s: f64,
    end_s: f64,
) -> knotlab_hw::skill::Track {
    use knotlab_hw::skill::{JawKey, Orientation, PoseKey, Track};
    let start = controller.record().arm(arm).expect("the arm").measured;
    let tip = rig.arm(arm).model.world_from_tip(&start);
    let pose = |t: f64| PoseKey {
        time_s: t,
        world_position_m: tip.translation.vector.into(),
        orientation: Orientation::AlongShaft,
    };
    Track {
        arm,
        poses: vec![pose(0.0), pose(end_s)],
        jaw: vec![JawKey { time_s: 0.0, jaw_rad: start.tool.jaw_rad }, JawKey { time_s: open_s, jaw_rad }],
        events: Vec::new(),
    }
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
    let (emulator, addr) = udp_drives(&NODES);
    let transport = UdpCan::connect("127.0.0.1:0".parse().expect("an address"), addr).expect("bound");
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
    use knotlab_hw::rig_config::{RigConfigError, parse_rig_config};
    use knotlab_hw::skill::Skill;
    let bad = "description = \"x\"\n[arms.left]\ntrocar_m = [0.0, 0.1, 1.0]\nservo = { backend = \"dummy\" }\n\
               instrument = { backend = \"canopen\", nodes = [11, 11, 12, 0], counts_per_rad = [1.0, 0.0, 1.0, 1.0], \
               coupling = [[1.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]] }\n\
               [arms.right]\ntrocar_m = [0.0, -0.1, 1.0]\nservo = { backend = \"dummy\" }\n\
               instrument = { backend = \"dummy\", nodes = [1, 2, 3, 4] }\n\
               [arms.assist]\ntrocar_m = [0.1, 0.0, 1.0]\nservo = { backend = \"dummy\" }\n\
               instrument = { backend = \"canopen\", interface = \"can 0\", udp = \"127.0.0.1:47000\", nodes = [1, 2, 3, 4], counts_per_rad = [1.0, 1.0, 1.0, 1.0] }\n";
    let Err(RigConfigError::Invalid { problems, .. }) = parse_rig_config(bad, "rig.toml") else {
        panic!("problems expected")
    };
    let has = |key: &str, words: &str| problems.iter().any(|(k, r)| k == key && r.contains(words));
    assert!(has("arms.left.instrument.interface", "udp = \"ip:port\""), "{problems:?}");
    assert!(has("arms.left.instrument.nodes", "node 0"), "{problems:?}");
    assert!(has("arms.left.instrument.nodes", "each drive its own node"), "{problems:?}");
    assert!(has("arms.left.instrument.counts_per_rad", "not 0"), "{problems:?}");
    assert!(has("arms.left.instrument.coupling", "invertible"), "{problems:?}");
    assert!(has("arms.right.instrument.nodes", "only for backend \"canopen\""), "{problems:?}");
    assert!(has("arms.assist.instrument.udp", "either interface or udp"), "{problems:?}");
    assert!(has("arms.assist.instrument.interface", "\"can 0\""), "{problems:?}");

    let (emulator, addr) = udp_drives(&NODES);
    let (mut controller, rig) = left_arm_on(&format!("udp = \"{addr}\""));
    let track = open_jaw(&controller, &rig, ArmName::Left, 0.4, 0.2, 0.4);
    let skill = Skill { name: "open the jaw".into(), tracks: vec![track] };
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

/// Guards the controller over a drop-out: two arms' instruments on CiA 402 drives, both moving; the
/// left's pitch node drops out mid-run. The run faults naming the node within the heartbeat's time-out,
/// the controller writes nothing more (every drive, the right's and the left's other three, stays
/// enabled where it stood), and shutdown then takes down every drive that still answers.
#[test]
fn a_node_dropping_out_mid_run_faults_the_run_and_every_other_device_holds() {
    use knotlab_hw::controller::{ControllerError, Status};
    use knotlab_hw::rig::Rig;
    use knotlab_hw::rig_config::{build_rig, parse_rig_config};
    use knotlab_hw::skill::Skill;
    let left_nodes = [11, 12, 13, 14];
    let right_nodes = [21, 22, 23, 24];
    let (left, left_addr) = udp_drives(&left_nodes);
    let (right, right_addr) = udp_drives(&right_nodes);
    let text = format!(
        "description = \"two dummy arms with CANopen drives\"\n[controller]\nperiod_s = 0.002\nreal_time = true\n\
         [arms.left]\ntrocar_m = [-0.08, 0.12, 1.02]\nservo = {{ backend = \"dummy\" }}\n{}\
         [arms.right]\ntrocar_m = [-0.08, -0.12, 1.02]\nservo = {{ backend = \"dummy\" }}\n{}\
         [pedals]\nbackend = \"dummy\"\n",
        canopen_line(&format!("udp = \"{left_addr}\""), left_nodes),
        canopen_line(&format!("udp = \"{right_addr}\""), right_nodes),
    );
    let config = parse_rig_config(&text, "two-canopen.toml").expect("a rig with CANopen drives");
    let rig = Rig::shipped().expect("the shipped rig");
    let (mut controller, _handles) =
        build_rig(&config, &rig, None).expect("built").into_controller().expect("a controller");
    let tracks = vec![
        open_jaw(&controller, &rig, ArmName::Left, 0.6, 2.0, 2.0),
        open_jaw(&controller, &rig, ArmName::Right, 0.6, 2.0, 2.0),
    ];
    controller.load_skill(Skill { name: "open both jaws".into(), tracks }).expect("loaded");
    let jaw_counts = |drives: &CanopenEmulator| drives.nodes()[3].2;
    let mut dropped_at = None;
    let error = loop {
        match controller.step() {
            Ok(record) => {
                assert_ne!(record.status, Status::Finished, "the run ended without noticing the drop-out");
                if dropped_at.is_none() && record.skill_time_s >= 0.3 {
                    assert!(jaw_counts(&right) > 100, "the right's jaw is opening: {:?}", right.nodes());
                    left.drop_out(12);
                    dropped_at = Some(Instant::now());
                }
            }
            Err(error) => {
                assert!(dropped_at.is_some(), "faulted before the drop-out: {error}");
                break error;
            }
        }
    };
    let noticed_s = dropped_at.expect("dropped out before the fault").elapsed().as_secs_f64();
    let text = error.to_string();
    assert!(matches!(error, ControllerError::Device(_)), "{text}");
    assert!(text.contains("node 12 (pitch): heartbeat lost"), "{text}");
    assert!(noticed_s < 0.5, "noticed {noticed_s:.3} s after the drop-out (time-out 0.05 s)");
    assert_eq!(controller.record().status, Status::Faulted);
    // Nothing more is written: every other drive stays enabled where it stood. Frames sent before the
    // fault may still be on their way to the emulator's thread, so the drives are read once they have
    // stood still for 50 ms (within 2 s), then again 200 ms later.
    let settled = |drives: &CanopenEmulator| {
        let started = Instant::now();
        let mut last = drives.nodes();
        loop {
            std::thread::sleep(Duration::from_millis(50));
            let now = drives.nodes();
            if now == last || started.elapsed() > Duration::from_secs(2) {
                break now;
            }
            last = now;
        }
    };
    let (left_then, right_then) = (settled(&left), settled(&right));
    std::thread::sleep(Duration::from_millis(200));
    assert!(matches!(controller.step(), Err(ControllerError::NotRunning { .. })));
    assert_eq!(left.nodes(), left_then);
    assert_eq!(right.nodes(), right_then);
    let enabled = |nodes: &[(u8, DriveState, i32)]| {
        nodes.iter().filter(|(_, state, _)| *state == DriveState::OperationEnabled).count()
    };
    assert_eq!(enabled(&right_then), 4, "{right_then:?}");
    assert_eq!(enabled(&left_then), 4, "the silent node stays enabled too: {left_then:?}");
    // Shutdown takes down what answers and names what does not.
    let error = controller.shutdown().expect_err("the pitch's node cannot be taken down");
    assert!(error.to_string().contains("node 12 (pitch)"), "{error}");
    assert!(right.nodes().iter().all(|(_, state, _)| *state == DriveState::SwitchOnDisabled));
    let left_after = left.nodes();
    assert!(
        left_after.iter().all(|(node, state, _)| (*node == 12) == (*state == DriveState::OperationEnabled)),
        "{left_after:?}"
    );
}

/// Guards the SocketCAN transport on a virtual CAN interface: the drives' emulator on one socket, the
/// driver on another (SocketCAN passes each socket's frames to the others), enabled and following, and
/// a rig whose instrument names the interface. It needs `vcan0` (`ip link add dev vcan0 type vcan &&
/// ip link set up vcan0`; `KNOTLAB_VCAN` names another), which few machines have, so it is ignored
/// unless asked for; asked for without one, it fails saying so. `scripts/test` runs it where vcan0 is
/// up and prints that it did not run where it is not.
#[cfg(target_os = "linux")]
#[test]
#[ignore = "needs a vcan0 interface; scripts/test runs it where there is one"]
fn the_drives_answer_over_socketcan_on_vcan() {
    use knotlab_hw::canopen::socketcan::SocketCan;
    use knotlab_hw::skill::Skill;
    let interface = std::env::var("KNOTLAB_VCAN").unwrap_or_else(|_| "vcan0".into());
    let open = |what: &str| {
        SocketCan::open(&interface).unwrap_or_else(|e| {
            panic!(
                "NOT RUN: no virtual CAN interface for the {what}: {e} \
                 (ip link add dev {interface} type vcan && ip link set up {interface})"
            )
        })
    };
    let nodes = NODES.iter().map(|n| NodeConfig::new(*n)).collect();
    let emulator = CanopenEmulator::start(
        Box::new(open("emulator")),
        CanopenEmulatorConfig { nodes, sync_period_s: 0.002 },
    );
    let mut drive =
        CanopenDrive::connect(Box::new(open("driver")), config()).expect("connected over SocketCAN");
    let target = ToolJoints { roll_rad: 0.2, pitch_rad: -0.1, yaw_rad: 0.04, jaw_rad: 0.5 };
    let read = run(&mut drive, &target, 300).expect("the drives follow");
    assert!((read.roll_rad - 0.2).abs() < 2e-4 && (read.jaw_rad - 0.5).abs() < 2e-4, "{read:?}");
    let counts: Vec<i32> = emulator.nodes().iter().map(|(_, _, p)| *p).collect();
    assert_eq!(counts, vec![2000, -1000, 400, 5200], "the jaw's motor turns 0.5 + 0.5 x 0.04 rad");
    drive.shutdown().expect("taken down");
    assert!(emulator.nodes().iter().all(|(_, state, _)| *state == DriveState::SwitchOnDisabled));

    let (mut controller, rig) = left_arm_on(&format!("interface = \"{interface}\""));
    let track = open_jaw(&controller, &rig, ArmName::Left, 0.3, 0.2, 0.4);
    controller.load_skill(Skill { name: "open the jaw".into(), tracks: vec![track] }).expect("loaded");
    controller.run_to_end(|_| {}).expect("run");
    std::thread::sleep(Duration::from_millis(20));
    let measured = controller.record().arm(ArmName::Left).expect("the left arm").measured;
    assert!((measured.tool.jaw_rad - 0.3).abs() < 0.01, "{:?}", measured.tool);
    controller.shutdown().expect("the drives taken down");
}
