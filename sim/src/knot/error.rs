//! Errors of knot evaluation: a centreline that cannot be classified, a tissue surface without a normal.

use thiserror::Error;

/// Why a centreline or a tissue surface was refused.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum KnotError {
    /// Too few points to hold a knot.
    #[error("only {count} point(s); a centreline needs at least 4")]
    TooFewPoints {
        /// How many points were given.
        count: usize,
    },
    /// More points than a centreline may have.
    #[error("{count} points; a centreline may have at most {max}")]
    TooManyPoints {
        /// How many points were given.
        count: usize,
        /// The most allowed ([`super::centreline::MAX_POINTS`]).
        max: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("point {index}: {axis} is not finite ({value})")]
    NotFinite {
        /// Index of the point, from the needle end (0).
        index: usize,
        /// Which coordinate: 'x', 'y' or 'z'.
        axis: char,
        /// The offending value.
        value: f64,
    },
    /// Two consecutive points coincide, leaving a segment without a direction.
    #[error("point {index} repeats point {previous}: consecutive points must differ")]
    DuplicatePoint {
        /// Index of the repeating point.
        index: usize,
        /// Index of the point it repeats (`index - 1`).
        previous: usize,
    },
    /// A grip point that is not on the thread's tail side (`1..count`).
    #[error("grip point {grip} is not on the thread: it has {count} points and the grip must be 1 to {}", count.saturating_sub(1))]
    GripOutOfRange {
        /// The grip point as given.
        grip: usize,
        /// How many points the thread has.
        count: usize,
    },
    /// A draw's length or step that is not finite and positive (or a length under one step).
    #[error(
        "a draw needs a finite length of at least one step and a positive step: got {length_m} m in steps of {step_m} m"
    )]
    BadDraw {
        /// The length as given, m.
        length_m: f64,
        /// The step as given, m.
        step_m: f64,
    },
    /// A tissue surface's normal is zero or not finite.
    #[error("the tissue surface's normal {normal:?} is zero or not finite")]
    BadNormal {
        /// The normal as given.
        normal: [f64; 3],
    },
}
