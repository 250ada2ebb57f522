//! The MELFA driver against the in-process emulator over loopback UDP: the session (NULL seeds the
//! joints, MOVE each cycle, NULL keep-alive, END ends the emulator), both layouts, per-cycle step
//! clamping (an unclamped jump faults the emulated controller), 10 % of replies dropped without a
//! fault, a run of 100 lost replies faulting the rig and leaving the arm standing, malformed replies
//! refused with a clear error, and the emulator's loopback-only binding.

use super::rigs;

use std::net::UdpSocket;
use std::time::Duration;

use knotlab_hw::controller::{ControllerError, RunOutcome, Status};
use knotlab_hw::device::{ArmServo, DeviceError};
use knotlab_hw::melfa::codec::MAX_LEN;
use knotlab_hw::melfa::emulator::{ArmFault, DropPolicy, Emulator, EmulatorError};
use knotlab_hw::melfa::session::max_steps;
use knotlab_hw::melfa::{CR750_CYCLE_S, Command, Data, DataType, Layout, MelfaArm, MelfaConfig, Packet};
use knotlab_hw::rig::ArmName;
use knotlab_hw::rig_config::{build_rig, parse_rig_config};
use nalgebra::Vector3;

use rigs::{emulator_config, parked, reach_skill, rig, spawn_emulator};

const ARM: ArmName = ArmName::Left;

fn close(a: &[f64; 6], b: &[f64; 6], tol: f64) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

fn session(layout: Layout) {
    let (start, _) = parked(ARM);
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, layout, DropPolicy::Never, 0.0));
    let limits = rig().arm(ARM).model.limits;
    let mut config = MelfaConfig::new(ARM, addr, &limits);
    config.layout = layout;
    let mut melfa = MelfaArm::connect(config).expect("the session works");
    // The NULL reply seeds the joints: the emulator's, to f32 precision.
    let first = melfa.read().expect("the session works");
    assert!(first.fresh);
    assert!(close(&first.joints_rad, &start.arm_rad, 1e-6), "{:?}", first.joints_rad);
    // A MOVE with a small step; the next read reports it (no filter: reached in one cycle).
    let mut target = start.arm_rad;
    target[1] += 0.01;
    melfa.write(&target).expect("the session works");
    let moved = melfa.read().expect("the session works");
    assert!(close(&moved.joints_rad, &target, 1e-6), "{:?}", moved.joints_rad);
    // Two reads without a write: a NULL keep-alive each.
    melfa.read().expect("the session works");
    melfa.read().expect("the session works");
    let stats = melfa.link_stats().expect("the session works");
    assert_eq!((stats.keep_alives, stats.lost_total), (3, 0), "{stats:?}");
    let reply = *melfa.last_reply().expect("the session works");
    assert_eq!(reply.command, Command::Null);
    assert_eq!(reply.send_type, DataType::FilteredJoint);
    if layout == Layout::H7 {
        assert_eq!(reply.monitors[0].kind, DataType::FeedbackJoint);
        assert!(matches!(reply.monitors[1].data, Data::Pose(_)), "{reply:?}");
    }
    melfa.shutdown().expect("the session works");
    let report = emulator.join().expect("the emulator thread ends").expect("the emulator ends cleanly");
    assert!(report.ended, "END ends the emulator's session");
    // Connect's NULL, the first read's NULL, one MOVE, two keep-alives.
    assert_eq!((report.nulls, report.moves, report.malformed), (4, 1, 0), "{report:?}");
    assert!(matches!(melfa.write(&target), Err(DeviceError::Closed { .. })));
}

/// An H7 session seeds the joints from NULL, reaches a MOVE in one cycle, keeps alive with NULLs and is
/// ended by END, after which writes are refused as closed.
#[test]
fn an_h7_session_seeds_moves_keeps_alive_and_ends() {
    session(Layout::H7);
}

/// A pre-H7 session seeds the joints from NULL, reaches a MOVE in one cycle, keeps alive with NULLs and
/// is ended by END, after which writes are refused as closed.
#[test]
fn a_pre_h7_session_seeds_moves_keeps_alive_and_ends() {
    session(Layout::PreH7);
}

