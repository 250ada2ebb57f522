//! Monte Carlo evaluation: learn once, then per trial draw a scene from the scene file's
//! `[randomization]` ([`draw`](mod@draw)), synthesize the skill there by each method, run it on the simulated rig
//! and evaluate the knot. Trials run on `jobs` threads; each is fully determined by the run's seed and
//! its index. Every finished trial is appended to `results.jsonl` at once, so an interrupted run
//! resumes where it stopped (trials already there are skipped); `summary.json` is made from the
//! results sorted by trial and method, so it is the same bytes whatever the number of jobs. A run can be
//! cut into shards (`run_info::Shard`) run apart and combined by [`merge::merge`]; `run.json` says which
//! run a directory holds.

pub mod draw;
pub mod merge;
pub mod one_trial;
pub mod run_info;
pub mod summary;

use std::collections::BTreeSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::{Learned, TrialError, TrialRun, TrialSetup, run_trial};
use knotlab_sim::knot::Verdict;
use knotlab_sim::scene::SceneConfig;
use serde::{Deserialize, Serialize};

pub use draw::{Draw, draw};
pub use merge::{MergeOutcome, merge};
pub use one_trial::trial_of_run;
pub use run_info::{RunInfo, Shard};
pub use summary::{MethodSummary, Summary, summarize, wilson_interval};

/// A Monte Carlo run.
#[derive(Clone, Debug)]
pub struct McOptions {
    /// The scene (its `[randomization]` says what is drawn), with the preset applied if one was picked.
    pub scene: SceneConfig,
    /// Its file, for the record.
    pub scene_name: String,
    /// The preset applied to the scene's randomization, for the record.
    pub preset: Option<String>,
    /// Trials 0 to N-1.
    pub trials: u64,
    /// The run's seed.
    pub seed: u64,
    /// Threads.
    pub jobs: usize,
    /// The methods, each run on every trial.
    pub methods: Vec<Method>,
    /// Where `results.jsonl` and `summary.json` go.
    pub out: PathBuf,
    /// Stop each trial's skill at this time, s (short runs for tests).
    pub until_s: Option<f64>,
    /// Only this shard's trials.
    pub shard: Option<Shard>,
    /// What the trials play ([`run_info::skill_fingerprint`]), for the record.
    pub skill_fingerprint: String,
}

impl McOptions {
    /// The run's `run.json`.
    pub fn run_info(&self) -> RunInfo {
        RunInfo {
            format: run_info::RUN_FORMAT.to_owned(),
            scene: self.scene_name.clone(),
            preset: self.preset.clone(),
            scene_fingerprint: run_info::scene_fingerprint(&self.scene),
            skill_fingerprint: self.skill_fingerprint.clone(),
            randomization: self.scene.randomization.clone(),
            seed: self.seed,
            trials: self.trials,
            methods: self.methods.iter().map(|m| m.to_string()).collect(),
            until_s: self.until_s,
            shard: self.shard,
        }
    }
}

/// How a run ended.
#[derive(Clone, Debug)]
pub struct McRun {
    /// The summary of the trials finished so far (also in `summary.json`).
    pub summary: Summary,
    /// (trial, method) pairs the run (or shard) is made of.
    pub expected: usize,
    /// ... of which finished, this time or before.
    pub finished: usize,
    /// Whether it was stopped before all were done (rerunning resumes it).
    pub interrupted: bool,
}

