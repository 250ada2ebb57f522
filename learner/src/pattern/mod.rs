//! Task patterns: what a demonstration of a task must contain, written by hand in TOML. Per instrument,
//! the features that must occur, in temporal order (each with an id, a kind, optional bounds on its
//! magnitude, a grasp state it must leave, and other instruments' features it must follow), and which
//! span between two of them becomes which motion primitive: a 2D movement, a linear movement, a
//! force-controlled movement, or a movement synchronized with another instrument's 2D movement.
//!
//! [`load_pattern`] / [`parse_pattern`] read one; every error names the file, the line and the field.
//! The knot-tying task's pattern ships as `scenarios/patterns/knot_tying.toml`; its comments document
//! the format.

pub mod parse;

pub use parse::{PATTERN_FORMAT, PATTERN_FORMAT_VERSION, PatternError, load_pattern, parse_pattern};

use std::fmt;

use knotlab_hw::rig::ArmName;

use crate::demonstration::GraspState;
use crate::features::{DetectorParams, FeatureKind};

/// The four kinds of motion primitive (after the paper).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PrimitiveType {
    /// A movement in a plane (the winding), regenerated later through the fluid simulation.
    TwoD,
    /// A straight movement from a start to an end.
    Linear,
    /// A straight pull until a force is reached, then a jaw action.
    Force,
    /// A movement tied to another instrument's 2D movement by a mapping.
    Synchronized,
}

impl PrimitiveType {
    /// All four.
    pub const ALL: [PrimitiveType; 4] =
        [PrimitiveType::TwoD, PrimitiveType::Linear, PrimitiveType::Force, PrimitiveType::Synchronized];

    /// The name in pattern files and knowledge bases: `2d`, `linear`, `force`, `synchronized`.
    pub fn as_str(self) -> &'static str {
        match self {
            PrimitiveType::TwoD => "2d",
            PrimitiveType::Linear => "linear",
            PrimitiveType::Force => "force",
            PrimitiveType::Synchronized => "synchronized",
        }
    }

    /// The type a name denotes.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.as_str() == name)
    }
}

impl fmt::Display for PrimitiveType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One feature a pattern expects of an instrument.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// Its id, unique in the pattern (`L1_start`).
    pub id: String,
    /// The kind of feature.
    pub kind: FeatureKind,
    /// What it means, for people and for rejection messages.
    pub description: String,
    /// The feature's magnitude must be at least this (unit of the kind).
    pub min_magnitude: Option<f64>,
    /// ... and at most this.
    pub max_magnitude: Option<f64>,
    /// It may come this much before the previous element's feature (near-simultaneous events), s.
    pub slack_s: f64,
    /// It must come after these elements of other instruments (ids), each less `slack_s`.
    pub after: Vec<String>,
    /// The grasp state the feature must leave (read shortly after it), if any.
    pub grasp: Option<GraspState>,
    /// Line of the element in the pattern file (0 when built in code).
    pub line: usize,
}

/// One primitive a pattern cuts out of an instrument's demonstration.
#[derive(Clone, Debug, PartialEq)]
pub struct PrimitiveSpec {
    /// Its name, unique in the pattern (`L1`, `R2`).
    pub name: String,
    /// Its type.
    pub kind: PrimitiveType,
    /// The element whose feature starts it (for a synchronized primitive, `None`: its reference's start).
    pub from: Option<String>,
    /// The element whose feature ends it (for a synchronized primitive, `None`: its reference's end).
    pub to: Option<String>,
    /// A synchronized primitive's reference: the name of another instrument's 2D primitive.
    pub reference: Option<String>,
    /// What it is.
    pub description: String,
    /// Line of the primitive in the pattern file (0 when built in code).
    pub line: usize,
}

/// What one instrument must do.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrumentPattern {
    /// The instrument.
    pub instrument: ArmName,
    /// The features in temporal order.
    pub elements: Vec<Element>,
    /// The primitives, in temporal order.
    pub primitives: Vec<PrimitiveSpec>,
}

impl InstrumentPattern {
    /// The index of an element by id.
    pub fn element_index(&self, id: &str) -> Option<usize> {
        self.elements.iter().position(|e| e.id == id)
    }
}

/// A task pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct TaskPattern {
    /// The task's name.
    pub name: String,
    /// What it is.
    pub description: String,
    /// The feature detectors' thresholds for this task (defaults unless the file's `[detector]` sets them).
    pub detector: DetectorParams,
    /// Per instrument, in the file's order (left, right, assist as present).
    pub instruments: Vec<InstrumentPattern>,
}

impl TaskPattern {
    /// The pattern of one instrument.
    pub fn instrument(&self, name: ArmName) -> Option<&InstrumentPattern> {
        self.instruments.iter().find(|i| i.instrument == name)
    }

    /// The instrument and index of an element by id.
    pub fn find_element(&self, id: &str) -> Option<(ArmName, usize)> {
        self.instruments.iter().find_map(|i| i.element_index(id).map(|k| (i.instrument, k)))
    }

    /// A primitive by name, with its instrument.
    pub fn find_primitive(&self, name: &str) -> Option<(ArmName, &PrimitiveSpec)> {
        self.instruments
            .iter()
            .find_map(|i| i.primitives.iter().find(|p| p.name == name).map(|p| (i.instrument, p)))
    }

    /// The primitive an element lies in (between its `from` and `to`, inclusive), if any.
    pub fn primitive_of(&self, instrument: ArmName, element: usize) -> Option<&PrimitiveSpec> {
        let ip = self.instrument(instrument)?;
        ip.primitives.iter().find(|p| {
            let (Some(from), Some(to)) = (&p.from, &p.to) else { return false };
            match (ip.element_index(from), ip.element_index(to)) {
                (Some(a), Some(b)) => (a..=b).contains(&element),
                _ => false,
            }
        })
    }
}
