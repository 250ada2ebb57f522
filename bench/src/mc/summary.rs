//! The run's summary: per method the success rate with its 95 % Wilson interval, the failure modes,
//! and success against the stitch's displacement and the play in bins. Built from the results sorted by
//! trial, so it does not depend on the order trials finished in.

use std::collections::BTreeMap;

use knotlab_learner::synthesis::Method;
use knotlab_sim::thread_watch::STRETCH_NOTED;
use serde::Serialize;

use super::TrialLine;

/// The 95 % Wilson score interval of `successes` out of `n` (`(0, 1)` for none).
pub fn wilson_interval(successes: usize, n: usize) -> (f64, f64) {
    if n == 0 {
        return (0.0, 1.0);
    }
    let z = 1.959_963_984_540_054;
    let (n, p) = (n as f64, successes as f64 / n as f64);
    let denominator = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denominator;
    let half = z * ((p * (1.0 - p) + z * z / (4.0 * n)) / n).sqrt() / denominator;
    // No success (or no failure) puts the bound exactly at 0 (or 1); the formula leaves round-off there.
    let lo = if successes == 0 { 0.0 } else { (centre - half).max(0.0) };
    let hi = if successes == n as usize { 1.0 } else { (centre + half).min(1.0) };
    (lo, hi)
}

/// Success in one bin of a drawn parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Bin {
    /// The bin's bounds.
    pub from: f64,
    /// ...
    pub to: f64,
    /// Trials in it.
    pub trials: usize,
    /// Successes.
    pub successes: usize,
}

/// One method's figures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MethodSummary {
    /// The method.
    pub method: String,
    /// Trials finished.
    pub trials: usize,
    /// Knots accepted.
    pub successes: usize,
    /// successes / trials.
    pub success_rate: f64,
    /// The 95 % Wilson interval of the rate.
    pub wilson_95: [f64; 2],
    /// Trials per verdict.
    pub verdicts: BTreeMap<String, usize>,
    /// How often the thread passed through itself (a solver failure, not a verdict): in how many
    /// trials, and how often in all, over the trials whose lines count it.
    pub thread_self_crossings: SelfCrossings,
    /// How far the suture stretched (a solver error: the suture is inextensible; not a verdict),
    /// over the trials whose lines record it.
    pub thread_stretch: ThreadStretch,
    /// Success against each drawn parameter, in 4 equal bins over its drawn range: the stitch's
    /// displacement (m) and turn (|rad|), the play (rad), the largest calibration error drawn over the
    /// arms' joints (rad), the thread's friction and bending stiffness (N m/rad), the sensor noise (N).
    pub bins: BTreeMap<String, Vec<Bin>>,
}

/// Thread self-crossings over a method's trials.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct SelfCrossings {
    /// Trials whose line counts them (lines written before the count was recorded do not).
    pub counted_trials: usize,
    /// Of those, trials where the thread passed through itself at least once.
    pub trials_with_any: usize,
    /// Self-crossings over all counted trials.
    pub total: usize,
}

/// The [`SelfCrossings`] of `lines`.
pub fn self_crossings(lines: &[&TrialLine]) -> SelfCrossings {
    let counts: Vec<usize> = lines.iter().filter_map(|l| l.thread_self_crossings).collect();
    SelfCrossings {
        counted_trials: counts.len(),
        trials_with_any: counts.iter().filter(|&&n| n > 0).count(),
        total: counts.iter().sum(),
    }
}

/// The suture's largest stretch over a method's trials.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ThreadStretch {
    /// Trials whose line records it (lines written before it was recorded do not).
    pub measured_trials: usize,
    /// The median over those trials of each trial's largest stretch, a fraction of the rest length.
    pub median: Option<f64>,
    /// The largest over them.
    pub max: Option<f64>,
    /// Trials whose suture stretched beyond [`STRETCH_NOTED`].
    pub trials_over_5_percent: usize,
    /// The median over the trials of the time each trial's suture spent stretched beyond
    /// [`STRETCH_NOTED`], s.
    pub median_over_5_percent_s: Option<f64>,
}

