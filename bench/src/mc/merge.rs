//! `knotlab mc merge`: shards of one run (directories run with `--shard I/N`) combined into the result a
//! single run gives: the same `results.jsonl` lines (sorted by trial and method), `run.json` without a
//! shard, and the same `summary.json` bytes. The shards must be of one run (their `run.json` agree but
//! for the shard), a trial found twice must have the same outcome, and every trial must be there.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use knotlab_learner::synthesis::Method;

use super::run_info::RunInfo;
use super::{McError, Summary, TrialLine, read_results, results_path, summarize, write_summary};

/// What a merge made.
#[derive(Clone, Debug)]
pub struct MergeOutcome {
    /// The merged run's summary (also in `OUT/summary.json`).
    pub summary: Summary,
    /// Lines written.
    pub lines: usize,
    /// The shards combined, as `I/N` (or `all` for a directory that holds a whole run).
    pub shards: Vec<String>,
}

fn error(file: impl Into<String>, reason: impl Into<String>) -> McError {
    McError::Results { file: file.into(), reason: reason.into() }
}

/// A line with what may differ between two runs of the same trial (its wall time) cleared.
fn outcome(line: &TrialLine) -> TrialLine {
    TrialLine { wall_seconds: 0.0, ..line.clone() }
}

/// Merges the run directories `dirs` into `out`.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<MergeOutcome, McError> {
    let Some(first) = dirs.first() else {
        return Err(error("knotlab mc merge", "no directories given"));
    };
    // The same directory twice would count its trials twice; an output that is an input would be
    // overwritten while it is read.
    let same = |a: &Path, b: &Path| {
        let canonical = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
        canonical(a) == canonical(b)
    };
    for (k, dir) in dirs.iter().enumerate() {
        if dirs[..k].iter().any(|d| same(d, dir)) {
            return Err(error(dir.display().to_string(), "given twice: merge each shard once"));
        }
        if same(dir, out) {
            return Err(error(
                out.display().to_string(),
                "is one of the shards being merged, which the merge would overwrite: give another --out",
            ));
        }
    }
    let info_of = |dir: &Path| -> Result<RunInfo, McError> {
        RunInfo::read(dir)?.ok_or_else(|| {
            error(RunInfo::path(dir).display().to_string(), "missing: not a knotlab mc run directory")
        })
    };
    let whole = RunInfo { shard: None, ..info_of(first)? };
    let mut lines: BTreeMap<(u64, String), (TrialLine, PathBuf)> = BTreeMap::new();
    let mut shards = Vec::new();
    for dir in dirs {
        let info = info_of(dir)?;
        if let Some(difference) = whole.difference(&RunInfo { shard: None, ..info.clone() }, true) {
            return Err(error(
                RunInfo::path(dir).display().to_string(),
                format!("not a shard of the same run as {} ({difference})", first.display()),
            ));
        }
        shards.push(info.shard.map_or("all".to_owned(), |s| s.to_string()));
        let shard_lines = read_results(dir)?;
        super::check_lines(&shard_lines, &info, &results_path(dir).display().to_string())?;
        for line in shard_lines {
            let key = (line.trial, line.method.clone());
            match lines.get(&key) {
                Some((seen, from)) if outcome(seen) != outcome(&line) => {
                    return Err(error(
                        results_path(dir).display().to_string(),
                        format!(
                            "trial {} by {} ended otherwise in {} ({} vs {})",
                            key.0,
                            key.1,
                            from.display(),
                            seen.verdict,
                            line.verdict
                        ),
                    ));
                }
                Some(_) => {}
                None => {
                    lines.insert(key, (line, dir.clone()));
                }
            }
        }
    }
    let missing: Vec<String> = (0..whole.trials)
        .flat_map(|t| whole.methods.iter().map(move |m| (t, m.clone())))
        .filter(|key| !lines.contains_key(key))
        .map(|(t, m)| format!("{t} {m}"))
        .collect();
    if !missing.is_empty() {
        let shown: Vec<&str> = missing.iter().take(5).map(String::as_str).collect();
        return Err(error(
            out.display().to_string(),
            format!(
                "{} (trial, method) pairs of the run's {} are in none of the shards ({}{}): run the missing \
                 shards (or resume the interrupted ones) first",
                missing.len(),
                whole.trials * whole.methods.len() as u64,
                shown.join(", "),
                if missing.len() > shown.len() { ", ..." } else { "" }
            ),
        ));
    }
    let methods: Vec<Method> = whole
        .methods
        .iter()
        .map(|m| {
            m.parse::<Method>().map_err(|e| error(RunInfo::path(first).display().to_string(), e.to_string()))
        })
        .collect::<Result<_, _>>()?;
    std::fs::create_dir_all(out).map_err(|e| error(out.display().to_string(), e.to_string()))?;
    if let Some(there) = RunInfo::read(out)?
        && let Some(difference) = there.difference(&whole, true)
        && !dirs.iter().any(|d| d == out)
    {
        return Err(error(
            RunInfo::path(out).display().to_string(),
            format!("the output directory holds another run ({difference}): give an empty one"),
        ));
    }
    let merged: Vec<TrialLine> = lines.into_values().map(|(l, _)| l).collect();
    let path = results_path(out);
    let mut text = Vec::new();
    for line in &merged {
        let json =
            serde_json::to_string(line).map_err(|e| error(path.display().to_string(), e.to_string()))?;
        writeln!(text, "{json}").map_err(|e| error(path.display().to_string(), e.to_string()))?;
    }
    std::fs::write(&path, text).map_err(|e| error(path.display().to_string(), e.to_string()))?;
    whole.write(out)?;
    let summary = summarize(&whole.scene, whole.seed, whole.trials, &methods, &merged);
    write_summary(out, &summary)?;
    Ok(MergeOutcome { summary, lines: merged.len(), shards })
}
