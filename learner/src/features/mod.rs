//! Feature detectors on a demonstration (the paper's "prominent features"): per instrument, inflection
//! points of the tip's path (curvature sign changes in a locally fitted plane) and loops (full turns in
//! it), force events (onset, peak, release), rapid speed changes (motion starts and stops, acceleration
//! peaks) and jaw openings and closings. Each [`Feature`] has a time, an instrument, a position and a
//! magnitude; the thresholds are [`DetectorParams`].
//!
//! Positions are smoothed with a Gaussian (tremor) before they are differentiated; the smoothed path,
//! its velocity and the motions are kept in [`InstrumentAnalysis`] for the primitive extraction.

pub mod force;
pub mod geometry;
pub mod jaw;
pub mod kind;
pub mod motion;
pub mod params;
pub mod signal;

pub use kind::FeatureKind;
pub use motion::MotionSegment;
pub use params::DetectorParams;

use nalgebra::Vector3;
use thiserror::Error;

use knotlab_hw::rig::ArmName;

use crate::demonstration::{Demonstration, GraspState, InstrumentRecord};

use self::geometry::ShapeFeature;
use self::signal::{derivative, gaussian_smooth, index_at, vector_at};

/// How long after a feature its grasp state is read (for a jaw movement: after the jaws reached the
/// open or closed band), s.
pub const GRASP_SETTLE_S: f64 = 0.15;

/// A feature found in a demonstration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Feature {
    /// The instrument.
    pub instrument: ArmName,
    /// What it is.
    pub kind: FeatureKind,
    /// When, s (the demonstration's clock).
    pub time_s: f64,
    /// The tip's position then (smoothed), world frame, m.
    pub position_m: Vector3<f64>,
    /// How strong (the unit depends on the kind: [`FeatureKind::magnitude_unit`]).
    pub magnitude: f64,
    /// The grasp state [`GRASP_SETTLE_S`] after the feature, or after a jaw movement ended (what the
    /// jaws hold once settled).
    pub grasp_after: GraspState,
}

/// One instrument's signals as the detectors saw them, and its features in time order.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrumentAnalysis {
    /// The instrument.
    pub instrument: ArmName,
    /// Sample times, s.
    pub times_s: Vec<f64>,
    /// Smoothed tip positions, world frame, m.
    pub positions_m: Vec<Vector3<f64>>,
    /// Velocity of the smoothed positions, m/s.
    pub velocity_mps: Vec<Vector3<f64>>,
    /// Its norm, m/s.
    pub speed_mps: Vec<f64>,
    /// The motions between rests.
    pub motions: Vec<MotionSegment>,
    /// The features, in increasing time.
    pub features: Vec<Feature>,
}

impl InstrumentAnalysis {
    /// The smoothed position at `time_s` (linear between samples).
    pub fn position_at(&self, time_s: f64) -> Vector3<f64> {
        vector_at(&self.times_s, &self.positions_m, time_s)
    }
}

/// The features of a whole demonstration.
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureSet {
    /// One analysis per instrument, in the demonstration's order.
    pub instruments: Vec<InstrumentAnalysis>,
}

impl FeatureSet {
    /// The analysis of one instrument.
    pub fn instrument(&self, name: ArmName) -> Option<&InstrumentAnalysis> {
        self.instruments.iter().find(|a| a.instrument == name)
    }

    /// How many features of each kind, over all instruments.
    pub fn count(&self, kind: FeatureKind) -> usize {
        self.instruments.iter().flat_map(|a| &a.features).filter(|f| f.kind == kind).count()
    }
}

/// Why features could not be detected.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FeatureError {
    /// A detector parameter is out of range.
    #[error("detector.{field}: {reason}")]
    Params {
        /// The parameter.
        field: &'static str,
        /// Why.
        reason: String,
    },
    /// An instrument has too few samples to analyse.
    #[error("{instrument}: {samples} samples, need at least 3")]
    TooShort {
        /// The instrument.
        instrument: ArmName,
        /// How many it has.
        samples: usize,
    },
}

