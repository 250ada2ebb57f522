//! Scores of a decomposition against known primitive boundaries, as used for surgical gesture
//! segmentation (JIGSAWS; Lea et al. 2016): the error of each boundary, boundary precision, recall and
//! F1 within a tolerance, and the segmental edit score (the Levenshtein distance between the sequences
//! of segment labels, as a percentage of the longer sequence).

use knotlab_hw::rig::ArmName;

/// A labelled time span of one instrument.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelledSpan {
    /// The instrument.
    pub instrument: ArmName,
    /// The label (the primitive's name).
    pub label: String,
    /// Start, s.
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
}

/// The absolute errors of the boundaries of `predicted` against `truth`, matched by instrument and
/// label (start with start, end with end); labels missing on either side are left out. Seconds.
pub fn boundary_errors(truth: &[LabelledSpan], predicted: &[LabelledSpan]) -> Vec<f64> {
    let mut out = Vec::new();
    for t in truth {
        if let Some(p) = predicted.iter().find(|p| p.instrument == t.instrument && p.label == t.label) {
            out.push((p.start_s - t.start_s).abs());
            out.push((p.end_s - t.end_s).abs());
        }
    }
    out
}

/// Counts of boundaries matched within a tolerance.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BoundaryCounts {
    /// Predicted boundaries within the tolerance of a true one (each true one used once).
    pub true_positives: usize,
    /// Predicted boundaries with no true one near.
    pub false_positives: usize,
    /// True boundaries with no predicted one near.
    pub false_negatives: usize,
}

impl BoundaryCounts {
    /// Adds another demonstration's counts.
    pub fn add(&mut self, other: BoundaryCounts) {
        self.true_positives += other.true_positives;
        self.false_positives += other.false_positives;
        self.false_negatives += other.false_negatives;
    }

    /// Precision (1 when nothing was predicted).
    pub fn precision(&self) -> f64 {
        let p = self.true_positives + self.false_positives;
        if p == 0 { 1.0 } else { self.true_positives as f64 / p as f64 }
    }

    /// Recall (1 when there was nothing to find).
    pub fn recall(&self) -> f64 {
        let t = self.true_positives + self.false_negatives;
        if t == 0 { 1.0 } else { self.true_positives as f64 / t as f64 }
    }

    /// The harmonic mean of precision and recall.
    pub fn f1(&self) -> f64 {
        let (p, r) = (self.precision(), self.recall());
        if p + r == 0.0 { 0.0 } else { 2.0 * p * r / (p + r) }
    }
}

/// The distinct boundary times of one instrument's spans (times within 1 ms are one boundary).
fn boundaries(spans: &[LabelledSpan], instrument: ArmName) -> Vec<f64> {
    let mut times: Vec<f64> =
        spans.iter().filter(|s| s.instrument == instrument).flat_map(|s| [s.start_s, s.end_s]).collect();
    times.sort_by(f64::total_cmp);
    times.dedup_by(|a, b| (*a - *b).abs() < 1e-3);
    times
}

/// Boundary counts within `tolerance_s`, per instrument, one-to-one (nearest pairs first).
pub fn boundary_counts(
    truth: &[LabelledSpan],
    predicted: &[LabelledSpan],
    tolerance_s: f64,
) -> BoundaryCounts {
    let mut counts = BoundaryCounts::default();
    let mut instruments: Vec<ArmName> = truth.iter().chain(predicted).map(|s| s.instrument).collect();
    instruments.sort();
    instruments.dedup();
    for arm in instruments {
        let t = boundaries(truth, arm);
        let p = boundaries(predicted, arm);
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for (i, a) in p.iter().enumerate() {
            for (j, b) in t.iter().enumerate() {
                let d = (a - b).abs();
                if d <= tolerance_s {
                    pairs.push((d, i, j));
                }
            }
        }
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (mut used_p, mut used_t) = (vec![false; p.len()], vec![false; t.len()]);
        let mut tp = 0;
        for (_, i, j) in pairs {
            if !used_p[i] && !used_t[j] {
                used_p[i] = true;
                used_t[j] = true;
                tp += 1;
            }
        }
        counts.add(BoundaryCounts {
            true_positives: tp,
            false_positives: p.len() - tp,
            false_negatives: t.len() - tp,
        });
    }
    counts
}

/// The sequence of labels over time of one instrument's spans, sampled every `dt_s` from `from_s` to
/// `to_s` (`""` where no span is), consecutive repeats collapsed.
fn label_sequence(
    spans: &[LabelledSpan],
    instrument: ArmName,
    from_s: f64,
    to_s: f64,
    dt_s: f64,
) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let count = ((to_s - from_s) / dt_s).ceil().max(0.0) as usize;
    for k in 0..=count {
        let t = from_s + k as f64 * dt_s;
        let label = spans
            .iter()
            .find(|s| s.instrument == instrument && s.start_s <= t && t < s.end_s)
            .map_or("", |s| s.label.as_str());
        if out.last().is_none_or(|l| l != label) {
            out.push(label.to_owned());
        }
    }
    out
}

/// Levenshtein distance between two sequences.
fn levenshtein(a: &[String], b: &[String]) -> usize {
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, x) in a.iter().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, y) in b.iter().enumerate() {
            let substitute = previous + usize::from(x != y);
            previous = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

/// The segmental edit score, 0 to 100, averaged over the instruments of `truth`: labels sampled every
/// `dt_s` over the union of both decompositions' time spans (gaps between primitives are a label of
/// their own), repeats collapsed, `100 (1 - distance / longer length)`.
pub fn segmental_edit_score(truth: &[LabelledSpan], predicted: &[LabelledSpan], dt_s: f64) -> f64 {
    let all = truth.iter().chain(predicted);
    let from = all.clone().map(|s| s.start_s).fold(f64::INFINITY, f64::min) - dt_s;
    let to = all.map(|s| s.end_s).fold(f64::NEG_INFINITY, f64::max) + dt_s;
    let mut instruments: Vec<ArmName> = truth.iter().map(|s| s.instrument).collect();
    instruments.sort();
    instruments.dedup();
    if instruments.is_empty() || to.partial_cmp(&from) != Some(std::cmp::Ordering::Greater) {
        return 100.0;
    }
    let scores: Vec<f64> = instruments
        .iter()
        .map(|&arm| {
            let a = label_sequence(truth, arm, from, to, dt_s);
            let b = label_sequence(predicted, arm, from, to, dt_s);
            100.0 * (1.0 - levenshtein(&a, &b) as f64 / a.len().max(b.len()).max(1) as f64)
        })
        .collect();
    scores.iter().sum::<f64>() / scores.len() as f64
}

/// The median of some values (`NaN` when empty).
pub fn median(values: &[f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}
