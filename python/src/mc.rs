//! A Monte Carlo run on the engine of `knotlab mc` (the same folder: `run.json`, `results.jsonl`,
//! `summary.json`; resumable, sharded, the same results whatever the number of jobs), and a run
//! folder read back.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use knotlab_bench::mc::run_info::skill_fingerprint;
use knotlab_bench::mc::{
    McOptions, RunInfo, Shard, check_lines, check_lines_alone, read_results, results_path, run_mc_with,
    summarize,
};
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::{TrialSetup, run_trial};

use crate::error::{knotlab_error, to_python};
use crate::skill::{Skill, or_shipped};
use crate::trial::method;

/// Most threads a run may ask for, as `knotlab mc --jobs`.
const MAX_JOBS: usize = 1024;

/// Runs (or resumes) a Monte Carlo run into the folder `out` and returns its summary as a dict (the
/// `summary.json` it writes): `trials` trials (0 to N-1) of the scene's randomization (the shipped
/// scene when none is given; `preset` picks one of its presets), each by every method in `methods`,
/// on `jobs` threads (one per core when none), the run's draws from `seed`; `shard` (`"I/N"`) runs
/// only the trials of one shard. `progress(line, done, total)` is called with each finished trial's
/// line as a dict. The interpreter's lock is released while trials run; an interrupt (Ctrl-C) stops
/// taking trials, lets those running finish (every finished trial is kept, so the same call
/// resumes the run) and is raised as `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (
    out, trials, seed=0, methods=vec!["fluid".to_owned()], jobs=None, preset=None, scene=None,
    skill=None, until_s=None, shard=None, progress=None
))]
#[allow(clippy::too_many_arguments)]
pub fn run_mc(
    py: Python<'_>,
    out: PathBuf,
    trials: u64,
    seed: u64,
    methods: Vec<String>,
    jobs: Option<usize>,
    preset: Option<String>,
    scene: Option<PathBuf>,
    skill: Option<&Skill>,
    until_s: Option<f64>,
    shard: Option<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Py<PyAny>> {
    let mut parsed: Vec<Method> = Vec::new();
    for name in &methods {
        let m = method(name)?;
        if !parsed.contains(&m) {
            parsed.push(m);
        }
    }
    if parsed.is_empty() {
        return Err(PyValueError::new_err("methods: empty; give at least one of fluid, dmp, replay"));
    }
    if let Some(j) = jobs
        && !(1..=MAX_JOBS).contains(&j)
    {
        return Err(PyValueError::new_err(format!("jobs {j}: 1 to {MAX_JOBS} threads (None: one per core)")));
    }
    crate::trial::check_until(until_s)?;
    let shard = shard.map(|s| s.parse::<Shard>()).transpose().map_err(PyValueError::new_err)?;
    let (scene, scene_name) =
        crate::scene::load(scene.as_deref(), preset.as_deref()).map_err(knotlab_error)?;
    let learned = py.detach(|| or_shipped(skill)).map_err(knotlab_error)?;
    let options = McOptions {
        scene,
        scene_name,
        preset,
        trials,
        seed,
        jobs: jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        methods: parsed,
        out,
        until_s,
        shard,
        skill_fingerprint: skill_fingerprint(&learned),
    };
    let stop = AtomicBool::new(false);
    let mut interrupt: Option<PyErr> = None;
    let runner =
        |setup: &TrialSetup, record: &RecordOptions, _trial: u64| run_trial(&learned, setup, record, None);
    let result = py.detach(|| {
        run_mc_with(&options, &runner, &stop, |line, done, total| {
            Python::attach(|py| {
                if let Err(e) = py.check_signals() {
                    stop.store(true, Ordering::SeqCst);
                    interrupt.get_or_insert(e);
                }
                if let Some(callback) = &progress
                    && interrupt.is_none()
                {
                    let called = to_python(py, line).and_then(|l| callback.call1(py, (l, done, total)));
                    if let Err(e) = called {
                        stop.store(true, Ordering::SeqCst);
                        interrupt.get_or_insert(e);
                    }
                }
            });
        })
    });
    let result = result.map_err(knotlab_error)?;
    if let Some(e) = interrupt {
        return Err(e);
    }
    Ok(to_python(py, &result.summary)?.unbind())
}

/// Reads the run folder `dir` (of `knotlab mc` or `run_mc`): its trials' lines (as dicts, in the
/// file's order), its `run.json` (None when there is none) and the summary of those lines. Every
/// line is checked to belong to the run, as a resumed run checks them.
#[pyfunction]
pub fn read_run(py: Python<'_>, dir: PathBuf) -> PyResult<(Py<PyAny>, Py<PyAny>, Py<PyAny>)> {
    let file = results_path(&dir).display().to_string();
    let info = RunInfo::read(&dir).map_err(knotlab_error)?;
    let lines = read_results(&dir).map_err(knotlab_error)?;
    if lines.is_empty() && info.is_none() {
        return Err(knotlab_error(format!("{}: no run here (no run.json, no results.jsonl)", dir.display())));
    }
    let summary = match &info {
        Some(info) => {
            check_lines(&lines, info, &file).map_err(knotlab_error)?;
            let methods = info.methods.iter().map(|m| method(m)).collect::<PyResult<Vec<_>>>()?;
            summarize(&info.scene, info.seed, info.trials, &methods, &lines)
        }
        None => {
            check_lines_alone(&lines, &file).map_err(knotlab_error)?;
            let mut methods: Vec<Method> = Vec::new();
            for l in &lines {
                let m = method(&l.method)?;
                if !methods.contains(&m) {
                    methods.push(m);
                }
            }
            let trials = lines.iter().map(|l| l.trial + 1).max().unwrap_or(0);
            summarize("", lines.first().map_or(0, |l| l.seed), trials, &methods, &lines)
        }
    };
    Ok((to_python(py, &lines)?.unbind(), to_python(py, &info)?.unbind(), to_python(py, &summary)?.unbind()))
}