/// Detects the features of every instrument of `demo`.
pub fn detect(demo: &Demonstration, params: &DetectorParams) -> Result<FeatureSet, FeatureError> {
    params.check().map_err(|(field, reason)| FeatureError::Params { field, reason })?;
    let instruments =
        demo.instruments.iter().map(|r| analyse(r, params)).collect::<Result<Vec<_>, FeatureError>>()?;
    Ok(FeatureSet { instruments })
}

/// Detects the features of one instrument.
pub fn analyse(
    record: &InstrumentRecord,
    params: &DetectorParams,
) -> Result<InstrumentAnalysis, FeatureError> {
    let samples = &record.samples;
    if samples.len() < 3 {
        return Err(FeatureError::TooShort { instrument: record.instrument, samples: samples.len() });
    }
    let instrument = record.instrument;
    let times: Vec<f64> = samples.iter().map(|s| s.time_s).collect();
    let raw: Vec<Vector3<f64>> = samples.iter().map(|s| s.position_m).collect();
    let positions = gaussian_smooth(&times, &raw, params.smoothing_s);
    let velocity = derivative(&times, &positions);
    let speed: Vec<f64> = velocity.iter().map(|v| v.norm()).collect();
    let steps: Vec<f64> = positions.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let motions = motion::motion_segments(&times, &raw, &speed, &steps, params);

    let grasp_after = |t: f64| samples[index_at(&times, t + GRASP_SETTLE_S)].grasp;
    let mut features = Vec::new();
    let mut push = |kind: FeatureKind, time_s: f64, magnitude: f64, settled_s: f64| {
        features.push(Feature {
            instrument,
            kind,
            time_s,
            position_m: vector_at(&times, &positions, time_s),
            magnitude,
            grasp_after: grasp_after(settled_s),
        });
    };
    for m in &motions {
        push(FeatureKind::MotionStart, m.start_s, m.path_length_m, m.start_s);
        push(FeatureKind::MotionStop, m.end_s, m.path_length_m, m.end_s);
        for f in geometry::shape_features(&times, &positions, m, params) {
            match f {
                ShapeFeature::Inflection { time_s, magnitude_per_m } => {
                    push(FeatureKind::Inflection, time_s, magnitude_per_m, time_s);
                }
                ShapeFeature::Loop { time_s, diameter_m } => {
                    push(FeatureKind::Loop, time_s, diameter_m, time_s)
                }
            }
        }
    }
    for (kind, sign) in [(FeatureKind::Acceleration, 1.0), (FeatureKind::Deceleration, -1.0)] {
        for (index, a) in motion::acceleration_peaks(&times, &speed, &motions, params, sign) {
            push(kind, times[index], a, times[index]);
        }
    }
    let force_raw: Vec<f64> = samples.iter().map(|s| s.force_n.norm()).collect();
    let force = gaussian_smooth(&times, &force_raw, params.force_smoothing_s);
    for e in force::force_episodes(&times, &force, params) {
        push(FeatureKind::ForceOnset, e.onset_s, e.peak_n, e.onset_s);
        push(FeatureKind::ForcePeak, times[e.peak_index], e.peak_n, times[e.peak_index]);
        if let Some((t, _)) = e.release {
            push(FeatureKind::ForceRelease, t, e.peak_n, t);
        }
    }
    let jaw: Vec<f64> = samples.iter().map(|s| s.jaw_rad).collect();
    for e in jaw::jaw_events(&times, &jaw, params) {
        let kind = if e.opening { FeatureKind::JawOpen } else { FeatureKind::JawClose };
        push(kind, e.time_s, e.magnitude_rad, e.ended_s);
    }
    features.sort_by(|a, b| a.time_s.total_cmp(&b.time_s).then(a.kind.cmp(&b.kind)));
    Ok(InstrumentAnalysis {
        instrument,
        times_s: times,
        positions_m: positions,
        velocity_mps: velocity,
        speed_mps: speed,
        motions,
        features,
    })
}