/// One finished trial of one method: a line of `results.jsonl`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrialLine {
    /// The trial's index.
    pub trial: u64,
    /// The run's seed.
    pub seed: u64,
    /// The method.
    pub method: String,
    /// What was drawn.
    pub draw: serde_json::Value,
    /// `success` or the failure mode.
    pub verdict: String,
    /// The knot before release, if any.
    pub knot: Option<String>,
    /// The wound gap at the end, m (none when the trial could not be set up).
    pub wound_gap_m: Option<f64>,
    /// The suture's largest stretch over the trial (its most stretched segment beyond its rest
    /// length, a fraction of it; not part of the verdict); none when the trial could not be set up,
    /// or in lines written before it was recorded.
    #[serde(default)]
    pub thread_max_stretch: Option<f64>,
    /// How long the suture was stretched beyond 5 % over the trial, s; none as
    /// `thread_max_stretch`.
    #[serde(default)]
    pub thread_stretched_s: Option<f64>,
    /// How often the thread passed through itself (a solver failure, not part of the verdict); none
    /// when the trial could not be set up, or in lines written before it was counted.
    #[serde(default)]
    pub thread_self_crossings: Option<usize>,
    /// The first of them (when, s of simulated time, and which two segments), to find the move that
    /// forced it; none when there was none, or in lines written before it was recorded.
    #[serde(default)]
    pub first_self_crossing: Option<knotlab_sim::thread_watch::SelfCrossing>,
    /// How much of each free end the knot drew in during the holding test (a knot that slips lets
    /// one through); none when the test did not run, or in lines written before it was measured.
    #[serde(default)]
    pub slid: Option<knotlab_sim::evaluate::Slid>,
    /// Simulated time, s.
    pub sim_seconds: f64,
    /// Wall time, s (not in the summary).
    pub wall_seconds: f64,
    /// A fault or a synthesis error, if one ended the trial.
    pub error: Option<String>,
}

/// Most trials one run may have: a week of a hundred cores at about 20 trials a minute each. The
/// run's list of pending trials is built up front.
pub const MAX_TRIALS: u64 = 100_000_000;

/// Why the run stopped.
#[derive(Debug, thiserror::Error)]
pub enum McError {
    /// The results file.
    #[error("{file}: {reason}")]
    Results {
        /// The file.
        file: String,
        /// Why.
        reason: String,
    },
}

/// `results.jsonl` in a run directory.
pub fn results_path(out: &Path) -> PathBuf {
    out.join("results.jsonl")
}

/// The lines already in `results.jsonl` (none when it does not exist). A last line cut short by a kill
/// is dropped (and its trial run again); any other bad line is an error naming it.
pub fn read_results(out: &Path) -> Result<Vec<TrialLine>, McError> {
    let path = results_path(out);
    let file = path.display().to_string();
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(McError::Results { file, reason: e.to_string() }),
    };
    let lines: Vec<&str> = text.lines().collect();
    let complete = text.ends_with('\n');
    let mut out = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        match serde_json::from_str::<TrialLine>(line) {
            Ok(l) => out.push(l),
            Err(_) if k + 1 == lines.len() && !complete => {}
            Err(e) => return Err(McError::Results { file, reason: format!("line {}: {e}", k + 1) }),
        }
    }
    Ok(out)
}

/// Checks that every line of `file` (as [`read_results`] gives them, the k-th on line k + 1) belongs
/// to the run `info` describes: its seed, one of its methods, a trial below its count and, for a
/// shard, one the shard holds; and that no trial of a method is there twice. The first line that does
/// not is named with what it holds and what the run asks.
pub fn check_lines(lines: &[TrialLine], info: &RunInfo, file: &str) -> Result<(), McError> {
    let error = |k: usize, reason: String| McError::Results { file: format!("{file}:{}", k + 1), reason };
    let mut seen: std::collections::BTreeMap<(u64, &str), usize> = std::collections::BTreeMap::new();
    for (k, line) in lines.iter().enumerate() {
        let (trial, method) = (line.trial, line.method.as_str());
        if line.seed != info.seed {
            return Err(error(
                k,
                format!("seed {} is not the run's ({}): a line of another run", line.seed, info.seed),
            ));
        }
        if !info.methods.iter().any(|m| m == method) {
            let methods = info.methods.join(", ");
            return Err(error(
                k,
                format!("method {method} is not one of the run's ({methods}): a line of another run"),
            ));
        }
        if trial >= info.trials {
            return Err(error(
                k,
                format!(
                    "trial {trial} is beyond the run's {} trials (0 to {})",
                    info.trials,
                    info.trials.saturating_sub(1)
                ),
            ));
        }
        if let Some(shard) = info.shard.filter(|s| !s.holds(trial)) {
            return Err(error(k, format!("trial {trial} is not one shard {shard} runs")));
        }
        if let Some(first) = seen.insert((trial, method), k) {
            return Err(error(k, format!("trial {trial} by {method} again (first on line {})", first + 1)));
        }
    }
    Ok(())
}

