//! `knotlab mc`: the Monte Carlo knot-tying evaluation. Learns once from the demonstration, then runs
//! N trials drawn from the scene's `[randomization]`, each by every method asked for, on `--jobs`
//! threads; results go to OUT/results.jsonl as they finish (a rerun resumes), the summary to
//! OUT/summary.json.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use knotlab_bench::mc::{McOptions, run_mc_with};
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::{Learned, TrialError, TrialRun, TrialSetup, run_trial};
use knotlab_sim::scene::load_scene;

use super::output::{Output, outln};
use super::skill_source::SkillSource;
use crate::rerun_log::{self, RerunArgs};

#[derive(Debug, Args)]
pub struct McArgs {
    /// The scene file (its [randomization] table says what each trial draws).
    #[arg(long, default_value = "scenarios/default.toml")]
    scene: PathBuf,
    #[command(flatten)]
    source: SkillSource,
    /// Trials 0 to N-1.
    #[arg(long, default_value_t = 10)]
    trials: u64,
    /// The run's seed: trial i draws from (seed, i) alone.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Threads (default: one per core).
    #[arg(long)]
    jobs: Option<usize>,
    /// The methods, each on every trial (repeat the flag): fluid, dmp, replay.
    #[arg(long = "method", default_value = "fluid")]
    methods: Vec<Method>,
    /// Stop each trial's skill at this time, s (short runs, to try the machinery).
    #[arg(long, value_name = "S")]
    until: Option<f64>,
    /// Where results.jsonl and summary.json go (an existing results.jsonl is resumed).
    #[arg(long)]
    out: PathBuf,
    /// Record these trials for the Rerun viewer (comma-separated indices), into OUT/rerun/.
    #[arg(long, value_delimiter = ',', value_name = "I,J,...")]
    record_trials: Vec<u64>,
    /// Record every trial that fails for the Rerun viewer, into OUT/rerun/.
    #[arg(long)]
    record_failures: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// Runs a trial, recording it into `OUT/rerun/trial-I-METHOD.rrd` when asked (a success is not kept when
/// only failures are asked for).
fn recorded_trial(
    learned: &Learned,
    args: &McArgs,
    setup: &TrialSetup,
    options: &RecordOptions,
    trial: u64,
) -> Result<TrialRun, TrialError> {
    let listed = args.record_trials.contains(&trial);
    if !listed && !args.record_failures {
        return run_trial(learned, setup, options, None);
    }
    let path = args.out.join("rerun").join(format!("trial-{trial}-{}.rrd", setup.method));
    let rerun = RerunArgs { rerun: Some(path.clone()), rerun_connect: None };
    let recording = match rerun.open(&format!("mc trial {trial} {}", setup.method)) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("warning: trial {trial}: not recorded: {e:#}");
            return run_trial(learned, setup, options, None);
        }
    };
    let result = rerun_log::record_trial(
        recording.as_ref(),
        |observer| run_trial(learned, setup, options, observer),
        |t| &t.run,
    );
    if let Err(e) = rerun_log::finish(recording) {
        eprintln!("warning: trial {trial}: {e:#}");
    }
    match result {
        Ok(run) => {
            if !listed && run.run.evaluation.verdict == knotlab_sim::knot::Verdict::Success {
                std::fs::remove_file(&path).ok();
            }
            Ok(run)
        }
        // A trial that could not be set up: run again without the recording for its own typed error
        // (it fails before simulating anything).
        Err(_) => run_trial(learned, setup, options, None),
    }
}

pub fn run(args: McArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if let Some(t) = args.until
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--until {t}: must be a positive number of seconds");
    }
    let learned = args.source.learned()?;
    let mut methods = args.methods.clone();
    methods.dedup();
    let jobs =
        args.jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);
    let options = McOptions {
        scene: load_scene(&args.scene)?,
        scene_name: args.scene.display().to_string(),
        trials: args.trials,
        seed: args.seed,
        jobs,
        methods,
        out: args.out.clone(),
        until_s: args.until,
    };
    let started = std::time::Instant::now();
    let json = args.json;
    let runner = |setup: &TrialSetup, record: &RecordOptions, trial: u64| {
        recorded_trial(&learned, &args, setup, record, trial)
    };
    let summary = run_mc_with(&options, &runner, |line, done, total| {
        if !json {
            let rate = done as f64 / started.elapsed().as_secs_f64().max(1e-9) * 60.0;
            eprintln!(
                "[{done}/{total}] trial {} {}: {} ({:.0} trials/min)",
                line.trial, line.method, line.verdict, rate
            );
        }
    })?;
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&summary)?);
    } else {
        for m in &summary.methods {
            outln!(
                out,
                "{}: {} of {} trials tied the knot ({:.1} %, 95 % Wilson {:.1}-{:.1} %); {}",
                m.method,
                m.successes,
                m.trials,
                100.0 * m.success_rate,
                100.0 * m.wilson_95[0],
                100.0 * m.wilson_95[1],
                m.verdicts.iter().map(|(v, n)| format!("{v} {n}")).collect::<Vec<_>>().join(", ")
            );
        }
        outln!(out, "results: {}", args.out.join("results.jsonl").display());
        outln!(out, "summary: {}", args.out.join("summary.json").display());
    }
    Ok(ExitCode::SUCCESS)
}
