//! Reading TOML files into typed values with errors that name the line and the key's path, the way
//! every file knotlab reads (scenes, rig configs, task patterns, demonstration metadata) reports them.

use serde::de::DeserializeOwned;

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

/// A TOML syntax error as a problem.
pub fn syntax_problem(text: &str, error: &toml::de::Error) -> TomlProblem {
    TomlProblem {
        line: error.span().map_or(0, |s| line_of(text, s.start)),
        key: "(syntax)".to_owned(),
        reason: error.message().to_owned(),
    }
}

/// Parses `text` into `T`: syntax first, then the schema (unknown keys, wrong types, missing keys),
/// naming the key's path and its line. Paths through `toml::Spanned` values read as the plain key.
pub fn deserialize<T: DeserializeOwned>(text: &str) -> Result<T, TomlProblem> {
    let deserializer = toml::Deserializer::parse(text).map_err(|e| syntax_problem(text, &e))?;
    serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let key = e
            .path()
            .to_string()
            .replace(".$__serde_spanned_private_value", "")
            .replace("$__serde_spanned_private_value.", "");
        let inner = e.into_inner();
        TomlProblem {
            line: inner.span().map_or(0, |s| line_of(text, s.start)),
            key: if key == "." { "(top level)".to_owned() } else { key },
            reason: inner.message().to_owned(),
        }
    })
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
