//! Reading a scene file: TOML syntax, then the schema (unknown keys, wrong types, with the key's path),
//! then the ranges (every value out of range, with its key).

use std::path::Path;

use super::config::SceneConfig;

/// Why a scene file was refused.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{file}: cannot read: {error}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        error: std::io::Error,
    },
    /// Not valid TOML, or a key that does not belong, or a value of the wrong type.
    #[error("{file}:{line}: {key}: {reason}")]
    Schema {
        /// The file.
        file: String,
        /// 1-based line of the offending text (0 when unknown).
        line: usize,
        /// The key's path, e.g. `thread.segments`.
        key: String,
        /// What is wrong.
        reason: String,
    },
    /// Values out of range; every one is listed.
    #[error("{file}: {}", problems.iter().map(|(k, r)| format!("{k}: {r}")).collect::<Vec<_>>().join("; "))]
    Range {
        /// The file.
        file: String,
        /// (key, reason) for every value out of range.
        problems: Vec<(String, String)>,
    },
}

/// Parses scene TOML; `file` names it in errors.
pub fn parse_scene(text: &str, file: &str) -> Result<SceneConfig, SceneError> {
    let config: SceneConfig = knotlab_hw::toml_file::deserialize(text).map_err(|p| SceneError::Schema {
        file: file.to_owned(),
        line: p.line,
        key: p.key,
        reason: p.reason,
    })?;
    let problems = config.range_problems();
    if problems.is_empty() { Ok(config) } else { Err(SceneError::Range { file: file.to_owned(), problems }) }
}

/// Reads and parses a scene file.
pub fn load_scene(path: &Path) -> Result<SceneConfig, SceneError> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|error| SceneError::Read { file: file.clone(), error })?;
    parse_scene(&text, &file)
}
