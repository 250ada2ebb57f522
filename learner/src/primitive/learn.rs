//! Learning in one call: features detected, the pattern matched, the primitives extracted.

use thiserror::Error;

use super::{ExtractError, KnowledgeBase, extract};
use crate::demonstration::Demonstration;
use crate::features::{FeatureError, detect};
use crate::pattern::TaskPattern;
use crate::segment::{Rejection, decompose};

/// Why nothing was learned.
#[derive(Debug, Error)]
pub enum LearnError {
    /// The features could not be detected.
    #[error("detecting features: {0}")]
    Features(#[from] FeatureError),
    /// The demonstration is not one of the task.
    #[error(transparent)]
    Rejected(#[from] Rejection),
    /// A primitive could not be extracted.
    #[error(transparent)]
    Extract(#[from] ExtractError),
}

/// Detects `demo`'s features with `pattern`'s detector, decomposes it by `pattern` and extracts the
/// primitives.
pub fn learn(demo: &Demonstration, pattern: &TaskPattern) -> Result<KnowledgeBase, LearnError> {
    let features = detect(demo, &pattern.detector)?;
    let decomposition = decompose(pattern, &features)?;
    Ok(extract(demo, pattern, &features, &decomposition)?)
}
