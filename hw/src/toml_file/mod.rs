//! Reading TOML files into typed values with errors that name the line and the key's path, the way
//! every file knotlab reads (scenes, rig configs, task patterns, demonstration metadata, the expert's
//! geometry) reports them; [`parse_checked`] and [`load_checked`] add the range checks and the file's name.

mod strict;

use serde::de::DeserializeOwned;

use strict::Strict;

/// One thing wrong with a TOML text: where and why.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{line}: {key}: {reason}")]
pub struct TomlProblem {
    /// 1-based line of the offending text (0 when unknown).
    pub line: usize,
    /// The key's path (`thread.segments`), `(syntax)` for malformed TOML, `(top level)` for the root.
    pub key: String,
    /// What is wrong.
    pub reason: String,
}

/// The 1-based line holding byte `offset` of `text`.
pub fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The 1-based line of the header `[key]` of a table, 0 when it has none (the top level, an inline
/// table).
fn table_line(text: &str, key: &str) -> usize {
    text.lines()
        .position(|l| {
            let l = l.split('#').next().unwrap_or("").trim();
            l.strip_prefix('[')
                .and_then(|l| l.strip_suffix(']'))
                .is_some_and(|inner| inner.split('.').map(str::trim).eq(key.split('.')))
        })
        .map_or(0, |k| k + 1)
}

/// `file:line`, or `file` alone when the line is not known (0).
pub fn located(file: &str, line: usize) -> String {
    if line == 0 { file.to_owned() } else { format!("{file}:{line}") }
}

/// A TOML syntax error as a problem.
pub fn syntax_problem(text: &str, error: &toml::de::Error) -> TomlProblem {
    TomlProblem {
        line: error.span().map_or(0, |s| line_of(text, s.start)),
        key: "(syntax)".to_owned(),
        reason: error.message().to_owned(),
    }
}

/// Parses `text` into `T`: syntax first, then the schema (unknown keys, wrong types, missing keys),
/// naming the key's path and its line. Paths through `toml::Spanned` values read as the plain key. A
/// fixed-length array (`[f64; 3]`) must hold exactly its length, not merely at least it (`strict::Strict`).
pub fn deserialize<T: DeserializeOwned>(text: &str) -> Result<T, TomlProblem> {
    let deserializer = toml::Deserializer::parse(text).map_err(|e| syntax_problem(text, &e))?;
    serde_path_to_error::deserialize(Strict(deserializer)).map_err(|e| {
        let key = e
            .path()
            .to_string()
            .replace(".$__serde_spanned_private_value", "")
            .replace("$__serde_spanned_private_value.", "");
        let inner = e.into_inner();
        TomlProblem {
            // A missing key has no text of its own: its table's header is where it belongs.
            line: inner.span().map_or_else(|| table_line(text, &key), |s| line_of(text, s.start)),
            key: if key == "." { "(top level)".to_owned() } else { key },
            reason: inner.message().to_owned(),
        }
    })
}

/// Why a checked TOML file (a scene, a rig config, the expert's geometry) was refused: it could not
/// be read, its text does not fit the schema, or values are out of range. Each names the file.
#[derive(Debug, thiserror::Error)]
pub enum TomlFileError {
    /// The file could not be read.
    #[error("{file}: cannot read: {error}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        error: std::io::Error,
    },
    /// Not valid TOML, a key that does not belong, or a value of the wrong type.
    #[error("{}: {key}: {reason}", located(file, *line))]
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
    /// Values out of range or combinations that cannot work; every one is listed.
    #[error("{file}: {}", problems.iter().map(|(k, r)| format!("{k}: {r}")).collect::<Vec<_>>().join("; "))]
    Invalid {
        /// The file.
        file: String,
        /// (key, reason) for each problem.
        problems: Vec<(String, String)>,
    },
}

/// Parses `text` into `T` ([`deserialize`]), then lists what `problems` finds wrong with it; `file`
/// names it in errors.
pub fn parse_checked<T: DeserializeOwned>(
    text: &str,
    file: &str,
    problems: impl FnOnce(&T) -> Vec<(String, String)>,
) -> Result<T, TomlFileError> {
    let value: T = deserialize(text).map_err(|p| TomlFileError::Schema {
        file: file.to_owned(),
        line: p.line,
        key: p.key,
        reason: p.reason,
    })?;
    let problems = problems(&value);
    if problems.is_empty() {
        Ok(value)
    } else {
        Err(TomlFileError::Invalid { file: file.to_owned(), problems })
    }
}

/// Reads `path` and [`parse_checked`]s it.
pub fn load_checked<T: DeserializeOwned>(
    path: &std::path::Path,
    problems: impl FnOnce(&T) -> Vec<(String, String)>,
) -> Result<T, TomlFileError> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|error| TomlFileError::Read { file: file.clone(), error })?;
    parse_checked(&text, &file, problems)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Outer {
        inner: Inner,
    }

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Inner {
        count: usize,
    }

    /// A wrong type, a misspelt key and broken syntax are each reported at their line and key path.
    #[test]
    fn problems_name_line_and_key() {
        let p = deserialize::<Outer>("[inner]\ncount = \"two\"\n").unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (2, "inner.count"), "{p}");
        let p = deserialize::<Outer>("[inner]\ncount = 2\ncuont = 3\n").unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (3, "inner.cuont"), "{p}");
        let p = deserialize::<Outer>("[inner\n").unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (1, "(syntax)"), "{p}");
        assert_eq!(deserialize::<Outer>("[inner]\ncount = 2\n").unwrap().inner.count, 2);
    }
}
