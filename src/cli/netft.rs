//! `knotlab netft-emulator`: an ATI Net F/T box on UDP, speaking RDT and streaming a force you choose,
//! to try the Net F/T driver and rig configs without the sensor.

use std::net::SocketAddr;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use knotlab_hw::netft::emulator::{NetFtEmulator, NetFtEmulatorConfig};

use super::numbers::parse_vector3;
use super::output::{Output, outln};

#[derive(Debug, Args)]
pub struct NetFtEmulatorArgs {
    /// Address to listen on, ip:port (a real box listens on port 49152; port 0: any free port).
    /// Loopback only unless --allow-remote.
    #[arg(long)]
    bind: SocketAddr,
    /// The force it measures, its own frame, N: `fx,fy,fz`.
    #[arg(long, value_parser = parse_vector3, allow_hyphen_values = true, default_value = "0,0,0")]
    force: nalgebra::Vector3<f64>,
    /// The torque it measures, N m: `tx,ty,tz`.
    #[arg(long, value_parser = parse_vector3, allow_hyphen_values = true, default_value = "0,0,0")]
    torque: nalgebra::Vector3<f64>,
    /// Records a second while streaming (the real box: up to 7000).
    #[arg(long, default_value_t = 1000.0)]
    rate_hz: f64,
    /// Counts per newton of its calibration (give the rig config the same).
    #[arg(long, default_value_t = 1.0e6)]
    counts_per_force: f64,
    /// Counts per newton-metre.
    #[arg(long, default_value_t = 1.0e6)]
    counts_per_torque: f64,
    /// Drop this fraction of the records (0 to 1), their sequence numbers skipped (to exercise a
    /// driver's loss counting).
    #[arg(long, default_value_t = 0.0)]
    drop: f64,
    /// Seeds which records are dropped.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Stop after this many seconds (default: at Ctrl-C).
    #[arg(long)]
    duration_s: Option<f64>,
    /// Allow binding an address other than loopback (the emulator then answers anyone who reaches it).
    #[arg(long)]
    allow_remote: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: NetFtEmulatorArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    super::serve::check_duration(args.duration_s)?;
    let wrench = [args.force.x, args.force.y, args.force.z, args.torque.x, args.torque.y, args.torque.z];
    if wrench.iter().any(|x| !x.is_finite()) {
        anyhow::bail!("--force, --torque: {wrench:?} is not finite");
    }
    let config = NetFtEmulatorConfig {
        bind: args.bind,
        allow_remote: args.allow_remote,
        rate_hz: args.rate_hz,
        counts_per_force: args.counts_per_force,
        counts_per_torque: args.counts_per_torque,
        wrench,
        drop_fraction: args.drop,
        seed: args.seed,
    };
    let emulator = NetFtEmulator::start(config).context("netft-emulator")?;
    outln!(
        out,
        "listening on {} (streaming {} records a second of force {:?} N, torque {:?} N m{})",
        emulator.local_addr(),
        args.rate_hz,
        args.force.as_slice(),
        args.torque.as_slice(),
        if args.drop > 0.0 { format!(", dropping {} of them", args.drop) } else { String::new() }
    );
    super::serve::until_stopped(args.duration_s)?;
    let report = emulator.stop().context("netft-emulator")?;
    if args.json {
        outln!(
            out,
            "{}",
            serde_json::json!({
                "requests": report.requests,
                "records_sent": report.records_sent,
                "records_dropped": report.records_dropped,
                "biases": report.biases,
                "malformed": report.malformed,
                "problems": report.problems,
            })
        );
    } else {
        outln!(
            out,
            "{} requests, {} records sent, {} dropped, {} biases, {} malformed",
            report.requests,
            report.records_sent,
            report.records_dropped,
            report.biases,
            report.malformed
        );
        for problem in &report.problems {
            out.error(format!("warning: {problem}"));
        }
    }
    Ok(ExitCode::SUCCESS)
}