/// [`check_lines`] for lines with no `run.json` beside them: the run is taken to be the first line's
/// seed, the methods and trials the lines hold, so that only another seed's line and a trial given
/// twice are refused.
pub fn check_lines_alone(lines: &[TrialLine], file: &str) -> Result<(), McError> {
    let Some(first) = lines.first() else { return Ok(()) };
    let mut methods: Vec<String> = lines.iter().map(|l| l.method.clone()).collect();
    methods.sort();
    methods.dedup();
    let trials = lines.iter().map(|l| l.trial + 1).max().unwrap_or(0);
    let info = RunInfo {
        format: run_info::RUN_FORMAT.to_owned(),
        scene: String::new(),
        preset: None,
        scene_fingerprint: String::new(),
        skill_fingerprint: String::new(),
        randomization: Default::default(),
        seed: first.seed,
        trials,
        methods,
        until_s: None,
        shard: None,
    };
    check_lines(lines, &info, file)
}

/// Runs one trial's set-up (the default: [`run_trial`] without an observer); a caller can wrap it, to
/// record a trial for a viewer, say.
pub type TrialRunner<'a> =
    dyn Fn(&TrialSetup, &RecordOptions, u64) -> Result<TrialRun, TrialError> + Sync + 'a;

/// Trial `trial` of a run seeded `seed` on `scene` (named `scene_name`) by `method`: its setup and what
/// it drew.
pub fn drawn_trial(
    scene: &SceneConfig,
    scene_name: &str,
    seed: u64,
    trial: u64,
    method: Method,
) -> (TrialSetup, Draw) {
    let (scene, stitch, drawn) = draw(scene, seed, trial);
    let setup = TrialSetup {
        scene,
        scene_name: scene_name.to_owned(),
        seed: drawn.sim_seed,
        stitch,
        method,
        offsets: Vec::new(),
    };
    (setup, drawn)
}

fn run_one(options: &McOptions, trial: u64, method: Method, runner: &TrialRunner<'_>) -> TrialLine {
    let (setup, drawn) = drawn_trial(&options.scene, &options.scene_name, options.seed, trial, method);
    let record =
        RecordOptions { cycles_per_sample: 10, stop_after_s: options.until_s, ..RecordOptions::default() };
    let draw_json = serde_json::to_value(drawn).unwrap_or(serde_json::Value::Null);
    match runner(&setup, &record, trial) {
        Ok(t) => {
            let e = &t.run.evaluation;
            TrialLine {
                trial,
                seed: options.seed,
                method: method.to_string(),
                draw: draw_json,
                verdict: t.verdict().label().to_owned(),
                knot: e.knot_before.map(|k| k.name().to_owned()),
                wound_gap_m: Some(e.gap_after_m.unwrap_or(e.gap_before_m)),
                thread_max_stretch: e.thread_most_stretched.map(|s| s.ratio),
                thread_stretched_s: e.thread_most_stretched.map(|s| s.over_5_percent_s),
                thread_self_crossings: Some(e.thread_self_crossings),
                first_self_crossing: t.run.self_crossings.first().copied(),
                slid: e.slid,
                sim_seconds: t.run.simulated_s,
                wall_seconds: t.run.wall_s,
                error: t.run.fault.clone(),
            }
        }
        Err(error) => TrialLine {
            trial,
            seed: options.seed,
            method: method.to_string(),
            draw: draw_json,
            verdict: Verdict::Failure(knotlab_sim::knot::FailureMode::Unreachable).label().to_owned(),
            knot: None,
            wound_gap_m: None,
            thread_max_stretch: None,
            thread_stretched_s: None,
            thread_self_crossings: None,
            first_self_crossing: None,
            slid: None,
            sim_seconds: 0.0,
            wall_seconds: 0.0,
            error: Some(format!("{error:#}")),
        },
    }
}

