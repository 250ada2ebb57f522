//! The run and each method's figures: trials, successes, the success rate with its 95 % Wilson
//! interval, and the trials per verdict. Plain numbers, no drawing.

use std::collections::{BTreeMap, BTreeSet};

use serde::Serialize;

use crate::mc::TrialLine;
use crate::mc::summary::{SelfCrossings, Tally, ThreadStretch, self_crossings, tally, thread_stretch};

/// The verdict of a knot accepted.
pub const SUCCESS: &str = "success";

/// Whether the line's trial tied the knot.
pub fn is_success(line: &TrialLine) -> bool {
    line.verdict == SUCCESS
}

/// The lines sorted by (trial, method), each (trial, method) once (the first in the file), as
/// `summary.json` counts them.
pub fn unique_lines(lines: &[TrialLine]) -> Vec<TrialLine> {
    let mut sorted = lines.to_vec();
    sorted.sort_by(|a, b| (a.trial, &a.method).cmp(&(b.trial, &b.method)));
    sorted.dedup_by(|a, b| a.trial == b.trial && a.method == b.method);
    sorted
}

/// The run as the lines tell it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunOverview {
    /// The run's seeds (one, unless files were merged).
    pub seeds: Vec<u64>,
    /// Distinct trial indices.
    pub trials: usize,
    /// The smallest and largest trial index.
    pub trial_range: (u64, u64),
    /// The methods, by name.
    pub methods: Vec<String>,
    /// Lines (one per trial and method).
    pub lines: usize,
}

/// What `lines` (as [`unique_lines`] gives them) say about the run; none for no lines.
pub fn run_overview(lines: &[TrialLine]) -> Option<RunOverview> {
    let trials: BTreeSet<u64> = lines.iter().map(|l| l.trial).collect();
    Some(RunOverview {
        seeds: lines.iter().map(|l| l.seed).collect::<BTreeSet<_>>().into_iter().collect(),
        trials: trials.len(),
        trial_range: (*trials.first()?, *trials.last()?),
        methods: method_names(lines),
        lines: lines.len(),
    })
}

/// The methods in `lines`, by name (sorted).
pub fn method_names(lines: &[TrialLine]) -> Vec<String> {
    lines.iter().map(|l| l.method.clone()).collect::<BTreeSet<_>>().into_iter().collect()
}

/// One method's figures (in JSON, the tally's fields beside the method's name).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodStats {
    /// The method.
    pub method: String,
    /// Its trials, successes, rate, Wilson interval and verdicts.
    #[serde(flatten)]
    pub tally: Tally,
    /// How often the thread passed through itself (a solver failure, not a verdict).
    pub thread_self_crossings: SelfCrossings,
    /// How far the suture stretched over the trials that record it.
    pub thread_stretch: ThreadStretch,
}

/// The figures of each of `methods` in `lines`.
pub fn method_stats(lines: &[TrialLine], methods: &[String]) -> Vec<MethodStats> {
    methods
        .iter()
        .map(|m| {
            let mine: Vec<&TrialLine> = lines.iter().filter(|l| &l.method == m).collect();
            MethodStats {
                method: m.clone(),
                tally: tally(&mine),
                thread_self_crossings: self_crossings(&mine),
                thread_stretch: thread_stretch(&mine),
            }
        })
        .collect()
}

/// The failure modes seen over all methods, the most frequent first (ties by name).
pub fn failure_modes(stats: &[MethodStats]) -> Vec<String> {
    let mut total: BTreeMap<&str, usize> = BTreeMap::new();
    for s in stats {
        for (v, n) in &s.tally.verdicts {
            if v != SUCCESS {
                *total.entry(v).or_insert(0) += n;
            }
        }
    }
    let mut modes: Vec<(&str, usize)> = total.into_iter().collect();
    modes.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    modes.into_iter().map(|(v, _)| v.to_owned()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mc::wilson_interval;

    fn line(trial: u64, method: &str, verdict: &str) -> TrialLine {
        TrialLine { trial, seed: 3, ..super::super::test_line(method, serde_json::Value::Null, verdict) }
    }

    /// Each method counts each trial once (the first of duplicate lines wins) with its verdicts and Wilson
    /// interval, failure modes rank by count, and no lines give no run overview.
    #[test]
    fn each_method_counts_its_trials_once_with_its_verdicts() {
        let lines = unique_lines(&[
            line(1, "fluid", "success"),
            line(0, "fluid", "no_knot"),
            line(0, "dmp", "loose"),
            line(1, "dmp", "loose"),
            line(2, "dmp", "success"),
            // A duplicate of (1, fluid): the first is kept.
            line(1, "fluid", "loose"),
        ]);
        assert_eq!(lines.len(), 5);
        let info = run_overview(&lines).unwrap();
        assert_eq!((info.seeds.clone(), info.trials, info.trial_range), (vec![3], 3, (0, 2)));
        assert_eq!(info.methods, vec!["dmp", "fluid"]);
        let stats = method_stats(&lines, &info.methods);
        assert_eq!((stats[0].tally.trials, stats[0].tally.successes), (3, 1));
        assert_eq!((stats[1].tally.trials, stats[1].tally.successes), (2, 1));
        assert_eq!(stats[1].tally.verdicts, BTreeMap::from([("no_knot".into(), 1), ("success".into(), 1)]));
        assert_eq!(stats[0].tally.wilson_95, {
            let (lo, hi) = wilson_interval(1, 3);
            [lo, hi]
        });
        assert_eq!(failure_modes(&stats), vec!["loose", "no_knot"]);
        assert!(run_overview(&[]).is_none());
    }
}
