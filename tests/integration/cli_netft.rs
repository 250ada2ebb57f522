//! `knotlab netft-emulator` end to end: the binary streams the force asked for to the Net F/T driver
//! over loopback, dropping a fifth of the records as asked, and stops after its duration with a
//! summary; a remote address is refused unless allowed.

use std::io::Read;
use std::process::Command;
use std::time::{Duration, Instant};

use knotlab_hw::device::ForceSensor;
use knotlab_hw::netft::{NetFtConfig, NetFtSensor};
use knotlab_hw::rig::ArmName;

/// The emulator streams 0.2, -0.1, 1.5 N at 2,000 counts per newton; the driver reads it in newtons,
/// counts the dropped records, and the summary agrees.
#[test]
fn the_emulator_streams_a_force_to_the_driver() {
    let (mut child, mut stdout, _, addr) = crate::common::emulator(&[
        "netft-emulator",
        "--bind",
        "127.0.0.1:0",
        "--force",
        "0.2,-0.1,1.5",
        "--counts-per-force",
        "2000",
        "--drop",
        "0.2",
        "--duration-s",
        "1.5",
        "--json",
    ]);
    let mut sensor = NetFtSensor::connect(NetFtConfig::new(ArmName::Left, addr, 2000.0))
        .expect("connected to the emulator");
    let start = Instant::now();
    while sensor.stats().records < 100 {
        let reading = sensor.read().expect("a reading");
        if reading.fresh {
            let f = reading.shaft_force_n;
            assert!(
                (f.x - 0.2).abs() < 1e-3 && (f.y + 0.1).abs() < 1e-3 && (f.z - 1.5).abs() < 1e-3,
                "{f:?}"
            );
        }
        assert!(start.elapsed() < Duration::from_secs(1), "{:?}", sensor.stats());
        std::thread::sleep(Duration::from_millis(2));
    }
    sensor.shutdown().expect("the stream stopped");
    let stats = sensor.stats();
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).expect("the summary");
    assert!(child.wait().expect("it exits").success());
    let summary: serde_json::Value = serde_json::from_str(rest.trim()).expect("a JSON summary");
    assert_eq!(summary["requests"], 2, "{summary}");
    let dropped = summary["records_dropped"].as_u64().expect("a count");
    assert!(stats.lost <= dropped && dropped <= stats.lost + 20, "{stats:?} {summary}");
    let fraction = stats.lost as f64 / (stats.lost + stats.records) as f64;
    assert!((0.1..0.3).contains(&fraction), "lost {fraction}: {stats:?}");
}

/// A non-loopback address is refused, naming it, unless --allow-remote.
#[test]
fn a_remote_address_is_refused() {
    let output = Command::new(env!("CARGO_BIN_EXE_knotlab"))
        .args(["netft-emulator", "--bind", "0.0.0.0:0", "--duration-s", "0.1"])
        .output()
        .expect("the binary runs");
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("0.0.0.0:0") && stderr.contains("loopback"), "{stderr}");
}
