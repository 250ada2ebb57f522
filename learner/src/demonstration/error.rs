//! Why a demonstration could not be read or written: the file, the line and the field.

use thiserror::Error;

/// An error reading, validating or writing a demonstration.
#[derive(Debug, Error)]
pub enum DemoError {
    /// A file could not be read or written.
    #[error("{file}: {action}: {error}")]
    Io {
        /// The file.
        file: String,
        /// `cannot read`, `cannot write`, ...
        action: &'static str,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The content is malformed or out of range.
    #[error("{}: {field}: {reason}", knotlab_hw::toml_file::located(file, *line))]
    Format {
        /// The file (its path as given, or its name inside the directory for data in memory).
        file: String,
        /// 1-based line (0 when the problem is not on one line, e.g. a missing key or file).
        line: usize,
        /// The column or key, e.g. `time_s`, `format_version`, `instrument[1].samples`.
        field: String,
        /// What is wrong.
        reason: String,
    },
}

impl DemoError {
    /// A [`DemoError::Format`].
    pub fn format(
        file: impl Into<String>,
        line: usize,
        field: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        Self::Format { file: file.into(), line, field: field.into(), reason: reason.into() }
    }

    /// The line a format error names (0 for I/O errors or when not on a line).
    pub fn line(&self) -> usize {
        match self {
            DemoError::Format { line, .. } => *line,
            DemoError::Io { .. } => 0,
        }
    }

    /// The field a format error names (empty for I/O errors).
    pub fn field(&self) -> &str {
        match self {
            DemoError::Format { field, .. } => field,
            DemoError::Io { .. } => "",
        }
    }

    /// The file the error names.
    pub fn file(&self) -> &str {
        match self {
            DemoError::Format { file, .. } | DemoError::Io { file, .. } => file,
        }
    }
}
