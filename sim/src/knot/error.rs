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
    /// A tissue surface's normal is zero or not finite.
    #[error("the tissue surface's normal {normal:?} is zero or not finite")]
    BadNormal {
        /// The normal as given.
        normal: [f64; 3],
    },
}
