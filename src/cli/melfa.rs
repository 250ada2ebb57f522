//! `knotlab melfa-emulator`: a MELFA controller emulator on UDP, speaking the real-time external control
//! protocol (MXT) and moving a simulated arm, to try the MELFA driver and rig configs without a robot.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, ValueEnum};
use serde::Serialize;

use knotlab_hw::melfa::Layout;
use knotlab_hw::melfa::emulator::{DropPolicy, Emulator, EmulatorConfig, EmulatorError, EmulatorReport};
use knotlab_hw::rig::{ArmName, Rig};

use super::numbers::parse_list;
use super::output::{Output, outln};

/// A comma-separated list as one argument (an alias, so clap does not read it as a repeated flag).
type Numbers = Vec<f64>;

/// The packet layouts on the command line.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum LayoutArg {
    /// Controller software H7 and later: 196-byte packets.
    H7,
    /// H6 and older: 64-byte packets.
    PreH7,
}

#[derive(Debug, Args)]
pub struct EmulatorArgs {
    /// Address to listen on, ip:port (port 0: any free port). Loopback only unless --allow-remote.
    #[arg(long)]
    bind: SocketAddr,
    /// The controller software's packet layout.
    #[arg(long, value_enum, default_value = "h7")]
    layout: LayoutArg,
    /// Drop every Nth reply (to exercise a driver's loss handling).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    drop_every: Option<u32>,
    /// Allow binding an address other than loopback (the emulator then answers anyone who reaches it).
    #[arg(long)]
    allow_remote: bool,
    /// Which arm it emulates: its limits and ready pose come from the rig (left, right, assist, camera).
    #[arg(long, default_value = "left")]
    arm: ArmName,
    /// Start at these joints instead of the arm's ready pose (six values, radians).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_list)]
    joints: Option<Numbers>,
    /// The controller's cycle, ms (7.11 for CR750/CR751, 3.5 for CR800).
    #[arg(long, default_value_t = 7.11)]
    cycle_ms: f64,
    /// The MXT filter time constant, ms (the third argument of `MXT 1,1,<filter>`; 0: none).
    #[arg(long, default_value_t = 0.0)]
    filter_ms: f64,
    /// Answer at once instead of at the controller's cycle boundaries (for tests).
    #[arg(long)]
    no_pace: bool,
    /// Give up after this many seconds without a packet (default: wait for ever).
    #[arg(long)]
    idle_timeout_s: Option<f64>,
    /// The rig's URDF (for the arm's limits); default: the rig shipped with knotlab.
    #[arg(long)]
    urdf: Option<PathBuf>,
    /// Print the session's summary as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Summary<'a> {
    ended: bool,
    packets: u64,
    nulls: u64,
    moves: u64,
    replies_sent: u64,
    replies_dropped: u64,
    malformed: u64,
    foreign: u64,
    cycles: u64,
    final_joints_rad: [f64; 6],
    problems: &'a [String],
    fault: Option<String>,
}

fn print_summary(
    report: &EmulatorReport,
    fault: Option<String>,
    json: bool,
    out: &mut Output,
) -> anyhow::Result<()> {
    if json {
        let summary = Summary {
            ended: report.ended,
            packets: report.packets,
            nulls: report.nulls,
            moves: report.moves,
            replies_sent: report.replies_sent,
            replies_dropped: report.replies_dropped,
            malformed: report.malformed,
            foreign: report.foreign,
            cycles: report.cycles,
            final_joints_rad: report.final_joints_rad,
            problems: &report.problems,
            fault,
        };
        outln!(out, "{}", serde_json::to_string(&summary)?);
        return Ok(());
    }
    let how = if report.ended { "ended by END" } else { "stopped without END" };
    outln!(
        out,
        "session {how}: {} packets ({} NULL, {} MOVE), {} replies sent, {} dropped, {} malformed, {} from other senders",
        report.packets,
        report.nulls,
        report.moves,
        report.replies_sent,
        report.replies_dropped,
        report.malformed,
        report.foreign
    );
    let joints: Vec<String> = report.final_joints_rad.iter().map(|q| format!("{q:.6}")).collect();
    outln!(out, "final joints (rad): {}", joints.join(","));
    for problem in &report.problems {
        out.error(format!("warning: {problem}"));
    }
    Ok(())
}

pub fn run(args: EmulatorArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let rig = match &args.urdf {
        Some(path) => Rig::from_file(path)?,
        None => Rig::shipped()?,
    };
    let model = rig.arm(args.arm).model;
    let initial_joints_rad = match &args.joints {
        None => args.arm.ready_joints().arm_rad,
        Some(j) => <[f64; 6]>::try_from(j.as_slice())
            .map_err(|_| anyhow::anyhow!("--joints: expected 6 values (axes 1..6, rad), got {}", j.len()))?,
    };
    for (i, (q, limit)) in initial_joints_rad.iter().zip(&model.limits).enumerate() {
        if !limit.contains(*q) {
            anyhow::bail!(
                "--joints: axis {} = {q} rad is outside the {} arm's limits, {:.4} to {:.4} rad",
                i + 1,
                args.arm,
                limit.lower_rad,
                limit.upper_rad
            );
        }
    }
    if !(args.cycle_ms.is_finite() && args.cycle_ms > 0.0 && args.cycle_ms <= 1000.0) {
        anyhow::bail!("--cycle-ms: {} is not a period of more than 0 and at most 1000 ms", args.cycle_ms);
    }
    if !(args.filter_ms.is_finite() && (0.0..=1000.0).contains(&args.filter_ms)) {
        anyhow::bail!("--filter-ms: {} is not a time constant of 0 to 1000 ms", args.filter_ms);
    }
    if let Some(t) = args.idle_timeout_s
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--idle-timeout-s: {t} is not a positive, finite number of seconds");
    }
    let layout = match args.layout {
        LayoutArg::H7 => Layout::H7,
        LayoutArg::PreH7 => Layout::PreH7,
    };
    let config = EmulatorConfig {
        layout,
        cycle_s: args.cycle_ms * 1e-3,
        filter_s: args.filter_ms * 1e-3,
        initial_joints_rad,
        limits: model.limits,
        drop: args.drop_every.map_or(DropPolicy::Never, DropPolicy::Every),
        pace: !args.no_pace,
        idle_timeout_s: args.idle_timeout_s,
    };
    let emulator = Emulator::bind(args.bind, args.allow_remote, config).context("melfa-emulator")?;
    let addr = emulator.local_addr()?;
    outln!(
        out,
        "listening on {addr} (arm {}, layout {}, cycle {} ms, filter {} ms{})",
        args.arm,
        layout.as_str(),
        args.cycle_ms,
        args.filter_ms,
        args.drop_every.map_or(String::new(), |n| format!(", dropping one reply in {n}"))
    );
    match emulator.run() {
        Ok(report) => {
            print_summary(&report, None, args.json, out)?;
            Ok(if report.ended { ExitCode::SUCCESS } else { ExitCode::FAILURE })
        }
        Err(EmulatorError::Fault { fault, report }) => {
            print_summary(&report, Some(fault.to_string()), args.json, out)?;
            Err(anyhow::anyhow!("controller fault: {fault}"))
        }
        Err(EmulatorError::Idle { seconds, report }) => {
            print_summary(&report, None, args.json, out)?;
            Err(anyhow::anyhow!("no packet for {seconds:.3} s: giving up"))
        }
        Err(other) => Err(other.into()),
    }
}
