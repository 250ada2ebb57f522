//! `knotlab melfa-emulator` end to end: the binary serves a MELFA driver session over loopback UDP in
//! the pre-H7 layout, drops every third reply as asked, ends cleanly on END with a summary; a remote
//! address is refused unless allowed.

use super::common;

use std::io::Read;

use knotlab_hw::device::ArmServo;
use knotlab_hw::melfa::{Layout, MelfaArm, MelfaConfig};
use knotlab_hw::rig::{ArmName, Rig};

/// The MELFA emulator serves a pre-H7 driver session over loopback, drops every third reply as asked, and on
/// END exits cleanly with a summary matching the moves, the drops and the final joints.
#[test]
fn the_emulator_serves_a_session_and_exits_on_end() {
    let (mut child, mut stdout, first, addr) = common::emulator(&[
        "melfa-emulator",
        "--bind",
        "127.0.0.1:0",
        "--layout",
        "pre-h7",
        "--drop-every",
        "3",
        "--no-pace",
        "--idle-timeout-s",
        "30",
        "--json",
    ]);
    assert!(first.contains("layout pre-h7") && first.contains("dropping one reply in 3"), "{first}");

    let rig = Rig::shipped().unwrap();
    let limits = rig.arm(ArmName::Left).model.limits;
    let mut config = MelfaConfig::new(ArmName::Left, addr, &limits);
    config.layout = Layout::PreH7;
    let mut melfa = MelfaArm::connect(config).unwrap();
    let ready = ArmName::Left.ready_joints().arm_rad;
    let start = melfa.read().unwrap().joints_rad;
    assert!(start.iter().zip(&ready).all(|(a, b)| (a - b).abs() < 1e-6), "{start:?}");
    let mut fresh = 0;
    for k in 1..=12 {
        let mut target = ready;
        target[0] += 0.001 * f64::from(k);
        melfa.write(&target).unwrap();
        fresh += usize::from(melfa.read().unwrap().fresh);
    }
    let stats = melfa.link_stats().unwrap();
    melfa.shutdown().unwrap();
    let status = child.wait().expect("the emulator exits");
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).unwrap();
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    assert!(status.success(), "exit {status:?}: {rest} {stderr}");
    // Every third reply of the session is dropped: connect's NULL and the first read's keep-alive get
    // replies 1 and 2, the twelve MOVEs replies 3 to 14, of which 3, 6, 9 and 12 are lost.
    assert_eq!(stats.lost_total, 4);
    assert_eq!(fresh, 8);
    let summary: serde_json::Value =
        serde_json::from_str(rest.trim()).unwrap_or_else(|e| panic!("{e}: {rest}"));
    assert_eq!(summary["ended"], true);
    assert_eq!(summary["moves"], 12);
    assert_eq!(summary["replies_dropped"].as_u64(), Some(stats.lost_total));
    assert_eq!(summary["malformed"], 0);
    let final_j1 = summary["final_joints_rad"][0].as_f64().unwrap();
    assert!((final_j1 - (ready[0] + 0.012)).abs() < 1e-6, "{final_j1}");
}

/// The MELFA emulator refuses to bind a non-loopback address without `--allow-remote`.
#[test]
fn a_remote_address_is_refused_without_allow_remote() {
    let (code, _, stderr) = common::knotlab(&["melfa-emulator", "--bind", "0.0.0.0:0"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("refusing to bind 0.0.0.0:0: not a loopback address"), "{stderr}");
}

/// The emulator refuses a start pose beyond the arm's limits (it served 99 rad on axis 1) and an idle
/// time-out that is not a number of seconds (NaN waited for ever), before binding anything.
#[test]
fn a_start_beyond_the_limits_or_a_nan_time_out_is_refused() {
    let (code, _, stderr) =
        common::knotlab(&["melfa-emulator", "--bind", "127.0.0.1:0", "--joints", "99,0,0,0,0,0"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--joints: axis 1 = 99 rad is outside the left arm's limits"), "{stderr}");
    let (code, _, stderr) =
        common::knotlab(&["melfa-emulator", "--bind", "127.0.0.1:0", "--idle-timeout-s", "nan"]);
    assert_eq!(code, 1);
    assert!(stderr.contains("--idle-timeout-s: NaN is not a positive, finite number of seconds"), "{stderr}");
}