/// The driver clamps each commanded step to the axis's per-cycle maximum, reaching a far goal in the
/// fewest cycles without faulting the emulated controller.
#[test]
fn the_driver_clamps_each_step_so_the_controller_never_faults() {
    let (start, _) = parked(ARM);
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, Layout::H7, DropPolicy::Never, 0.0));
    let limits = rig().arm(ARM).model.limits;
    let max = max_steps(&limits, CR750_CYCLE_S);
    let mut melfa = MelfaArm::connect(MelfaConfig::new(ARM, addr, &limits)).unwrap();
    let mut goal = start.arm_rad;
    goal[0] += 0.3;
    goal[3] -= 0.2;
    let mut last = melfa.read().unwrap().joints_rad;
    let mut cycles = 0;
    while !close(&last, &goal, 1e-5) {
        melfa.write(&goal).unwrap();
        let now = melfa.read().unwrap().joints_rad;
        for i in 0..6 {
            assert!((now[i] - last[i]).abs() <= max[i] + 1e-5, "axis {} stepped {}", i + 1, now[i] - last[i]);
        }
        last = now;
        cycles += 1;
        assert!(cycles < 100, "reaches the goal");
    }
    // Axis 1 at 250 deg/s moves 0.031 rad per 7.11 ms cycle: 0.3 rad takes 10 cycles.
    assert_eq!(cycles, (0.3 / max[0]).ceil() as u64);
    assert_eq!(melfa.link_stats().unwrap().clamped, cycles - 1);
    melfa.end().unwrap();
    let report = emulator.join().unwrap().unwrap();
    assert!(report.ended);
}

/// A MOVE jumping an axis 0.2 rad in one cycle faults the emulated controller for over-speed on that
/// joint, and the faulted controller sends no reply.
#[test]
fn an_unclamped_jump_faults_the_emulated_controller() {
    let (start, _) = parked(ARM);
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, Layout::H7, DropPolicy::Never, 0.0));
    let pc = UdpSocket::bind("127.0.0.1:0").unwrap();
    let mut buf = [0_u8; MAX_LEN];
    let mut packet = Packet::command(Command::Move, DataType::FilteredJoint, [DataType::Null; 3], 1);
    packet.send_type = DataType::Joint;
    let mut j = start.arm_rad.map(|q| q as f32);
    j[2] += 0.2;
    packet.data = Data::Joint([j[0], j[1], j[2], j[3], j[4], j[5], 0.0, 0.0]);
    let n = packet.encode(Layout::H7, &mut buf);
    pc.send_to(&buf[..n], addr).unwrap();
    match emulator.join().unwrap() {
        Err(EmulatorError::Fault { fault: ArmFault::OverSpeed { joint: 3, step_rad, .. }, report }) => {
            assert!((step_rad - 0.2).abs() < 1e-6);
            assert_eq!(report.replies_sent, 0, "a faulted controller does not answer");
        }
        other => panic!("expected an over-speed fault, got {other:?}"),
    }
}

fn melfa_rig_text(addr: std::net::SocketAddr) -> String {
    let t = rigs::trocar(ARM);
    format!(
        "description = \"one MELFA arm on the emulator\"\n\
         [arms.left]\n\
         trocar_m = [{}, {}, {}]\n\
         servo = {{ backend = \"melfa\", controller = \"{addr}\", layout = \"h7\", cycle_s = {CR750_CYCLE_S} }}\n\
         instrument = {{ backend = \"dummy\" }}\n\
         force = {{ backend = \"dummy\" }}\n",
        t.x, t.y, t.z
    )
}

