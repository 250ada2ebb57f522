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

/// The 1-based line where `text` gives the value at the dotted `key` (a table's keys joined by dots,
/// an array's elements by `[i]` from 0, as the range checks name them: `thread.segments`,
/// `servo.calibration_offset_rad.left[2]`, `obstacles[0].centre_m`), or, where the text gives no
/// value of its own for the whole path (`trocars.left.x`, a point written as an array), the line of
/// the nearest value that holds it. 0 when the text gives none of it.
pub fn key_line(text: &str, key: &str) -> usize {
    let Ok(root) = toml::de::DeTable::parse(text) else {
        return 0;
    };
    let root = toml::de::DeValue::Table(root.into_inner());
    let mut value = &root;
    let mut line = 0;
    for part in key.split('.') {
        let (name, indices) = part.split_once('[').map_or((part, None), |(name, rest)| (name, Some(rest)));
        let Some(found) = value.get(name) else {
            return line;
        };
        (value, line) = (found.get_ref(), line_of(text, found.span().start));
        for index in indices.into_iter().flat_map(|rest| rest.split('[')).map(|i| i.trim_end_matches(']')) {
            let Some(found) = index.parse::<usize>().ok().and_then(|i| value.get(i)) else {
                return line;
            };
            (value, line) = (found.get_ref(), line_of(text, found.span().start));
        }
    }
    line
}

/// Largest TOML text knotlab reads, bytes: its files are a few to a few tens of kilobytes.
pub const MAX_TOML_BYTES: usize = 1 << 20;

/// Deepest nesting of arrays and inline tables in a TOML text: its files nest two or three deep. The
/// toml parser's memory grows steeply with nesting (20,000 levels asked for half a gigabyte).
pub const MAX_TOML_NESTING: usize = 64;

