//! `knotlab mc`: the Monte Carlo knot-tying evaluation. Learns once from the demonstration, then runs
//! N trials drawn from the scene's `[randomization]`, each by every method asked for, on `--jobs`
//! threads; results go to OUT/results.jsonl as they finish (a rerun resumes), the summary to
//! OUT/summary.json. `--shard I/N` runs one of N disjoint parts of the trials; `knotlab mc merge` combines
//! the parts into the result one run gives. A progress bar shows trials done, rate and ETA; Ctrl-C
//! stops taking trials (those running finish and are kept; rerunning resumes), a second Ctrl-C at once.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use clap::{Args, Subcommand};

use knotlab_bench::mc::{McOptions, Shard, merge, run_mc_with};
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::{Learned, TrialError, TrialRun, TrialSetup, run_trial};

use super::output::{Output, outln};
use super::skill_source::SkillSource;
use crate::rerun_log::{self, RerunArgs};
use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct McArgs {
    #[command(subcommand)]
    command: Option<McCommand>,
    /// The scene file (its [randomization] table says what each trial draws) [default: the shipped
    /// scenarios/default.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    /// A preset of the scene file's [presets] applied to its randomization (e.g. endopar, ideal).
    #[arg(long)]
    preset: Option<String>,
    /// Run only shard I of N (I from 0): trials t with t % N == I. Combine shards with `knotlab mc merge`.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
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
    /// Where run.json, results.jsonl and summary.json go (an existing run there is resumed).
    #[arg(long, required = true)]
    out: Option<PathBuf>,
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

#[derive(Debug, Subcommand)]
enum McCommand {
    /// Combine the shards of one run (directories run with --shard I/N) into the result one run gives.
    Merge(MergeArgs),
}

#[derive(Debug, Args)]
struct MergeArgs {
    /// The shards' directories.
    #[arg(required = true)]
    dirs: Vec<PathBuf>,
    /// Where the merged run.json, results.jsonl and summary.json go.
    #[arg(long)]
    out: PathBuf,
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
    let path = out_dir(args).join("rerun").join(format!("trial-{trial}-{}.rrd", setup.method));
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

fn out_dir(args: &McArgs) -> PathBuf {
    args.out.clone().unwrap_or_default()
}

fn print_summary(out: &mut Output, summary: &knotlab_bench::mc::Summary) -> anyhow::Result<()> {
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
        let (x, t) = (&m.thread_self_crossings, &m.thread_stretch);
        if let (Some(median), Some(max)) = (t.median, t.max) {
            outln!(
                out,
                "  the thread passed through itself in {} of {} trials; stretched beyond 5 % in {} of {} (for a median {:.1} s a trial), at most {:.0} % (median {:.0} %)",
                x.trials_with_any,
                x.counted_trials,
                t.trials_over_5_percent,
                t.measured_trials,
                t.median_over_5_percent_s.unwrap_or(0.0),
                100.0 * max,
                100.0 * median
            );
        }
    }
    Ok(())
}

fn run_merge(args: MergeArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let merged = merge(&args.dirs, &args.out)?;
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&merged.summary)?);
    } else {
        outln!(
            out,
            "merged shards {} into {} ({} lines)",
            merged.shards.join(", "),
            args.out.display(),
            merged.lines
        );
        print_summary(out, &merged.summary)?;
        outln!(out, "summary: {}", args.out.join("summary.json").display());
    }
    Ok(ExitCode::SUCCESS)
}

/// Exit status of a run stopped by Ctrl-C (128 + SIGINT, as shells report it).
const INTERRUPTED: u8 = 130;

