//! `knotlab canopen-emulator` end to end: the binary's drives answer the CiA 402 driver over loopback
//! UDP (enabled, following, taken down), and it stops after its duration listing each node; bad
//! arguments are refused by name.

use std::io::Read;
use std::process::Command;
use std::time::{Duration, Instant};

use knotlab_hw::canopen::drive::{CanopenConfig, CanopenDrive};
use knotlab_hw::canopen::udp::UdpCan;
use knotlab_hw::device::InstrumentDrive;
use knotlab_hw::kinematics::ToolJoints;
use knotlab_hw::rig::ArmName;

/// The driver enables the emulator's four drives, moves them to a target (10,000 counts per radian)
/// and takes them down; the emulator's closing lines show each node disabled where it was sent.
#[test]
fn the_emulator_s_drives_follow_the_driver() {
    let (mut child, mut stdout, _, addr) = crate::common::emulator(&[
        "canopen-emulator",
        "--bind",
        "127.0.0.1:0",
        "--nodes",
        "21,22,23,24",
        "--duration-s",
        "2",
    ]);
    let transport = UdpCan::connect("127.0.0.1:0".parse().expect("an address"), addr).expect("bound");
    let config = CanopenConfig::new(ArmName::Right, [21, 22, 23, 24], 10_000.0);
    let mut drive = CanopenDrive::connect(Box::new(transport), config).expect("the drives enabled");
    let target = ToolJoints { roll_rad: 0.1, pitch_rad: -0.2, yaw_rad: 0.05, jaw_rad: 0.4 };
    let start = Instant::now();
    let read = loop {
        drive.write(&target).expect("written");
        std::thread::sleep(Duration::from_millis(2));
        let read = drive.read().expect("read").joints;
        if start.elapsed() > Duration::from_millis(300) {
            break read;
        }
    };
    assert!((read.pitch_rad + 0.2).abs() < 2e-4 && (read.jaw_rad - 0.4).abs() < 2e-4, "{read:?}");
    drive.shutdown().expect("taken down");
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).expect("the closing lines");
    assert!(child.wait().expect("it exits").success());
    for line in ["node 21: SwitchOnDisabled, at 1000 counts", "node 24: SwitchOnDisabled, at 4000 counts"] {
        assert!(rest.contains(line), "{line:?} not in {rest:?}");
    }
}

/// A node outside 1 to 127, a remote address without --allow-remote and a period of 0 are refused,
/// each named.
#[test]
fn bad_arguments_are_refused_by_name() {
    for (args, words) in [
        (&["--bind", "127.0.0.1:0", "--nodes", "11,0", "--duration-s", "0.1"][..], "node 0"),
        (&["--bind", "0.0.0.0:0", "--duration-s", "0.1"][..], "loopback"),
        (&["--bind", "127.0.0.1:0", "--sync-period-ms", "0", "--duration-s", "0.1"][..], "--sync-period-ms"),
        (&["--bind", "127.0.0.1:0", "--duration-s", "NaN"][..], "--duration-s: NaN"),
    ] {
        let output = Command::new(env!("CARGO_BIN_EXE_knotlab"))
            .arg("canopen-emulator")
            .args(args)
            .output()
            .expect("the binary runs");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success() && stderr.contains(words), "{args:?}: {stderr}");
    }
}