/// The [`ThreadStretch`] of `lines`.
pub fn thread_stretch(lines: &[&TrialLine]) -> ThreadStretch {
    let median = |mut values: Vec<f64>| {
        values.sort_by(f64::total_cmp);
        (!values.is_empty()).then(|| values[values.len() / 2])
    };
    let mut ratios: Vec<f64> = lines.iter().filter_map(|l| l.thread_max_stretch).collect();
    ratios.sort_by(f64::total_cmp);
    ThreadStretch {
        measured_trials: ratios.len(),
        median: median(ratios.clone()),
        max: ratios.last().copied(),
        trials_over_5_percent: ratios.iter().filter(|&&r| r > STRETCH_NOTED).count(),
        median_over_5_percent_s: median(lines.iter().filter_map(|l| l.thread_stretched_s).collect()),
    }
}

/// The summary file.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Summary {
    /// The scene.
    pub scene: String,
    /// The run's seed.
    pub seed: u64,
    /// Trials asked for.
    pub trials: u64,
    /// Per method.
    pub methods: Vec<MethodSummary>,
}

fn bins(lines: &[&TrialLine], value: impl Fn(&TrialLine) -> f64) -> Vec<Bin> {
    let values: Vec<f64> = lines.iter().map(|l| value(l)).collect();
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !(lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let width = ((hi - lo) / 4.0).max(1e-12);
    (0..4)
        .map(|b| {
            let (from, to) = (lo + width * b as f64, lo + width * (b + 1) as f64);
            let inside: Vec<&&TrialLine> = lines
                .iter()
                .zip(&values)
                .filter(|(_, v)| **v >= from && (**v < to || (b == 3 && **v <= to + 1e-12)))
                .map(|(l, _)| l)
                .collect();
            Bin {
                from,
                to,
                trials: inside.len(),
                successes: inside.iter().filter(|l| l.verdict == "success").count(),
            }
        })
        .collect()
}

fn number(l: &TrialLine, key: &str) -> f64 {
    l.draw.get(key).and_then(serde_json::Value::as_f64).unwrap_or(0.0)
}

fn displacement(l: &TrialLine) -> f64 {
    l.draw
        .get("stitch_offset_m")
        .and_then(|v| v.as_array())
        .map_or(0.0, |a| a.iter().filter_map(serde_json::Value::as_f64).map(|x| x * x).sum::<f64>().sqrt())
}

/// Success against every drawn parameter.
fn binned(lines: &[&TrialLine]) -> BTreeMap<String, Vec<Bin>> {
    let mut out = BTreeMap::new();
    out.insert("stitch_displacement_m".to_owned(), bins(lines, displacement));
    out.insert("stitch_rotate_rad".to_owned(), bins(lines, |l| number(l, "stitch_rotate_rad").abs()));
    out.insert("stitch_tilt_rad".to_owned(), bins(lines, |l| number(l, "stitch_tilt_rad").abs()));
    for key in
        ["play_rad", "calibration_max_rad", "thread_friction", "thread_bend_stiffness", "force_noise_n"]
    {
        out.insert(key.to_owned(), bins(lines, |l| number(l, key)));
    }
    out
}

/// How `lines` ended: trials, successes, the rate, its 95 % Wilson interval, trials per verdict.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Tally {
    /// Trials.
    pub trials: usize,
    /// Knots accepted.
    pub successes: usize,
    /// successes / trials (0 for none).
    pub success_rate: f64,
    /// The 95 % Wilson interval of the rate.
    pub wilson_95: [f64; 2],
    /// Trials per verdict.
    pub verdicts: BTreeMap<String, usize>,
}

/// The [`Tally`] of `lines`.
pub fn tally(lines: &[&TrialLine]) -> Tally {
    let successes = lines.iter().filter(|l| l.verdict == "success").count();
    let (lo, hi) = wilson_interval(successes, lines.len());
    let mut verdicts = BTreeMap::new();
    for l in lines {
        *verdicts.entry(l.verdict.clone()).or_insert(0) += 1;
    }
    Tally {
        trials: lines.len(),
        successes,
        success_rate: if lines.is_empty() { 0.0 } else { successes as f64 / lines.len() as f64 },
        wilson_95: [lo, hi],
        verdicts,
    }
}