/// Refuses a text longer than [`MAX_TOML_BYTES`] or nesting arrays and inline tables deeper than
/// [`MAX_TOML_NESTING`], before the toml parser sees it. Brackets inside strings and comments do
/// not count.
pub fn check_bounds(text: &str) -> Result<(), TomlProblem> {
    if text.len() > MAX_TOML_BYTES {
        return Err(TomlProblem {
            line: 0,
            key: "(file)".to_owned(),
            reason: format!("{} bytes; a TOML file may have at most {MAX_TOML_BYTES}", text.len()),
        });
    }
    let bytes = text.as_bytes();
    let (mut depth, mut i) = (0usize, 0usize);
    while i < bytes.len() {
        match bytes[i] {
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            quote @ (b'"' | b'\'') => {
                let triple = bytes[i..].starts_with(if quote == b'"' { b"\"\"\"" } else { b"'''" });
                let (open, escapes) = (if triple { 3 } else { 1 }, quote == b'"');
                i += open;
                while i < bytes.len() {
                    if escapes && bytes[i] == b'\\' {
                        i += 2;
                        continue;
                    }
                    if bytes[i] == quote && (!triple || bytes[i..].starts_with(&[quote; 3])) {
                        i += open - 1;
                        break;
                    }
                    if !triple && bytes[i] == b'\n' {
                        break;
                    }
                    i += 1;
                }
            }
            b'[' | b'{' => {
                depth += 1;
                if depth > MAX_TOML_NESTING {
                    return Err(TomlProblem {
                        line: line_of(text, i),
                        key: "(syntax)".to_owned(),
                        reason: format!("arrays or inline tables nested deeper than {MAX_TOML_NESTING}"),
                    });
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    Ok(())
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
    check_bounds(text)?;
    let deserializer = toml::Deserializer::parse(text).map_err(|e| syntax_problem(text, &e))?;
    serde_path_to_error::deserialize(Strict(deserializer)).map_err(|e| {
        let key = e
            .path()
            .to_string()
            .replace(".$__serde_spanned_private_value", "")
            .replace("$__serde_spanned_private_value.", "");
        let inner = e.into_inner();
        TomlProblem {
            // A missing key has no text of its own: its table's line is where it belongs.
            line: inner.span().map_or_else(|| key_line(text, &key), |s| line_of(text, s.start)),
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
    /// Values out of range or combinations that cannot work; every one is listed, at its line.
    #[error("{}", problems.iter().zip(lines).map(|((k, r), line)| format!("{}: {k}: {r}", located(file, *line))).collect::<Vec<_>>().join("; "))]
    Invalid {
        /// The file.
        file: String,
        /// (key, reason) for each problem.
        problems: Vec<(String, String)>,
        /// Each problem's 1-based line ([`key_line`]; 0 when the file gives none of its key).
        lines: Vec<usize>,
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
        let lines = problems.iter().map(|(key, _)| key_line(text, key)).collect();
        Err(TomlFileError::Invalid { file: file.to_owned(), problems, lines })
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

    /// Guards the line a range problem is reported at: a key's own line, an array element's, an
    /// array of tables' entry's key, the nearest line holding a path the text does not spell out,
    /// and 0 for a key the text does not give.
    #[test]
    fn a_problems_key_is_found_at_its_line() {
        let text = "top = 1\n[thread]\nsegments = 80\n\n[servo.calibration_offset_rad]\nleft = [\n  0.0,\n  0.3,\n]\n[trocars]\nleft = [1.0, 2.0, 3.0]\n[[obstacles]]\ncentre_m = [0.0, 0.0, 0.0]\n[[obstacles]]\ncentre_m = [1.0, 0.0, 0.0]\nhalf = { x = 1.0,\n  y = 2.0 }\n";
        for (key, line) in [
            ("top", 1),
            ("thread.segments", 3),
            ("thread", 2),
            ("servo.calibration_offset_rad.left", 6),
            ("servo.calibration_offset_rad.left[1]", 8),
            ("trocars.left.x", 11),
            ("obstacles[1].centre_m", 15),
            ("obstacles[1].half.y", 17),
            ("obstacles[2].centre_m", 12),
            ("thread.radius_m", 2),
            ("nowhere", 0),
        ] {
            assert_eq!(key_line(text, key), line, "{key}");
        }
        assert_eq!(key_line("not = = toml", "not"), 0);
    }

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

    #[derive(Debug, serde::Deserialize)]
    #[serde(deny_unknown_fields)]
    #[allow(dead_code)]
    struct Listed {
        inner: Inner,
        #[serde(default)]
        items: Vec<Inner>,
    }

    /// A missing key, which has no text of its own, is reported at the line of the table it is
    /// missing from: a table's header, an array of tables' entry; the top level at the first line.
    #[test]
    fn a_missing_key_is_found_at_its_tables_line() {
        let p = deserialize::<Outer>(
            "# a comment

[inner]
",
        )
        .unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (3, "inner"), "{p}");
        let text = "[inner]
count = 1
[[items]]
count = 2

[[items]]
# none
";
        let p = deserialize::<Listed>(text).unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (6, "items[1]"), "{p}");
        let p = deserialize::<Outer>(
            "# nothing
",
        )
        .unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (1, "(top level)"), "{p}");
    }

    /// A text nesting arrays deeper than the bound is refused at the line it passes it, before the
    /// toml parser (whose memory grows steeply with nesting) sees it; brackets in strings and comments
    /// do not count; a text past the size bound is refused.
    #[test]
    fn deep_nesting_and_huge_texts_are_refused_before_parsing() {
        let deep =
            format!("a = 1\nb = {}{}\n", "[".repeat(MAX_TOML_NESTING + 1), "]".repeat(MAX_TOML_NESTING + 1));
        let p = check_bounds(&deep).unwrap_err();
        assert_eq!((p.line, p.key.as_str()), (2, "(syntax)"), "{p}");
        let fine = format!("{}{}", "[".repeat(MAX_TOML_NESTING), "]".repeat(MAX_TOML_NESTING));
        assert!(check_bounds(&format!("b = {fine}\n")).is_ok());
        let quoted = format!(
            "s = \"{}\"\nt = '{}'\nu = \"\"\"{}\"\"\"\n# {}\n",
            "[".repeat(100),
            "{".repeat(100),
            "[".repeat(100),
            "[".repeat(100)
        );
        assert!(check_bounds(&quoted).is_ok(), "{:?}", check_bounds(&quoted));
        let huge = "# padding\n".repeat(MAX_TOML_BYTES / 10 + 1);
        assert_eq!(check_bounds(&huge).unwrap_err().key, "(file)");
    }
}