pub fn run(mut args: McArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if let Some(McCommand::Merge(merge_args)) = args.command.take() {
        return run_merge(merge_args, out);
    }
    if let Some(t) = args.until
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--until {t}: must be a positive number of seconds");
    }
    if args.trials == 0 {
        anyhow::bail!("--trials 0: a run needs at least 1 trial (it runs trials 0 to N-1)");
    }
    if args.trials > knotlab_bench::mc::MAX_TRIALS {
        anyhow::bail!(
            "--trials {}: a run has at most {} trials (split a larger study into runs of other seeds)",
            args.trials,
            knotlab_bench::mc::MAX_TRIALS
        );
    }
    if args.jobs == Some(0) {
        anyhow::bail!("--jobs 0: needs at least 1 thread (leave it out for one per core)");
    }
    if let Some(jobs) = args.jobs
        && jobs > 1024
    {
        anyhow::bail!("--jobs {jobs}: at most 1024 threads (leave it out for one per core)");
    }
    if let Some(t) = args.record_trials.iter().find(|t| **t >= args.trials) {
        anyhow::bail!("--record-trials {t}: no such trial in a run of trials 0 to {}", args.trials - 1);
    }
    let out_dir = out_dir(&args);
    let scene_name = shipped::name(args.scene.as_deref(), &shipped::SCENE);
    let mut scene = shipped::scene(args.scene.as_deref(), &shipped::SCENE)?;
    if let Some(preset) = &args.preset {
        scene = scene.with_preset(preset).map_err(|e| anyhow::anyhow!("{scene_name}: {e}"))?;
    }
    let learned = args.source.learned()?;
    // Each method once, in the order first given (`--method a --method b --method a` ran `a` twice).
    let mut methods = args.methods.clone();
    let mut seen = Vec::new();
    methods.retain(|m| {
        let first = !seen.contains(m);
        seen.push(*m);
        first
    });
    let jobs = args.jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let options = McOptions {
        scene,
        scene_name,
        preset: args.preset.clone(),
        trials: args.trials,
        seed: args.seed,
        jobs,
        methods,
        out: out_dir.clone(),
        until_s: args.until,
        shard: args.shard,
        skill_fingerprint: knotlab_bench::mc::run_info::skill_fingerprint(&learned),
    };
    // Ctrl-C: the first stops taking trials, the second exits at once (every finished trial is already
    // in results.jsonl).
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = Arc::clone(&stop);
        ctrlc::set_handler(move || {
            if stop.swap(true, Ordering::SeqCst) {
                std::process::exit(i32::from(INTERRUPTED));
            }
            eprintln!("\nstopping: the trials running finish and are kept (Ctrl-C again to quit now)");
        })?;
    }
    let json = args.json;
    let bar = indicatif::ProgressBar::new(0);
    bar.set_style(indicatif::ProgressStyle::with_template(
        "{bar:40} {pos}/{len} trials, {msg}, elapsed {elapsed}, ETA {eta}",
    )?);
    // Without a terminal the bar draws nothing: a line per trial then.
    let lines = bar.is_hidden() && !json;
    let already = knotlab_bench::mc::read_results(&out_dir)?.len();
    let per_trial = options.methods.len() as u64;
    let in_run = (0..options.trials).filter(|t| options.shard.is_none_or(|s| s.holds(*t))).count() as u64;
    bar.set_length((in_run * per_trial).saturating_sub(already as u64));
    let started = std::time::Instant::now();
    let runner = |setup: &TrialSetup, record: &RecordOptions, trial: u64| {
        recorded_trial(&learned, &args, setup, record, trial)
    };
    let result = run_mc_with(&options, &runner, &stop, |line, done, total| {
        let rate = done as f64 / started.elapsed().as_secs_f64().max(1e-9) * 60.0;
        bar.set_length(total as u64);
        bar.set_position(done as u64);
        bar.set_message(format!("{rate:.1} trials/min"));
        if lines {
            eprintln!(
                "[{done}/{total}] trial {} {}: {} ({:.1} trials/min)",
                line.trial, line.method, line.verdict, rate
            );
        }
    })?;
    bar.finish_and_clear();
    let summary = &result.summary;
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(summary)?);
    } else {
        print_summary(out, summary)?;
        outln!(out, "results: {}", knotlab_bench::mc::results_path(&out_dir).display());
        outln!(out, "summary: {}", out_dir.join("summary.json").display());
    }
    if result.interrupted {
        eprintln!(
            "interrupted: {} of {} trials done; the same command resumes the run",
            result.finished, result.expected
        );
        return Ok(ExitCode::from(INTERRUPTED));
    }
    Ok(ExitCode::SUCCESS)
}