/// Runs (or resumes) the Monte Carlo run; `progress` sees each finished line. Returns the summary
/// (also written to `summary.json`).
pub fn run_mc(
    learned: &Learned,
    options: &McOptions,
    progress: impl FnMut(&TrialLine, usize, usize),
) -> Result<Summary, McError> {
    let runner =
        |setup: &TrialSetup, record: &RecordOptions, _trial: u64| run_trial(learned, setup, record, None);
    Ok(run_mc_with(options, &runner, &AtomicBool::new(false), progress)?.summary)
}

/// Writes `summary.json` into `out`.
pub fn write_summary(out: &Path, summary: &Summary) -> Result<(), McError> {
    let summary_file = out.join("summary.json");
    let text = serde_json::to_string_pretty(summary)
        .map_err(|e| McError::Results { file: summary_file.display().to_string(), reason: e.to_string() })?;
    std::fs::write(&summary_file, text + "\n")
        .map_err(|e| McError::Results { file: summary_file.display().to_string(), reason: e.to_string() })
}

/// [`run_mc`] with each trial run by `runner`. Once `stop` is set no trial is started any more: those
/// running finish and are written, the summary covers what is done, and the result says it was
/// interrupted.
pub fn run_mc_with(
    options: &McOptions,
    runner: &TrialRunner<'_>,
    stop: &AtomicBool,
    mut progress: impl FnMut(&TrialLine, usize, usize),
) -> Result<McRun, McError> {
    let file = results_path(&options.out).display().to_string();
    if options.trials == 0 || options.trials > MAX_TRIALS {
        return Err(McError::Results {
            file,
            reason: format!("{} trials: a run has 1 to {MAX_TRIALS}", options.trials),
        });
    }
    std::fs::create_dir_all(&options.out)
        .map_err(|e| McError::Results { file: file.clone(), reason: e.to_string() })?;
    let info = options.run_info();
    let there = RunInfo::read(&options.out)?;
    let done = read_results(&options.out)?;
    match there {
        Some(there) => {
            if let Some(difference) = there.difference(&info, false) {
                return Err(McError::Results {
                    file: RunInfo::path(&options.out).display().to_string(),
                    reason: format!(
                        "the directory holds another run ({difference}): resume it with the same arguments \
                         or give another --out"
                    ),
                });
            }
            // The lines already there belong to this run (with as many trials as it had or has).
            check_lines(&done, &RunInfo { trials: there.trials.max(info.trials), ..info.clone() }, &file)?;
            // A run grows by more trials; asked for fewer, it keeps its count (and its lines beyond
            // them) and summarizes the trials asked for.
            if info.trials > there.trials {
                info.write(&options.out)?;
            }
        }
        None if !done.is_empty() => {
            return Err(McError::Results {
                file,
                reason: format!(
                    "holds {} finished trials but the directory has no run.json: they cannot be told to \
                     belong to this run; give another --out, or remove results.jsonl to start anew",
                    done.len()
                ),
            });
        }
        None => info.write(&options.out)?,
    }
    let mut done = done;
    let finished: BTreeSet<(u64, String)> = done.iter().map(|l| (l.trial, l.method.clone())).collect();
    let all: Vec<(u64, Method)> = (0..options.trials)
        .filter(|t| options.shard.is_none_or(|s| s.holds(*t)))
        .flat_map(|t| options.methods.iter().map(move |m| (t, *m)))
        .collect();
    let expected = all.len();
    let todo: Vec<(u64, Method)> =
        all.into_iter().filter(|(t, m)| !finished.contains(&(*t, m.to_string()))).collect();
    // Rewrite the file without a line cut short, then append.
    let mut text = String::new();
    for l in &done {
        text.push_str(
            &serde_json::to_string(l)
                .map_err(|e| McError::Results { file: file.clone(), reason: e.to_string() })?,
        );
        text.push('\n');
    }
    std::fs::write(results_path(&options.out), text)
        .map_err(|e| McError::Results { file: file.clone(), reason: e.to_string() })?;
    let mut writer = std::fs::OpenOptions::new()
        .append(true)
        .open(results_path(&options.out))
        .map_err(|e| McError::Results { file: file.clone(), reason: e.to_string() })?;
    let total = todo.len();
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel::<TrialLine>();
    let mut write_error = None;
    std::thread::scope(|scope| {
        for _ in 0..options.jobs.max(1) {
            let tx = tx.clone();
            let (todo, next) = (&todo, &next);
            scope.spawn(move || {
                while !stop.load(Ordering::SeqCst) {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&(trial, method)) = todo.get(k) else { break };
                    if tx.send(run_one(options, trial, method, runner)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        for (count, line) in rx.iter().enumerate() {
            let written = serde_json::to_string(&line).map_err(|e| e.to_string()).and_then(|json| {
                writeln!(writer, "{json}").and_then(|()| writer.flush()).map_err(|e| e.to_string())
            });
            if let Err(reason) = written {
                write_error.get_or_insert(reason);
            }
            progress(&line, count + 1, total);
            done.push(line);
        }
    });
    if let Some(reason) = write_error {
        return Err(McError::Results { file, reason });
    }
    let summary = summarize(&options.scene_name, options.seed, options.trials, &options.methods, &done);
    write_summary(&options.out, &summary)?;
    let finished = done.len();
    Ok(McRun { summary, expected, finished, interrupted: finished < expected })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A results line that lacks the self-crossing and slip fields reads, with those fields as none.
    #[test]
    fn lines_written_before_self_crossings_were_counted_still_read() {
        let out = std::env::temp_dir().join(format!("knotlab-mc-old-lines-{}", std::process::id()));
        std::fs::create_dir_all(&out).unwrap();
        let old = r#"{"trial":0,"seed":7,"method":"dmp","draw":null,"verdict":"no_knot","knot":null,"wound_gap_m":0.004,"sim_seconds":0.3,"wall_seconds":1.0,"error":null}"#;
        std::fs::write(results_path(&out), format!("{old}\n")).unwrap();
        let lines = read_results(&out).expect("an old line reads");
        assert_eq!(lines.len(), 1);
        assert_eq!(lines[0].thread_self_crossings, None);
        assert_eq!(lines[0].first_self_crossing, None);
        assert_eq!(lines[0].slid, None);
        assert_eq!(lines[0].verdict, "no_knot");
        std::fs::remove_dir_all(&out).ok();
    }

    /// A trial line's first self-crossing (its time and segment pair) is written and reads back unchanged.
    #[test]
    fn a_lines_first_self_crossing_reads_back_as_written() {
        let crossing = knotlab_sim::thread_watch::SelfCrossing { time_s: 21.25, segments: (16, 35) };
        let line = TrialLine {
            thread_self_crossings: Some(2),
            first_self_crossing: Some(crossing),
            ..crate::report::test_line("fluid", serde_json::Value::Null, "knot_slipped")
        };
        let text = serde_json::to_string(&line).unwrap();
        assert!(text.contains(r#""first_self_crossing":{"time_s":21.25,"segments":[16,35]}"#), "{text}");
        assert_eq!(serde_json::from_str::<TrialLine>(&text).unwrap(), line);
    }

    /// How much of each free end a knot let through is written into the trial line and reads back unchanged.
    #[test]
    fn what_a_knot_let_through_reads_back_as_written() {
        let slid = knotlab_sim::evaluate::Slid { long_end_m: 0.011, tail_m: 0.039 };
        let line = TrialLine {
            slid: Some(slid),
            ..crate::report::test_line("fluid", serde_json::Value::Null, "knot_slipped")
        };
        let text = serde_json::to_string(&line).unwrap();
        assert!(text.contains(r#""slid":{"long_end_m":0.011,"tail_m":0.039}"#), "{text}");
        assert_eq!(serde_json::from_str::<TrialLine>(&text).unwrap(), line);
    }
}
