//! `knotlab session`: the lab's workflow at a desk, in the simulator. A gamepad (or any master and
//! pedals the rig config names) steers the instruments; the skill pedal instantiates the learned skill
//! at the stitch as it stands, previews and executes it; the session is recorded as a demonstration.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use serde::Serialize;

use knotlab_hw::controller::TeleopSettings;
use knotlab_hw::rig::Rig;
use knotlab_learner::demonstration::write_demonstration;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::session::run_session;
use knotlab_sim::world::SimWorld;

use super::output::{Output, outln};
use super::skill_source::SkillSource;
use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
pub struct SessionArgs {
    /// The rig: which masters and pedals steer (scenarios/rigs/sim-gamepad.toml needs the `gamepad`
    /// feature; scenarios/rigs/sim.toml, which `knotlab shipped dump` writes out, has dummy ones that
    /// stay still) [default: the shipped scenarios/rigs/sim-gamepad.toml, built in].
    #[arg(long)]
    rig: Option<PathBuf>,
    /// The scene file [default: the shipped scenarios/default.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    #[command(flatten)]
    source: SkillSource,
    /// How the skill is carried to the stitch: fluid, dmp or replay.
    #[arg(long, default_value = "fluid")]
    method: Method,
    /// How long the session lasts, simulated s.
    #[arg(long, default_value_t = 60.0)]
    seconds: f64,
    /// Tip motion per handle motion.
    #[arg(long, default_value_t = 1.0 / 3.0)]
    scale: f64,
    /// Run as fast as the simulation goes instead of at the wall clock's pace.
    #[arg(long)]
    unpaced: bool,
    /// Where to write the session's recording (a demonstration directory).
    #[arg(long)]
    out: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

#[derive(Serialize)]
struct Report {
    log: Vec<(f64, String)>,
    skill_started_s: Option<f64>,
    skill_finished_s: Option<f64>,
    refused: Option<String>,
    status: String,
    samples: usize,
    out: String,
}

pub fn run(args: SessionArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if !(args.seconds.is_finite() && args.seconds > 0.0) {
        anyhow::bail!("--seconds {}: must be a positive number of seconds", args.seconds);
    }
    let rig_name = shipped::name(args.rig.as_deref(), &shipped::GAMEPAD_RIG);
    let config = shipped::rig_config(args.rig.as_deref(), &shipped::GAMEPAD_RIG)?;
    let learned = args.source.learned()?;
    let rig = Rig::shipped().context("the shipped rig")?;
    let scene_name = shipped::name(args.scene.as_deref(), &shipped::SCENE);
    let world = SimWorld::new(shipped::scene(args.scene.as_deref(), &shipped::SCENE)?, rig.clone())
        .with_context(|| scene_name.clone())?;
    let teleop = TeleopSettings { scale: args.scale, ..TeleopSettings::default() };
    let mut report = run_session(
        world,
        &rig,
        &config,
        &learned,
        args.method,
        teleop,
        &Vec::new(),
        args.seconds,
        !args.unpaced,
    )
    .with_context(|| format!("the session on {rig_name}"))?;
    report.demonstration.metadata.scene = scene_name;
    report.demonstration.metadata.source = format!("teleoperation ({rig_name})");
    write_demonstration(&args.out, &report.demonstration)
        .with_context(|| format!("writing the session's recording to {}", args.out.display()))?;
    let r = Report {
        log: report.log.clone(),
        skill_started_s: report.skill_started_s,
        skill_finished_s: report.skill_finished_s,
        refused: report.refused.clone(),
        status: format!("{:?}", report.status),
        samples: report.demonstration.instruments.iter().map(|i| i.samples.len()).sum(),
        out: args.out.display().to_string(),
    };
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&r)?);
    } else {
        for (t, what) in &r.log {
            outln!(out, "{t:8.3} s  {what}");
        }
        outln!(out, "recorded {} samples -> {}", r.samples, r.out);
    }
    Ok(ExitCode::SUCCESS)
}
