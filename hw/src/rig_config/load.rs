//! Reading a rig config: TOML syntax, then the schema (unknown keys, wrong types, with the key's path
//! and line), then the checks (every problem, with its key).

use std::path::Path;

use super::schema::RigConfig;

/// Why a rig config was refused.
#[derive(Debug, thiserror::Error)]
pub enum RigConfigError {
    /// The file could not be read.
    #[error("{file}: cannot read: {error}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        error: std::io::Error,
    },
    /// Not TOML, an unknown key, or a value of the wrong type.
    #[error("{file}:{line}: {key}: {reason}")]
    Schema {
        /// The file.
        file: String,
        /// 1-based line (0 when unknown).
        line: usize,
        /// The key's path, e.g. `arms.left.servo.layout`.
        key: String,
        /// What is wrong.
        reason: String,
    },
    /// Values out of range or combinations that cannot work; every one is listed.
    #[error("{file}: {}", problems.iter().map(|(k, r)| format!("{k}: {r}")).collect::<Vec<_>>().join("; "))]
    Invalid {
        /// The file.
        file: String,
        /// (key, reason) for each problem.
        problems: Vec<(String, String)>,
    },
}

/// Parses rig config TOML; `file` names it in errors.
pub fn parse_rig_config(text: &str, file: &str) -> Result<RigConfig, RigConfigError> {
    let config: RigConfig = crate::toml_file::deserialize(text).map_err(|p| RigConfigError::Schema {
        file: file.to_owned(),
        line: p.line,
        key: p.key,
        reason: p.reason,
    })?;
    let problems = config.problems();
    if problems.is_empty() {
        Ok(config)
    } else {
        Err(RigConfigError::Invalid { file: file.to_owned(), problems })
    }
}

/// Reads and parses a rig config file.
pub fn load_rig_config(path: &Path) -> Result<RigConfig, RigConfigError> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|error| RigConfigError::Read { file: file.clone(), error })?;
    parse_rig_config(&text, &file)
}
