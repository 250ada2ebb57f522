//! Why a demonstration is not a demonstration of the task: per instrument, the pattern element that
//! could not be matched, what it means, the primitive it belongs to, where matching stopped, and what
//! the demonstration had instead.

use std::collections::HashMap;
use std::fmt;

use knotlab_hw::rig::ArmName;

use crate::features::{Feature, FeatureKind};
use crate::pattern::{InstrumentPattern, TaskPattern};

use super::matcher::admissible;

/// Why an element failed.
#[derive(Clone, Debug, PartialEq)]
pub enum FailureReason {
    /// No feature qualifies; `instead` says what the nearest candidate lacked, if there was one.
    NotFound {
        /// The first feature of the element's kind after matching stopped, and why it does not qualify.
        instead: Option<String>,
    },
    /// The element must follow another instrument's element that was not found.
    NeedsUnmatched {
        /// The other element's id.
        id: String,
        /// Its instrument.
        instrument: ArmName,
    },
    /// The element was found, but before the other instrument's element it must follow.
    TooEarly {
        /// The other element's id.
        id: String,
        /// When that one was, s.
        reference_s: f64,
        /// When this one was, s.
        time_s: f64,
    },
}

/// One instrument's failure.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The instrument.
    pub instrument: ArmName,
    /// The element's id.
    pub element: String,
    /// The feature kind it wants.
    pub kind: FeatureKind,
    /// What it means (the pattern's description).
    pub description: String,
    /// The primitive the element belongs to, if any.
    pub primitive: Option<String>,
    /// Where matching stopped: the time of the last element matched before it (the recording's start if
    /// none), s.
    pub stopped_at_s: f64,
    /// The time of the recording's last sample, s.
    pub recording_end_s: f64,
    /// Why.
    pub reason: FailureReason,
}

impl Failure {
    /// Whether the failure is the instrument's own (not caused by another instrument's failure).
    pub fn is_root(&self) -> bool {
        !matches!(self.reason, FailureReason::NeedsUnmatched { .. })
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what =
            if self.description.is_empty() { String::new() } else { format!(": {}", self.description) };
        let within = self.primitive.as_ref().map_or(String::new(), |p| format!(", in {p}"));
        write!(f, "{}: '{}' ({}{what}{within})", self.instrument, self.element, self.kind)?;
        match &self.reason {
            FailureReason::NotFound { instead } => {
                write!(f, " not found after {:.3} s, where matching stopped", self.stopped_at_s)?;
                if let Some(instead) = instead {
                    write!(f, "; {instead}")?;
                }
                write!(f, " (the recording ends at {:.3} s)", self.recording_end_s)
            }
            FailureReason::NeedsUnmatched { id, instrument } => {
                write!(f, " must follow {instrument}'s '{id}', which was not found")
            }
            FailureReason::TooEarly { id, reference_s, time_s } => {
                write!(f, " at {time_s:.3} s comes before '{id}' at {reference_s:.3} s, which it must follow")
            }
        }
    }
}

/// A rejected demonstration.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("not a demonstration of '{pattern}': {}", failures.iter().map(|f| f.to_string()).collect::<Vec<_>>().join("; "))]
pub struct Rejection {
    /// The pattern's name.
    pub pattern: String,
    /// The failures, the instruments' own first, then those caused by another's.
    pub failures: Vec<Failure>,
}

impl Rejection {
    /// A rejection; the failures are ordered roots first.
    pub fn new(pattern: String, mut failures: Vec<Failure>) -> Self {
        failures.sort_by_key(|f| !f.is_root());
        Self { pattern, failures }
    }

    /// The first root failure (what is missing).
    pub fn primary(&self) -> Option<&Failure> {
        self.failures.first()
    }
}

fn describe(f: &Feature) -> String {
    format!("{} at {:.3} s (magnitude {:.4} {})", f.kind, f.time_s, f.magnitude, f.kind.magnitude_unit())
}

/// The failure of an instrument whose elements matched only up to `matched`.
pub(super) fn not_found(
    pattern: &TaskPattern,
    ip: &InstrumentPattern,
    (matched, assignment): (usize, &[usize]),
    features: &[Feature],
    times: &HashMap<String, f64>,
    (recording_start_s, recording_end_s): (f64, f64),
) -> Failure {
    let e = &ip.elements[matched];
    let stopped_at_s = assignment.last().map_or(recording_start_s, |&j| features[j].time_s);
    let primitive = pattern.primitive_of(ip.instrument, matched).map(|p| p.name.clone());
    let base = |reason| Failure {
        instrument: ip.instrument,
        element: e.id.clone(),
        kind: e.kind,
        description: e.description.clone(),
        primitive: primitive.clone(),
        stopped_at_s,
        recording_end_s,
        reason,
    };
    if let Some(id) = e.after.iter().find(|id| !times.contains_key(*id)) {
        let instrument = pattern.find_element(id).map_or(ip.instrument, |(a, _)| a);
        return base(FailureReason::NeedsUnmatched { id: id.clone(), instrument });
    }
    let bound = e.after.iter().filter_map(|id| times.get(id).map(|t| t - e.slack_s)).reduce(f64::max);
    let candidates: Vec<&Feature> =
        features.iter().filter(|f| f.kind == e.kind && f.time_s >= stopped_at_s - e.slack_s).collect();
    let instead = candidates.iter().find(|f| !admissible(e, f, bound)).map(|f| {
        let why = if e.min_magnitude.is_some_and(|m| f.magnitude < m) {
            format!("below min_magnitude {}", e.min_magnitude.unwrap_or_default())
        } else if e.max_magnitude.is_some_and(|m| f.magnitude > m) {
            format!("above max_magnitude {}", e.max_magnitude.unwrap_or_default())
        } else if let Some(g) = e.grasp.filter(|g| *g != f.grasp_after) {
            format!("leaving the jaws {}, not {}", f.grasp_after.as_str(), g.as_str())
        } else if let Some(t) = bound.filter(|t| f.time_s < *t) {
            format!("before {t:.3} s, where its 'after' allows it")
        } else {
            "out of order".to_owned()
        };
        format!("found {} instead, {why}", describe(f))
    });
    let instead = instead.or_else(|| {
        candidates
            .is_empty()
            .then(|| format!("the demonstration has no {} after {stopped_at_s:.3} s", e.kind))
    });
    base(FailureReason::NotFound { instead })
}

/// The first `after` constraint of an instrument that the final matches break, if any.
pub(super) fn unmet_after(
    pattern: &TaskPattern,
    ip: &InstrumentPattern,
    times: &HashMap<String, f64>,
    recording_end_s: f64,
) -> Option<Failure> {
    for (k, e) in ip.elements.iter().enumerate() {
        let time_s = times.get(&e.id).copied()?;
        for id in &e.after {
            let reason = match times.get(id) {
                None => FailureReason::NeedsUnmatched {
                    id: id.clone(),
                    instrument: pattern.find_element(id).map_or(ip.instrument, |(a, _)| a),
                },
                Some(&reference_s) if time_s < reference_s - e.slack_s => {
                    FailureReason::TooEarly { id: id.clone(), reference_s, time_s }
                }
                Some(_) => continue,
            };
            let stopped_at_s =
                if k > 0 { times.get(&ip.elements[k - 1].id).copied().unwrap_or(0.0) } else { 0.0 };
            return Some(Failure {
                instrument: ip.instrument,
                element: e.id.clone(),
                kind: e.kind,
                description: e.description.clone(),
                primitive: pattern.primitive_of(ip.instrument, k).map(|p| p.name.clone()),
                stopped_at_s,
                recording_end_s,
                reason,
            });
        }
    }
    None
}
