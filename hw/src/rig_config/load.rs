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

fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// Parses rig config TOML; `file` names it in errors.
pub fn parse_rig_config(text: &str, file: &str) -> Result<RigConfig, RigConfigError> {
    let schema = |line: usize, key: String, reason: String| RigConfigError::Schema {
        file: file.to_owned(),
        line,
        key,
        reason,
    };
    let deserializer = toml::Deserializer::parse(text).map_err(|e| {
        let line = e.span().map_or(0, |s| line_of(text, s.start));
        schema(line, "(syntax)".to_owned(), e.message().to_owned())
    })?;
    let config: RigConfig = serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let key = e.path().to_string();
        let inner = e.into_inner();
        let line = inner.span().map_or(0, |s| line_of(text, s.start));
        schema(line, if key == "." { "(top level)".to_owned() } else { key }, inner.message().to_owned())
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
