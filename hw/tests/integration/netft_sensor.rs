//! The Net F/T driver against the emulated box on loopback: a force read in newtons and turned into
//! the shaft frame; the box's bias; 10 % of the records lost, counted, the reading going on; a stalled
//! stream faulting the sensor by name; a box that never answers; the stream stopped at shutdown.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use knotlab_hw::device::{DeviceError, ForceSensor};
use knotlab_hw::netft::emulator::{NetFtEmulator, NetFtEmulatorConfig};
use knotlab_hw::netft::{NetFtConfig, NetFtSensor, RdtCommand, Request};
use knotlab_hw::rig::ArmName;
use nalgebra::{Rotation3, Vector3};

fn loopback() -> SocketAddr {
    "127.0.0.1:0".parse().expect("an address")
}

fn emulator(wrench: [f64; 6], drop_fraction: f64) -> NetFtEmulator {
    let config =
        NetFtEmulatorConfig { wrench, drop_fraction, seed: 7, ..NetFtEmulatorConfig::new(loopback()) };
    NetFtEmulator::start(config).expect("the emulator")
}

/// Reads every millisecond until a fresh reading comes (at most a second).
fn fresh(sensor: &mut NetFtSensor) -> Vector3<f64> {
    let start = Instant::now();
    loop {
        let reading = sensor.read().expect("a reading");
        if reading.fresh {
            return reading.shaft_force_n;
        }
        assert!(start.elapsed() < Duration::from_secs(1), "no fresh reading in a second");
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// Guards units and frames: counts become newtons by the calibration, the sensor's frame turns into
/// the shaft's; the box's bias zeroes the reading.
#[test]
fn a_force_is_read_in_newtons_in_the_shaft_frame_and_biased_away() {
    let box_ = emulator([0.5, -0.25, 1.0, 0.0, 0.0, 0.01], 0.0);
    let config = NetFtConfig {
        shaft_from_sensor: Rotation3::from_axis_angle(&Vector3::z_axis(), std::f64::consts::FRAC_PI_2),
        ..NetFtConfig::new(ArmName::Right, box_.local_addr(), 1.0e6)
    };
    let mut sensor = NetFtSensor::connect(config).expect("connected");
    let force = fresh(&mut sensor);
    assert!((force - Vector3::new(0.25, 0.5, 1.0)).norm() < 1e-9, "{force:?}");
    sensor.zero().expect("biased");
    std::thread::sleep(Duration::from_millis(20));
    let biased = fresh(&mut sensor);
    assert!(biased.norm() < 1e-9, "{biased:?}");
    box_.set_wrench([0.5, -0.25, 1.5, 0.0, 0.0, 0.0]);
    std::thread::sleep(Duration::from_millis(20));
    let more = fresh(&mut sensor);
    assert!((more - Vector3::new(0.0, 0.0, 0.5)).norm() < 1e-9, "{more:?}");
    let report = box_.stop().expect("the emulator's report");
    assert_eq!(report.biases, 1);
}

/// Guards loss counting: with a tenth of the records dropped, the driver counts the gaps (the box's
/// own count of what it dropped, within the records in flight) and keeps reading.
#[test]
fn a_tenth_of_the_records_lost_are_counted_and_the_reading_goes_on() {
    let box_ = emulator([0.0, 0.0, 2.0, 0.0, 0.0, 0.0], 0.1);
    let mut sensor =
        NetFtSensor::connect(NetFtConfig::new(ArmName::Left, box_.local_addr(), 1.0e6)).expect("connected");
    // Until 400 records have been sent or lost (0.4 s at the box's 1 kHz; longer on a busy machine).
    let mut fresh_reads = 0;
    let start = Instant::now();
    while sensor.stats().records + sensor.stats().lost < 400 {
        let reading = sensor.read().expect("a reading, lossy or not");
        if reading.fresh {
            fresh_reads += 1;
            assert!((reading.shaft_force_n - Vector3::new(0.0, 0.0, 2.0)).norm() < 1e-9);
        }
        assert!(start.elapsed() < Duration::from_secs(10), "{:?}", sensor.stats());
        std::thread::sleep(Duration::from_millis(2));
    }
    sensor.shutdown().expect("stopped");
    let stats = sensor.stats();
    let report = box_.stop().expect("the emulator's report");
    let seen = stats.records + stats.lost;
    let fraction = stats.lost as f64 / seen as f64;
    // 400 records, a tenth lost: 40 +- 6 (binomial), so 5 % to 15 % is beyond three deviations.
    assert!((0.05..0.15).contains(&fraction), "lost {fraction} of {seen}: {stats:?}");
    assert!(
        stats.lost <= report.records_dropped && report.records_dropped <= stats.lost + 20,
        "{stats:?} {report:?}"
    );
    assert!(fresh_reads >= 20, "{fresh_reads} fresh readings: {stats:?}");
}

/// Guards the stall: a box that stops streaming makes the reading stale, then faults the sensor with
/// its name once the stall time-out has passed.
#[test]
fn a_stalled_stream_faults_the_sensor() {
    let box_ = emulator([0.0; 6], 0.0);
    let config =
        NetFtConfig { stall_timeout_s: 0.05, ..NetFtConfig::new(ArmName::Assist, box_.local_addr(), 1.0e6) };
    let mut sensor = NetFtSensor::connect(config).expect("connected");
    fresh(&mut sensor);
    box_.stall(true);
    std::thread::sleep(Duration::from_millis(10));
    while sensor.read().is_ok() {}
    let start = Instant::now();
    let error = loop {
        match sensor.read() {
            Err(e) => break e,
            Ok(r) => assert!(!r.fresh),
        }
        assert!(start.elapsed() < Duration::from_secs(1));
    };
    assert!(matches!(error, DeviceError::LinkDown { .. }), "{error}");
    let text = error.to_string();
    assert!(text.contains("assist") && text.contains("stalled"), "{text}");
}

/// Guards start-up: a box that never answers is a time-out naming the sensor, not a hang.
#[test]
fn a_box_that_never_answers_is_a_time_out() {
    let silent = std::net::UdpSocket::bind(loopback()).expect("a silent socket");
    let config = NetFtConfig {
        stall_timeout_s: 0.05,
        ..NetFtConfig::new(ArmName::Left, silent.local_addr().expect("its address"), 1.0e6)
    };
    let error = NetFtSensor::connect(config).err().expect("no box");
    assert!(matches!(error, DeviceError::Timeout { .. }), "{error}");
    assert!(error.to_string().contains("left"), "{error}");
}

/// Guards the session's end: shutdown asks the box to stop (start and stop are its two requests), and
/// a box asked to stop sends nothing more.
#[test]
fn shutdown_stops_the_stream() {
    let box_ = emulator([0.0; 6], 0.0);
    let mut sensor =
        NetFtSensor::connect(NetFtConfig::new(ArmName::Right, box_.local_addr(), 1.0e6)).expect("connected");
    fresh(&mut sensor);
    sensor.shutdown().expect("stopped");
    assert!(matches!(sensor.read(), Err(DeviceError::Closed { .. })));
    // The same by hand: start, some records, stop, silence.
    let raw = std::net::UdpSocket::bind(loopback()).expect("a socket");
    raw.connect(box_.local_addr()).expect("connected");
    raw.set_read_timeout(Some(Duration::from_millis(50))).expect("a time-out");
    let request = |command| Request { command, sample_count: 0 }.encode();
    raw.send(&request(RdtCommand::StartRealTime)).expect("sent");
    let mut buf = [0u8; 64];
    assert_eq!(raw.recv(&mut buf).expect("a record"), 36);
    raw.send(&request(RdtCommand::Stop)).expect("sent");
    std::thread::sleep(Duration::from_millis(20));
    while raw.recv(&mut buf).is_ok() {}
    assert!(raw.recv(&mut buf).is_err(), "a record after stop");
    let report = box_.stop().expect("the report");
    assert_eq!(report.requests, 4, "{report:?}");
}

/// Guards the rig config: a force sensor of backend `netft` is checked key by key (its address and
/// calibration needed, its fields only for it), and a rig with one reads the box through the
/// controller: the emulator's force, turned from the sensor's frame into the shaft's and by the arm
/// into the world.
#[test]
fn a_rig_reads_a_netft_box_through_the_controller() {
    use knotlab_hw::rig::Rig;
    use knotlab_hw::rig_config::{RigConfigError, build_rig, parse_rig_config};
    let bad = "description = \"x\"\n[arms.right]\ntrocar_m = [-0.08, -0.12, 1.02]\nservo = { backend = \"dummy\" }\n\
               force = { backend = \"netft\", stall_timeout_s = -1.0 }\n[arms.left]\ntrocar_m = [0.0, 0.1, 1.0]\n\
               servo = { backend = \"dummy\" }\nforce = { backend = \"dummy\", counts_per_force = 1.0 }\n";
    let Err(RigConfigError::Invalid { problems, .. }) = parse_rig_config(bad, "rig.toml") else {
        panic!("problems expected")
    };
    let has = |key: &str, words: &str| problems.iter().any(|(k, r)| k == key && r.contains(words));
    assert!(has("arms.right.force.address", "49152"), "{problems:?}");
    assert!(has("arms.right.force.counts_per_force", "counts per newton"), "{problems:?}");
    assert!(has("arms.right.force.stall_timeout_s", "positive"), "{problems:?}");
    assert!(has("arms.left.force.counts_per_force", "only for backend \"netft\""), "{problems:?}");
    let box_ = emulator([0.0, 0.0, 1.5, 0.0, 0.0, 0.0], 0.0);
    let world_force = |rpy: &str| {
        let text = format!(
            "description = \"a dummy arm with a Net F/T box\"\n[controller]\nperiod_s = 0.002\nreal_time = true\n\
             [arms.right]\ntrocar_m = [-0.08, -0.12, 1.02]\nservo = {{ backend = \"dummy\" }}\n\
             instrument = {{ backend = \"dummy\" }}\n\
             force = {{ backend = \"netft\", address = \"{}\", counts_per_force = 1000000.0, shaft_from_sensor_rpy_rad = {rpy} }}\n\
             [pedals]\nbackend = \"dummy\"\n",
            box_.local_addr()
        );
        let config = parse_rig_config(&text, "netft.toml").expect("a rig with a Net F/T box");
        let rig = Rig::shipped().expect("the shipped rig");
        let (mut controller, _handles) =
            build_rig(&config, &rig, None).expect("built").into_controller().expect("a controller");
        let mut force = None;
        for _ in 0..200 {
            let record = controller.step().expect("a cycle");
            let f = record.arm(ArmName::Right).expect("the right arm").world_force_n;
            if f.norm() > 0.0 {
                force = Some(f);
                break;
            }
        }
        controller.shutdown().expect("the devices' sessions ended");
        force.expect("the box's force reached the controller")
    };
    let along = world_force("[0.0, 0.0, 0.0]");
    // A roll of pi about x turns the sensor's z against the shaft's: the same force, reversed.
    let reversed = world_force("[3.141592653589793, 0.0, 0.0]");
    assert!((along.norm() - 1.5).abs() < 1e-6, "{along:?}");
    assert!((along + reversed).norm() < 1e-6, "{along:?} {reversed:?}");
    let report = box_.stop().expect("the emulator's report");
    assert_eq!(report.requests, 4, "start and stop twice: {report:?}");
}
