//! Errors from reading a rig: the file, the element, the field and the reason.

use std::fmt;

/// One thing wrong with a URDF element.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// The element, e.g. `joint 'left_joint2'`.
    pub element: String,
    /// The field of the element, e.g. `parent` or `limit.upper`.
    pub field: String,
    /// What is wrong.
    pub reason: String,
}

impl Problem {
    /// A problem with `field` of `element`.
    pub fn new(element: impl Into<String>, field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self { element: element.into(), field: field.into(), reason: reason.into() }
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}, {}: {}", self.element, self.field, self.reason)
    }
}

/// Why a rig could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum RigError {
    /// The file could not be read.
    #[error("{file}: cannot read: {error}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error (part of this message, so not chained as a source).
        error: std::io::Error,
    },
    /// The file is not a URDF document urdf-rs can parse.
    #[error("{file}: not a valid URDF document: {reason}")]
    Parse {
        /// The file.
        file: String,
        /// The parser's message.
        reason: String,
    },
    /// The document parsed, but elements are wrong; every problem found is listed.
    #[error("{file}: {} problem(s) in the rig:\n{}", problems.len(), list(problems))]
    Invalid {
        /// The file.
        file: String,
        /// Everything found wrong, in document order.
        problems: Vec<Problem>,
    },
}

fn list(problems: &[Problem]) -> String {
    problems.iter().map(|p| format!("  - {p}")).collect::<Vec<_>>().join("\n")
}
