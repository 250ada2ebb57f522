//! Decomposition of a demonstration by its task pattern (the paper's matching step): each instrument's
//! pattern elements are aligned with its detected features ([`matcher`], dynamic programming, tolerant
//! of spurious features and of jitter within each element's slack), the instruments' `after`
//! constraints resolved by repeating the alignment with the other instruments' matched times, and the
//! pattern's spans cut into primitives. A demonstration that does not match is rejected
//! ([`Rejection`]): which element of which instrument could not be found, what it means, where matching
//! stopped, and what was there instead.
//!
//! [`metrics`] scores a decomposition against known boundaries (boundary error, boundary F1, segmental
//! edit score).

pub mod matcher;
pub mod metrics;
pub mod rejection;

pub use rejection::{Failure, FailureReason, Rejection};

use std::collections::HashMap;

use knotlab_hw::rig::ArmName;

use crate::features::{Feature, FeatureSet};
use crate::pattern::{PrimitiveType, TaskPattern};

use self::matcher::{Alignment, align};

/// How many times the alignment is repeated to settle the instruments' `after` constraints.
const MAX_PASSES: usize = 4;

/// One primitive cut out of the demonstration.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The instrument.
    pub instrument: ArmName,
    /// The primitive's name in the pattern.
    pub name: String,
    /// Its type.
    pub kind: PrimitiveType,
    /// Start, s (the demonstration's clock).
    pub start_s: f64,
    /// End, s.
    pub end_s: f64,
    /// A synchronized primitive's reference primitive.
    pub reference: Option<String>,
}

impl Segment {
    /// As a labelled span for [`metrics`].
    pub fn span(&self) -> metrics::LabelledSpan {
        metrics::LabelledSpan {
            instrument: self.instrument,
            label: self.name.clone(),
            start_s: self.start_s,
            end_s: self.end_s,
        }
    }
}

/// The features one instrument's elements were matched to.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrumentMatch {
    /// The instrument.
    pub instrument: ArmName,
    /// Per element of the pattern: its id and the feature matched.
    pub matched: Vec<(String, Feature)>,
    /// Detected features left unmatched before the last match (spurious ones).
    pub skipped: usize,
}

/// A demonstration decomposed by a pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct Decomposition {
    /// The pattern's name.
    pub pattern: String,
    /// The primitives, per instrument in the pattern's order, each in time order.
    pub segments: Vec<Segment>,
    /// The matches.
    pub matches: Vec<InstrumentMatch>,
}

impl Decomposition {
    /// The time of a matched element by id.
    pub fn element_time_s(&self, id: &str) -> Option<f64> {
        self.matches.iter().flat_map(|m| &m.matched).find(|(e, _)| e == id).map(|(_, f)| f.time_s)
    }

    /// Every segment as a labelled span for [`metrics`].
    pub fn spans(&self) -> Vec<metrics::LabelledSpan> {
        self.segments.iter().map(Segment::span).collect()
    }

    /// A segment by name.
    pub fn segment(&self, name: &str) -> Option<&Segment> {
        self.segments.iter().find(|s| s.name == name)
    }
}

/// Decomposes a demonstration's features by `pattern`, or rejects it.
pub fn decompose(pattern: &TaskPattern, features: &FeatureSet) -> Result<Decomposition, Rejection> {
    let first = |a: &crate::features::InstrumentAnalysis| a.times_s.first().copied();
    let last = |a: &crate::features::InstrumentAnalysis| a.times_s.last().copied();
    let recording_start_s = features.instruments.iter().filter_map(first).reduce(f64::min).unwrap_or(0.0);
    let recording_end_s = features.instruments.iter().filter_map(last).reduce(f64::max).unwrap_or(0.0);
    let empty: Vec<Feature> = Vec::new();
    let features_of = |arm: ArmName| features.instrument(arm).map_or(&empty, |a| &a.features);
    // Matched times of element ids, from the previous pass.
    let mut times: HashMap<String, f64> = HashMap::new();
    let mut alignments: Vec<Alignment> = Vec::new();
    for _pass in 0..MAX_PASSES {
        let mut next_times: HashMap<String, f64> = HashMap::new();
        let mut next_alignments = Vec::new();
        for ip in &pattern.instruments {
            let fs = features_of(ip.instrument);
            let bounds: Vec<Option<f64>> = ip
                .elements
                .iter()
                .map(|e| {
                    e.after.iter().filter_map(|id| times.get(id).map(|t| t - e.slack_s)).reduce(f64::max)
                })
                .collect();
            let alignment = align(&ip.elements, fs, &bounds);
            let assignment = match &alignment {
                Alignment::Complete { assignment, .. } | Alignment::Partial { assignment, .. } => assignment,
            };
            for (e, &j) in ip.elements.iter().zip(assignment) {
                next_times.insert(e.id.clone(), fs[j].time_s);
            }
            next_alignments.push(alignment);
        }
        let settled = next_alignments == alignments;
        alignments = next_alignments;
        times = next_times;
        if settled {
            break;
        }
    }

    // Failures: elements not found, and `after` constraints not met by the final matches.
    let mut failures = Vec::new();
    for (ip, alignment) in pattern.instruments.iter().zip(&alignments) {
        let fs = features_of(ip.instrument);
        match alignment {
            Alignment::Partial { matched, assignment } => {
                let mut failure = rejection::not_found(
                    pattern,
                    ip,
                    (*matched, assignment),
                    fs,
                    &times,
                    (recording_start_s, recording_end_s),
                );
                if features.instrument(ip.instrument).is_none() {
                    failure.reason = FailureReason::NotFound {
                        instead: Some(format!(
                            "the demonstration has no record of the {} instrument",
                            ip.instrument
                        )),
                    };
                }
                failures.push(failure);
            }
            Alignment::Complete { .. } => {
                if let Some(f) = rejection::unmet_after(pattern, ip, &times, recording_end_s) {
                    failures.push(f);
                }
            }
        }
    }
    if !failures.is_empty() {
        return Err(Rejection::new(pattern.name.clone(), failures));
    }

    let mut matches = Vec::new();
    for (ip, alignment) in pattern.instruments.iter().zip(&alignments) {
        let Alignment::Complete { assignment, skipped } = alignment else { continue };
        let fs = features_of(ip.instrument);
        matches.push(InstrumentMatch {
            instrument: ip.instrument,
            matched: ip.elements.iter().zip(assignment).map(|(e, &j)| (e.id.clone(), fs[j])).collect(),
            skipped: *skipped,
        });
    }
    let time = |id: &str| times.get(id).copied().unwrap_or(f64::NAN);
    let mut segments = Vec::new();
    for ip in &pattern.instruments {
        for p in &ip.primitives {
            let (start_s, end_s) = match (&p.from, &p.to, &p.reference) {
                (Some(from), Some(to), _) => (time(from), time(to)),
                (_, _, Some(reference)) => match pattern.find_primitive(reference) {
                    Some((_, r)) => {
                        (r.from.as_deref().map_or(f64::NAN, time), r.to.as_deref().map_or(f64::NAN, time))
                    }
                    None => (f64::NAN, f64::NAN),
                },
                _ => (f64::NAN, f64::NAN),
            };
            segments.push(Segment {
                instrument: ip.instrument,
                name: p.name.clone(),
                kind: p.kind,
                start_s,
                end_s,
                reference: p.reference.clone(),
            });
        }
    }
    Ok(Decomposition { pattern: pattern.name.clone(), segments, matches })
}