/// The summary of `lines` (any order) for `methods`.
pub fn summarize(scene: &str, seed: u64, trials: u64, methods: &[Method], lines: &[TrialLine]) -> Summary {
    let mut sorted: Vec<&TrialLine> = lines.iter().filter(|l| l.trial < trials).collect();
    sorted.sort_by(|a, b| (a.trial, &a.method).cmp(&(b.trial, &b.method)));
    sorted.dedup_by(|a, b| a.trial == b.trial && a.method == b.method);
    let methods = methods
        .iter()
        .map(|m| {
            let mine: Vec<&TrialLine> = sorted.iter().copied().filter(|l| l.method == m.as_str()).collect();
            let Tally { trials, successes, success_rate, wilson_95, verdicts } = tally(&mine);
            MethodSummary {
                method: m.to_string(),
                trials,
                successes,
                success_rate,
                wilson_95,
                verdicts,
                thread_self_crossings: self_crossings(&mine),
                thread_stretch: thread_stretch(&mine),
                bins: binned(&mine),
            }
        })
        .collect();
    Summary { scene: scene.to_owned(), seed, trials, methods }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The 95 % Wilson interval matches the textbook, also with no successes, all successes or no trials.
    #[test]
    fn wilson_intervals_match_the_textbook() {
        // 8 of 10: 0.490 to 0.943 (Wilson 1927, z = 1.96).
        let (lo, hi) = wilson_interval(8, 10);
        assert!((lo - 0.4902).abs() < 1e-4 && (hi - 0.9433).abs() < 1e-4, "{lo} {hi}");
        let (lo, hi) = wilson_interval(0, 50);
        assert!(lo == 0.0 && (hi - 0.0714).abs() < 1e-4, "{lo} {hi}");
        let (lo, hi) = wilson_interval(50, 50);
        assert!((lo - 0.9286).abs() < 1e-4 && hi == 1.0, "{lo} {hi}");
        assert_eq!(wilson_interval(0, 0), (0.0, 1.0));
    }

    /// The stretch tally takes the median and the largest of the lines that record it, counts those
    /// beyond 5 % and takes the median of their time beyond it.
    #[test]
    fn thread_stretch_takes_median_and_max_and_counts_the_large_ones() {
        let stretched = |trial, ratio: Option<f64>| TrialLine {
            thread_max_stretch: ratio,
            thread_stretched_s: ratio.map(|r| if r > 0.05 { 0.5 } else { 0.0 }),
            ..line(trial, Some(0))
        };
        let lines =
            [stretched(0, Some(0.01)), stretched(1, Some(0.2)), stretched(2, None), stretched(3, Some(0.04))];
        let refs: Vec<&TrialLine> = lines.iter().collect();
        let expected = ThreadStretch {
            measured_trials: 3,
            median: Some(0.04),
            max: Some(0.2),
            trials_over_5_percent: 1,
            median_over_5_percent_s: Some(0.0),
        };
        assert_eq!(thread_stretch(&refs), expected);
        assert_eq!(thread_stretch(&[]), ThreadStretch::default());
    }

    fn line(trial: u64, crossings: Option<usize>) -> TrialLine {
        TrialLine {
            trial,
            thread_self_crossings: crossings,
            ..crate::report::test_line("dmp", serde_json::Value::Null, "no_knot")
        }
    }

    /// The self-crossing tally counts only lines that carry a count, the trials with any and the total, and
    /// the run summary reports that total.
    #[test]
    fn self_crossings_count_trials_and_passes_and_skip_lines_that_lack_them() {
        let lines = [line(0, Some(0)), line(1, Some(2)), line(2, None), line(3, Some(1))];
        let refs: Vec<&TrialLine> = lines.iter().collect();
        assert_eq!(self_crossings(&refs), SelfCrossings { counted_trials: 3, trials_with_any: 2, total: 3 });
        let summary = summarize("s", 7, 4, &[Method::Dmp], &lines);
        assert_eq!(summary.methods[0].thread_self_crossings.total, 3);
    }
}
