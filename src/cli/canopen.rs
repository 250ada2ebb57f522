//! `knotlab canopen-emulator`: the instrument's four CiA 402 drives on CAN-over-UDP, to try the
//! CANopen instrument driver without the motors.

use std::net::SocketAddr;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use knotlab_hw::canopen::emulator::{CanopenEmulator, CanopenEmulatorConfig, NodeConfig};
use knotlab_hw::canopen::udp::UdpCan;

use super::output::{Output, outln};

#[derive(Debug, Args)]
pub struct CanopenEmulatorArgs {
    /// Address to listen on for CAN frames over UDP, ip:port (port 0: any free port). Loopback only
    /// unless --allow-remote.
    #[arg(long)]
    bind: SocketAddr,
    /// The drives' node ids (1 to 127), roll, pitch, yaw and jaw by default.
    #[arg(long, value_delimiter = ',', default_values_t = [11u8, 12, 13, 14])]
    nodes: Vec<u8>,
    /// The time between SYNCs the motors move by, ms (the controller's cycle).
    #[arg(long, default_value_t = 1.0)]
    sync_period_ms: f64,
    /// Each motor's lag, ms.
    #[arg(long, default_value_t = 5.0)]
    time_constant_ms: f64,
    /// Stop after this many seconds (default: at Ctrl-C).
    #[arg(long)]
    duration_s: Option<f64>,
    /// Allow binding an address other than loopback.
    #[arg(long)]
    allow_remote: bool,
}

pub fn run(args: CanopenEmulatorArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if !args.allow_remote && !args.bind.ip().is_loopback() {
        anyhow::bail!(
            "refusing to bind {}: not a loopback address (the emulator listens on loopback only unless --allow-remote)",
            args.bind
        );
    }
    if let Some(bad) = args.nodes.iter().find(|n| !(1..=127).contains(*n)) {
        anyhow::bail!("--nodes: node {bad}: CANopen nodes are 1 to 127");
    }
    if args.nodes.is_empty() || args.nodes.len() > 16 {
        anyhow::bail!("--nodes: 1 to 16 nodes, not {}", args.nodes.len());
    }
    for (name, ms) in
        [("--sync-period-ms", args.sync_period_ms), ("--time-constant-ms", args.time_constant_ms)]
    {
        if !(ms.is_finite() && ms > 0.0 && ms <= 10_000.0) {
            anyhow::bail!("{name}: {ms} is not a time of more than 0 and at most 10000 ms");
        }
    }
    super::serve::check_duration(args.duration_s)?;
    let transport = UdpCan::listen(args.bind).context("canopen-emulator")?;
    let addr = transport.local_addr().context("canopen-emulator")?;
    let nodes = args
        .nodes
        .iter()
        .map(|n| NodeConfig { time_constant_s: args.time_constant_ms * 1e-3, ..NodeConfig::new(*n) })
        .collect();
    let emulator = CanopenEmulator::start(
        Box::new(transport),
        CanopenEmulatorConfig { nodes, sync_period_s: args.sync_period_ms * 1e-3 },
    );
    outln!(out, "listening on {addr} (CiA 402 drives, nodes {:?})", args.nodes);
    super::serve::until_stopped(args.duration_s)?;
    for (node, state, position) in emulator.nodes() {
        outln!(out, "node {node}: {state:?}, at {position} counts");
    }
    emulator.stop();
    Ok(ExitCode::SUCCESS)
}
