//! The knowledge base file: pretty-printed JSON, versioned. Reading checks the format and its version
//! first, then the schema; errors name the file, the line and the field.

use std::path::Path;

use thiserror::Error;

use super::KnowledgeBase;

/// The value of a knowledge base's `format` field.
pub const KB_FORMAT: &str = "knotlab-knowledge-base";

/// The knowledge base format version this knotlab writes. Version 2 added the instruments' `jaw` and
/// the `dependencies`, version 3 the path keys' whole frame (`quaternion_xyzw`).
pub const KB_FORMAT_VERSION: u32 = 3;

/// The versions this knotlab reads (a version 1 file has no jaw points and no dependencies; the path
/// keys of versions 1 and 2 have no frame, and skills made from them orient the jaws by direction).
pub const KB_READABLE_VERSIONS: [u32; 3] = [1, 2, 3];

/// Why a knowledge base could not be written or read.
#[derive(Debug, Error)]
pub enum KnowledgeError {
    /// The file could not be read or written.
    #[error("{file}: {action}: {error}")]
    Io {
        /// The file.
        file: String,
        /// `cannot read` or `cannot write`.
        action: &'static str,
        /// The error.
        error: std::io::Error,
    },
    /// The file is malformed.
    #[error("{file}:{line}: {field}: {reason}")]
    Invalid {
        /// The file.
        file: String,
        /// 1-based line.
        line: usize,
        /// The field's path.
        field: String,
        /// What is wrong.
        reason: String,
    },
    /// The file fits the schema but its values do not make a skill; every problem is listed.
    #[error("{file}: {}", problems.iter().map(|(k, r)| format!("{k}: {r}")).collect::<Vec<_>>().join("; "))]
    Inconsistent {
        /// The file.
        file: String,
        /// (field path, reason) for each problem.
        problems: Vec<(String, String)>,
    },
}

/// Writes `kb` as pretty-printed JSON.
pub fn write_knowledge_base(path: &Path, kb: &KnowledgeBase) -> Result<(), KnowledgeError> {
    let file = path.display().to_string();
    let text = serde_json::to_string_pretty(kb).map_err(|e| KnowledgeError::Inconsistent {
        file: file.clone(),
        problems: vec![("(all)".to_owned(), e.to_string())],
    })?;
    std::fs::write(path, text + "\n").map_err(|error| KnowledgeError::Io {
        file,
        action: "cannot write",
        error,
    })
}

/// Parses knowledge base JSON; `file` names it in errors.
pub fn parse_knowledge_base(text: &str, file: &str) -> Result<KnowledgeBase, KnowledgeError> {
    let invalid = |line: usize, field: &str, reason: String| KnowledgeError::Invalid {
        file: file.to_owned(),
        line,
        field: field.to_owned(),
        reason,
    };
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| invalid(e.line(), "(syntax)", e.to_string()))?;
    let line_of = |key: &str| {
        let needle = format!("\"{key}\"");
        text.find(&needle).map_or(1, |at| knotlab_hw::toml_file::line_of(text, at))
    };
    let shown = |v: Option<&serde_json::Value>| v.map_or("missing".to_owned(), |v| v.to_string());
    match value.get("format").and_then(|f| f.as_str()) {
        Some(KB_FORMAT) => {}
        _ => {
            return Err(invalid(
                line_of("format"),
                "format",
                match value.get("format") {
                    None => format!("missing (a knowledge base has format = \"{KB_FORMAT}\")"),
                    Some(f) => format!("{f} is not a knowledge base (expected \"{KB_FORMAT}\")"),
                },
            ));
        }
    }
    match value.get("format_version").and_then(serde_json::Value::as_u64) {
        Some(v) if KB_READABLE_VERSIONS.iter().any(|r| u64::from(*r) == v) => {}
        _ => {
            return Err(invalid(
                line_of("format_version"),
                "format_version",
                format!(
                    "{} is not supported (this knotlab reads versions {})",
                    shown(value.get("format_version")),
                    KB_READABLE_VERSIONS.map(|v| v.to_string()).join(", ")
                ),
            ));
        }
    }
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let kb: KnowledgeBase = serde_path_to_error::deserialize(&mut deserializer).map_err(|e| {
        let mut field = e.path().to_string();
        let inner = e.into_inner();
        // A primitive is tagged by its type, which hides the field inside it: find it again.
        if let Some(inside) = field_inside_primitive(&value, &field) {
            field = format!("{field}.{inside}");
        }
        invalid(inner.line(), &field, inner.to_string())
    })?;
    let problems = super::check::problems(&kb);
    if !problems.is_empty() {
        return Err(KnowledgeError::Inconsistent { file: file.to_owned(), problems });
    }
    Ok(kb)
}

/// For an error at `instruments[i].primitives[j]`, the path of the offending field inside that
/// primitive (deserialized again as the struct its `type` names).
fn field_inside_primitive(value: &serde_json::Value, path: &str) -> Option<String> {
    let rest = path.strip_prefix("instruments[")?;
    let (i, rest) = rest.split_once("].primitives[")?;
    let j = rest.strip_suffix(']')?;
    let primitive = value
        .get("instruments")?
        .get(i.parse::<usize>().ok()?)?
        .get("primitives")?
        .get(j.parse::<usize>().ok()?)?;
    let mut fields = primitive.as_object()?.clone();
    let kind = fields.remove("type")?;
    let fields = serde_json::Value::Object(fields);
    fn inner<T: serde::de::DeserializeOwned>(v: serde_json::Value) -> Option<String> {
        serde_path_to_error::deserialize::<_, T>(v).err().map(|e| e.path().to_string())
    }
    match kind.as_str()? {
        "2d" => inner::<super::TwoDPrimitive>(fields),
        "linear" => inner::<super::LinearPrimitive>(fields),
        "force" => inner::<super::ForcePrimitive>(fields),
        "synchronized" => inner::<super::SynchronizedPrimitive>(fields),
        _ => Some("type".to_owned()),
    }
}

/// Reads a knowledge base file.
pub fn load_knowledge_base(path: &Path) -> Result<KnowledgeBase, KnowledgeError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|error| KnowledgeError::Io {
        file: file.clone(),
        action: "cannot read",
        error,
    })?;
    parse_knowledge_base(&text, &file)
}