/// With one reply in ten dropped, a MELFA rig's skill still completes on its last target, its losses
/// counted as stale cycles, and no command needs the driver's clamp.
#[test]
fn ten_percent_of_replies_dropped_and_the_skill_still_completes() {
    let (_, tip) = parked(ARM);
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, Layout::H7, DropPolicy::Every(10), 0.0));
    let config = parse_rig_config(&melfa_rig_text(addr), "melfa-test.toml").unwrap();
    let (mut controller, _) = build_rig(&config, &rig(), None).unwrap().into_controller().unwrap();
    assert!((controller.period_s() - CR750_CYCLE_S).abs() < 1e-15, "the cycle follows the MELFA period");
    let skill = reach_skill(ARM, tip, Vector3::new(0.02, -0.01, -0.015), 2.0);
    let last_target = skill.tracks[0].target_at(2.0).unwrap();
    controller.load_skill(skill).unwrap();
    let mut stale = 0;
    let summary = controller.run_to_end(|r| stale += usize::from(!r.arm(ARM).unwrap().fresh)).unwrap();
    assert_eq!(summary.outcome, RunOutcome::Completed);
    let stats = controller.link_stats(ARM).unwrap();
    // One reply in ten is dropped: the losses are the stale cycles, and about a tenth of the exchanges.
    assert_eq!(stats.lost_total, stale as u64);
    let expected = stats.exchanges / 10;
    assert!(stats.lost_total.abs_diff(expected) <= 1, "{stats:?}");
    assert!(stats.lost_total >= 25, "{stats:?}");
    assert_eq!(stats.clamped, 0, "the controller's commands never needed the driver's clamp");
    // Hold a few cycles (keep-alives) so the last set-point is reported, then check the tip.
    for _ in 0..3 {
        controller.step().unwrap();
    }
    let record = controller.record();
    let tip_now = record.arm(ARM).unwrap().world_from_tip.translation.vector;
    assert!((tip_now - last_target.world_position_m).norm() < 1e-5, "{tip_now:?}");
    controller.shutdown().unwrap();
    let report = emulator.join().unwrap().unwrap();
    assert!(report.ended);
    assert_eq!(report.replies_dropped, stats.lost_total);
}

/// A run of 100 lost replies faults the rig with a link-down error, and no MOVE is sent after the fault,
/// so the arm holds its last command.
#[test]
fn a_run_of_100_lost_replies_faults_the_rig_and_the_arm_stands_still() {
    let (_, tip) = parked(ARM);
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, Layout::H7, DropPolicy::AllAfter(60), 0.02));
    let config = parse_rig_config(&melfa_rig_text(addr), "melfa-test.toml").unwrap();
    let (mut controller, _) = build_rig(&config, &rig(), None).unwrap().into_controller().unwrap();
    controller.load_skill(reach_skill(ARM, tip, Vector3::new(0.02, -0.01, -0.015), 2.0)).unwrap();
    let mut writes = 0_u64;
    let error = controller.run_to_end(|r| writes += u64::from(r.arm(ARM).unwrap().wrote)).unwrap_err();
    match &error {
        ControllerError::Device(DeviceError::LinkDown { lost, .. }) => assert_eq!(*lost, 100),
        other => panic!("expected the link to go down, got {other}"),
    }
    assert!(error.to_string().contains("100 replies lost in a row"), "{error}");
    assert_eq!(controller.status(), Status::Faulted);
    assert!(matches!(controller.step(), Err(ControllerError::NotRunning { .. })));
    // Nothing more is sent after the fault: END (from shutdown) is the next packet the emulator sees.
    std::thread::sleep(Duration::from_millis(50));
    controller.shutdown().unwrap();
    let report = emulator.join().unwrap().unwrap();
    assert!(report.ended);
    // Every MOVE the emulated controller got came from a cycle before the fault: since then it has
    // had no new command, so the arm holds the last one.
    assert_eq!(report.moves, writes, "no MOVE after the fault");
    assert_eq!(report.replies_dropped, 100);
}

/// A pre-H7 reply to a driver expecting H7 is refused as a protocol error naming the servo, the sender,
/// both sizes and the other layout.
#[test]
fn a_reply_in_the_wrong_layout_is_refused_clearly() {
    // A fake controller that answers in the pre-H7 layout while the driver expects H7.
    let fake = UdpSocket::bind("127.0.0.1:0").unwrap();
    let addr = fake.local_addr().unwrap();
    let server = std::thread::spawn(move || {
        let mut buf = [0_u8; 512];
        let (_, from) = fake.recv_from(&mut buf).unwrap();
        let reply = Packet {
            send_type: DataType::FilteredJoint,
            data: Data::Joint([0.1; 8]),
            ..Packet::command(Command::Null, DataType::FilteredJoint, [DataType::Null; 3], 0)
        };
        let mut out = [0_u8; MAX_LEN];
        let n = reply.encode(Layout::PreH7, &mut out);
        fake.send_to(&out[..n], from).unwrap();
    });
    let limits = rig().arm(ARM).model.limits;
    let error = MelfaArm::connect(MelfaConfig::new(ARM, addr, &limits)).err().expect("refused");
    server.join().unwrap();
    let text = error.to_string();
    assert!(matches!(error, DeviceError::Protocol { .. }), "{text}");
    assert!(text.starts_with("left arm servo: reply from 127.0.0.1:"), "{text}");
    assert!(text.contains("64 bytes; the h7 layout has 196") && text.contains("pre-h7"), "{text}");
}

