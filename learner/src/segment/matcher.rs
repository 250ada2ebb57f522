//! Aligning one instrument's pattern elements with its detected features by dynamic programming: every
//! element is matched to a distinct feature of its kind that meets its bounds, in temporal order (an
//! element may come up to its `slack_s` before the previous one), skipping as few unmatched features as
//! possible before and between matches; spurious features are skipped, jitter within the slack tolerated.

use crate::features::Feature;
use crate::pattern::Element;

/// The result of aligning one instrument.
#[derive(Clone, Debug, PartialEq)]
pub enum Alignment {
    /// Every element matched: the feature index of each, and how many features were skipped between.
    Complete {
        /// Feature index per element.
        assignment: Vec<usize>,
        /// Features skipped before the last match.
        skipped: usize,
    },
    /// Elements `0..matched` could be matched (the best such prefix given), element `matched` not.
    Partial {
        /// How many leading elements matched.
        matched: usize,
        /// Feature index per matched element.
        assignment: Vec<usize>,
    },
}

/// Whether feature `f` can stand for element `e` given the lower time bound from `after` (`None`: none).
pub fn admissible(e: &Element, f: &Feature, lower_bound_s: Option<f64>) -> bool {
    f.kind == e.kind
        && e.min_magnitude.is_none_or(|m| f.magnitude >= m)
        && e.max_magnitude.is_none_or(|m| f.magnitude <= m)
        && e.grasp.is_none_or(|g| f.grasp_after == g)
        && lower_bound_s.is_none_or(|t| f.time_s >= t)
}

/// Aligns `elements` with `features` (in increasing time); `bounds[k]` is element `k`'s lower time
/// bound from its `after` references.
pub fn align(elements: &[Element], features: &[Feature], bounds: &[Option<f64>]) -> Alignment {
    let m = elements.len();
    let n = features.len();
    const NONE: usize = usize::MAX;
    // cost[k][j]: fewest skipped features matching elements 0..=k with element k on feature j;
    // back[k][j]: the feature of element k - 1 on that best path.
    let mut cost = vec![vec![usize::MAX; n]; m];
    let mut back = vec![vec![NONE; n]; m];
    let chain_uses = |back: &Vec<Vec<usize>>, k: usize, mut j: usize, target: usize| -> bool {
        // Whether the best path ending with element k on feature j uses feature `target`.
        let mut kk = k;
        loop {
            if j == target {
                return true;
            }
            if kk == 0 {
                return false;
            }
            j = back[kk][j];
            kk -= 1;
        }
    };
    // Features before the first match count as skipped too: of two otherwise equal alignments the one
    // that starts earlier, explaining more of the demonstration, wins.
    for j in 0..n {
        if admissible(&elements[0], &features[j], bounds[0]) {
            cost[0][j] = j;
        }
    }
    let mut reached = usize::from((0..n).any(|j| cost[0][j] != usize::MAX));
    for k in 1..m {
        if reached < k {
            break;
        }
        let slack = elements[k].slack_s;
        for j in 0..n {
            if !admissible(&elements[k], &features[j], bounds[k]) {
                continue;
            }
            let mut best = (usize::MAX, NONE);
            for i in 0..n {
                if cost[k - 1][i] == usize::MAX || features[j].time_s < features[i].time_s - slack {
                    continue;
                }
                if chain_uses(&back, k - 1, i, j) {
                    continue;
                }
                let skipped = if j > i { j - i - 1 } else { 0 };
                let c = cost[k - 1][i] + skipped;
                if c < best.0 {
                    best = (c, i);
                }
            }
            if best.1 != NONE {
                cost[k][j] = best.0;
                back[k][j] = best.1;
            }
        }
        if (0..n).any(|j| cost[k][j] != usize::MAX) {
            reached = k + 1;
        }
    }
    // The best path of the longest matched prefix: least cost, then earliest end.
    let path_to = |k: usize| -> Option<(usize, Vec<usize>)> {
        let end = (0..n).filter(|&j| cost[k][j] != usize::MAX).min_by(|&a, &b| {
            cost[k][a].cmp(&cost[k][b]).then(features[a].time_s.total_cmp(&features[b].time_s))
        })?;
        let mut assignment = vec![end];
        let mut j = end;
        for kk in (1..=k).rev() {
            j = back[kk][j];
            assignment.push(j);
        }
        assignment.reverse();
        Some((cost[k][end], assignment))
    };
    if reached == m
        && m > 0
        && let Some((skipped, assignment)) = path_to(m - 1)
    {
        return Alignment::Complete { assignment, skipped };
    }
    if reached == 0 {
        return Alignment::Partial { matched: 0, assignment: Vec::new() };
    }
    let (_, assignment) = path_to(reached - 1).unwrap_or((0, Vec::new()));
    Alignment::Partial { matched: assignment.len(), assignment }
}
