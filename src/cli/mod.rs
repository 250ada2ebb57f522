//! Command-line parsing and dispatch; each command group lives in its own file.

mod knot;
mod melfa;
mod numbers;
mod output;
mod rig;
mod sim;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// knotlab: surgical knot tying learned from one demonstration, in simulation and on robots.
#[derive(Debug, Parser)]
#[command(name = "knotlab", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The robots: validate the rig, forward and inverse kinematics.
    #[command(subcommand)]
    Rig(rig::RigCommand),
    /// Knots: which knot a thread's centreline holds.
    #[command(subcommand)]
    Knot(knot::KnotCommand),
    /// A MELFA controller emulator: MXT real-time external control over UDP, moving a simulated arm.
    MelfaEmulator(melfa::EmulatorArgs),
    /// The simulated scene: run its scripted stress sequence and report what the thread did.
    Sim(sim::SimArgs),
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    let mut out = output::Output::stdout();
    match cli.command {
        Command::Rig(command) => rig::run(command, &mut out),
        Command::Knot(command) => knot::run(command, &mut out),
        Command::MelfaEmulator(args) => melfa::run(args, &mut out),
        Command::Sim(args) => sim::run(args, &mut out),
    }
}