/// Connecting to a controller that never answers fails as a link down after the allowed lost replies.
#[test]
fn a_controller_that_never_answers_is_a_link_down() {
    // A bound socket that never replies.
    let silent = UdpSocket::bind("127.0.0.1:0").unwrap();
    let limits = rig().arm(ARM).model.limits;
    let mut config = MelfaConfig::new(ARM, silent.local_addr().unwrap(), &limits);
    config.max_lost = 5;
    config.receive_timeout_s = 0.005;
    let error = MelfaArm::connect(config).err().expect("no session");
    assert!(matches!(error, DeviceError::LinkDown { lost: 5, .. }), "{error}");
}

/// The emulator counts malformed packets, reporting each one's number and its whole size (a 65,507-byte
/// datagram was reported as the 197 bytes its buffer held), and keeps answering the packets after them.
#[test]
fn the_emulator_ignores_malformed_packets_and_keeps_serving() {
    let (addr, emulator) = spawn_emulator(emulator_config(ARM, Layout::H7, DropPolicy::Never, 0.0));
    let pc = UdpSocket::bind("127.0.0.1:0").unwrap();
    pc.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
    pc.send_to(&[1, 2, 3], addr).unwrap();
    pc.send_to(&vec![0_u8; 65_507], addr).unwrap();
    let mut buf = [0_u8; MAX_LEN];
    let n =
        Packet::command(Command::Null, DataType::Joint, [DataType::Null; 3], 9).encode(Layout::H7, &mut buf);
    pc.send_to(&buf[..n], addr).unwrap();
    let mut rx = [0_u8; 512];
    let (got, _) = pc.recv_from(&mut rx).unwrap();
    let reply = Packet::decode(&rx[..got], Layout::H7).unwrap();
    assert_eq!((reply.command, reply.send_type, reply.c_count), (Command::Null, DataType::Joint, 9));
    let n =
        Packet::command(Command::End, DataType::Null, [DataType::Null; 3], 10).encode(Layout::H7, &mut buf);
    pc.send_to(&buf[..n], addr).unwrap();
    let report = emulator.join().unwrap().unwrap();
    assert_eq!((report.malformed, report.nulls), (2, 1));
    assert!(
        report.problems[0].contains("packet 1") && report.problems[0].contains("3 bytes"),
        "{:?}",
        report.problems
    );
    assert!(report.problems[1].contains("packet is 65507 bytes"), "{:?}", report.problems);
}

/// A paced emulator counts the 7.11 ms cycles that pass between packets, in its replies and its report.
#[test]
fn a_paced_emulator_counts_the_cycles_between_packets() {
    let mut config = emulator_config(ARM, Layout::H7, DropPolicy::Never, 0.0);
    config.pace = true;
    let (addr, emulator) = spawn_emulator(config);
    let limits = rig().arm(ARM).model.limits;
    let mut melfa = MelfaArm::connect(MelfaConfig::new(ARM, addr, &limits)).unwrap();
    for _ in 0..5 {
        // 30 ms between packets: at least four 7.11 ms cycle boundaries pass.
        std::thread::sleep(Duration::from_millis(30));
        assert!(melfa.read().unwrap().fresh);
        assert!(melfa.last_reply().unwrap().t_count >= 3, "{:?}", melfa.last_reply());
    }
    melfa.end().unwrap();
    let report = emulator.join().unwrap().unwrap();
    assert!(report.cycles >= 5 * 4, "{report:?}");
}

/// The emulator refuses to bind a non-loopback address unless explicitly allowed to.
#[test]
fn the_emulator_binds_loopback_only_unless_told() {
    let config = emulator_config(ARM, Layout::H7, DropPolicy::Never, 0.0);
    let error = Emulator::bind("0.0.0.0:0".parse().unwrap(), false, config.clone()).err().expect("refused");
    assert!(matches!(error, EmulatorError::RemoteRefused { .. }), "{error}");
    assert!(error.to_string().contains("not a loopback address"), "{error}");
    let allowed = Emulator::bind("0.0.0.0:0".parse().unwrap(), true, config).unwrap();
    assert!(allowed.local_addr().unwrap().ip().is_unspecified());
}
