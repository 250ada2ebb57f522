//! `demo.toml`, a demonstration's metadata: format and version, source, scene, seed, sample rate, units,
//! the stitch frame and the instrument files. Parsed in two passes: the format version first (a file of
//! another version is refused for that, not for a field it may have renamed), then the schema (unknown
//! keys, wrong types), then the values; every error names the line and the key.

use serde::Deserialize;
use toml::Spanned;

use knotlab_hw::rig::ArmName;
use knotlab_hw::toml_file::{line_of, syntax_problem};

use super::error::DemoError;
use super::{Demonstration, FORMAT_VERSION, MIN_SAMPLE_RATE_HZ, Metadata, StitchPose};

/// The metadata file's name inside a demonstration directory.
pub const METADATA_FILE: &str = "demo.toml";

/// The value of the `format` key.
pub const FORMAT_NAME: &str = "knotlab-demonstration";

/// The `[units]` table of format version 1: (key, the only value allowed).
pub const UNITS: [(&str, &str); 6] = [
    ("time", "s"),
    ("position", "m"),
    ("angle", "rad"),
    ("force", "N"),
    ("orientation", "quaternion_xyzw"),
    ("frame", "world"),
];

/// Most samples one instrument's file may hold (an hour at 2.5 kHz).
pub const MAX_SAMPLES: usize = 10_000_000;

/// An instrument entry of the metadata: which CSV file holds it and how many samples it has.
#[derive(Clone, Debug, PartialEq)]
pub struct InstrumentEntry {
    /// The instrument.
    pub instrument: ArmName,
    /// The CSV file's name inside the directory.
    pub file: String,
    /// How many samples (data rows) the file must hold.
    pub samples: usize,
}

/// The parsed metadata file.
#[derive(Clone, Debug, PartialEq)]
pub struct MetadataFile {
    /// The metadata.
    pub metadata: Metadata,
    /// The instruments in file order.
    pub instruments: Vec<InstrumentEntry>,
}

#[derive(Deserialize)]
struct VersionProbe {
    format: Option<Spanned<String>>,
    format_version: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Raw {
    #[serde(rename = "format")]
    _format: String,
    #[serde(rename = "format_version")]
    _format_version: i64,
    source: String,
    #[serde(default)]
    scene: String,
    seed: Option<Spanned<toml::Value>>,
    sample_rate_hz: Spanned<f64>,
    #[serde(default)]
    description: String,
    units: Spanned<toml::Table>,
    stitch: RawStitch,
    instrument: Vec<RawInstrument>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStitch {
    position_m: Spanned<[f64; 3]>,
    quaternion_xyzw: Spanned<[f64; 4]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInstrument {
    name: Spanned<String>,
    file: Spanned<String>,
    samples: Spanned<i64>,
}

/// Parses `demo.toml`; `file` names it in errors.
pub fn parse_metadata(text: &str, file: &str) -> Result<MetadataFile, DemoError> {
    let err = |line: usize, field: &str, reason: String| DemoError::format(file, line, field, reason);
    let line = |span: std::ops::Range<usize>| line_of(text, span.start);
    let syntax = |e: toml::de::Error| {
        let p = syntax_problem(text, &e);
        err(p.line, &p.key, p.reason)
    };

    // 1. Format and version, before anything else.
    knotlab_hw::toml_file::check_bounds(text).map_err(|p| err(p.line, &p.key, p.reason))?;
    let probe: VersionProbe = toml::from_str(text).map_err(syntax)?;
    let Some(format) = probe.format else {
        return Err(err(
            0,
            "format",
            format!("missing (a demonstration's demo.toml says format = \"{FORMAT_NAME}\")"),
        ));
    };
    if format.get_ref() != FORMAT_NAME {
        return Err(err(
            line(format.span()),
            "format",
            format!("'{}' is not a demonstration (expected '{FORMAT_NAME}')", format.get_ref()),
        ));
    }
    let Some(version) = probe.format_version else {
        return Err(err(0, "format_version", "missing".to_owned()));
    };
    if *version.get_ref() != i64::from(FORMAT_VERSION) {
        return Err(err(
            line(version.span()),
            "format_version",
            format!(
                "version {} is not supported (this knotlab reads version {FORMAT_VERSION})",
                version.get_ref()
            ),
        ));
    }

    // 2. The schema.
    let raw: Raw = knotlab_hw::toml_file::deserialize(text).map_err(|p| err(p.line, &p.key, p.reason))?;

    // 3. The values.
    let units_line = line(raw.units.span());
    for (key, unit) in UNITS {
        match raw.units.get_ref().get(key) {
            Some(toml::Value::String(s)) if s == unit => {}
            Some(other) => {
                return Err(err(
                    units_line,
                    &format!("units.{key}"),
                    format!("{other} is not supported: format version {FORMAT_VERSION} uses \"{unit}\""),
                ));
            }
            None => {
                return Err(err(
                    units_line,
                    &format!("units.{key}"),
                    format!("missing (must be \"{unit}\")"),
                ));
            }
        }
    }
    if let Some(extra) = raw.units.get_ref().keys().find(|k| !UNITS.iter().any(|(u, _)| u == k)) {
        return Err(err(units_line, &format!("units.{extra}"), "unknown unit key".to_owned()));
    }
    let seed = match raw.seed {
        Some(s) => Some(parse_seed(s.get_ref()).ok_or_else(|| {
            err(
                line(s.span()),
                "seed",
                format!(
                    "must be an integer from 0 to 2^64 - 1 (above 2^63 - 1 written as a quoted string of digits), got {}",
                    s.get_ref()
                ),
            )
        })?),
        None => None,
    };
    let metadata = Metadata {
        format_version: FORMAT_VERSION,
        source: raw.source,
        scene: raw.scene,
        seed,
        sample_rate_hz: *raw.sample_rate_hz.get_ref(),
        stitch: StitchPose {
            position_m: *raw.stitch.position_m.get_ref(),
            quaternion_xyzw: *raw.stitch.quaternion_xyzw.get_ref(),
        },
        description: raw.description,
    };
    let key_line = |key: &str| match key {
        "sample_rate_hz" => line(raw.sample_rate_hz.span()),
        "stitch.position_m" => line(raw.stitch.position_m.span()),
        "stitch.quaternion_xyzw" => line(raw.stitch.quaternion_xyzw.span()),
        _ => 0,
    };
    check_metadata_values(&metadata).map_err(|(key, reason)| err(key_line(key), key, reason))?;

    if raw.instrument.is_empty() {
        return Err(err(0, "instrument", "no [[instrument]] entries".to_owned()));
    }
    let mut instruments: Vec<InstrumentEntry> = Vec::new();
    for (k, entry) in raw.instrument.iter().enumerate() {
        let field = |name: &str| format!("instrument[{k}].{name}");
        let name_line = line(entry.name.span());
        let instrument: ArmName =
            entry.name.get_ref().parse().map_err(|e| err(name_line, &field("name"), format!("{e}")))?;
        if !instrument.carries_instrument() {
            return Err(err(
                name_line,
                &field("name"),
                "'camera' is the endoscope, not an instrument".to_owned(),
            ));
        }
        if instruments.iter().any(|i| i.instrument == instrument) {
            return Err(err(name_line, &field("name"), format!("'{instrument}' appears twice")));
        }
        let file_name = entry.file.get_ref();
        if file_name.is_empty() || file_name.contains(['/', '\\']) || file_name.starts_with('.') {
            return Err(err(
                line(entry.file.span()),
                &field("file"),
                format!("'{file_name}' must be a plain file name inside the demonstration's directory"),
            ));
        }
        let samples = *entry.samples.get_ref();
        if !(2..=MAX_SAMPLES as i64).contains(&samples) {
            return Err(err(
                line(entry.samples.span()),
                &field("samples"),
                format!("{samples}: a demonstration has 2 to {MAX_SAMPLES} samples per instrument"),
            ));
        }
        instruments.push(InstrumentEntry { instrument, file: file_name.clone(), samples: samples as usize });
    }
    Ok(MetadataFile { metadata, instruments })
}

/// The range checks on metadata values: `(key, reason)` of the first bad one.
fn check_metadata_values(m: &Metadata) -> Result<(), (&'static str, String)> {
    if m.format_version != FORMAT_VERSION {
        return Err((
            "format_version",
            format!(
                "version {} is not supported (this knotlab writes version {FORMAT_VERSION})",
                m.format_version
            ),
        ));
    }
    if !(m.sample_rate_hz.is_finite() && m.sample_rate_hz >= MIN_SAMPLE_RATE_HZ) {
        return Err((
            "sample_rate_hz",
            format!("must be at least {MIN_SAMPLE_RATE_HZ} Hz, got {}", m.sample_rate_hz),
        ));
    }
    if !m.stitch.position_m.iter().all(|x| x.is_finite()) {
        return Err(("stitch.position_m", format!("not finite: {:?}", m.stitch.position_m)));
    }
    let q = m.stitch.quaternion_xyzw;
    let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if !(norm.is_finite() && (norm - 1.0).abs() <= 1e-6) {
        return Err(("stitch.quaternion_xyzw", format!("not a unit quaternion (norm {norm})")));
    }
    Ok(())
}

/// Checks metadata in memory (before writing); `file` names it in errors.
pub fn validate_metadata(m: &Metadata, file: &str) -> Result<(), DemoError> {
    check_metadata_values(m).map_err(|(key, reason)| DemoError::format(file, 0, key, reason))
}

/// A seed as `demo.toml` holds it: a non-negative integer, or (above TOML's 2^63 - 1) a string
/// of decimal digits.
fn parse_seed(value: &toml::Value) -> Option<u64> {
    match value {
        toml::Value::Integer(i) => u64::try_from(*i).ok(),
        toml::Value::String(s) if !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit()) => s.parse().ok(),
        _ => None,
    }
}

/// A TOML float that reads back to the same bits.
fn float(x: f64) -> String {
    format!("{x:?}")
}

/// A TOML string, quoted and escaped.
fn string(s: &str) -> String {
    toml::Value::String(s.to_owned()).to_string()
}

/// The text of `demo.toml` for a demonstration, with comments saying what each key is.
pub fn render_metadata(demo: &Demonstration) -> String {
    let m = &demo.metadata;
    let mut out = String::new();
    out.push_str("# A knotlab demonstration: this file and one CSV file per instrument (see FORMAT.md).\n");
    out.push_str(&format!("format = {}\n", string(FORMAT_NAME)));
    out.push_str(&format!("format_version = {}\n", m.format_version));
    out.push_str("# Who performed it, in which scene file.\n");
    out.push_str(&format!("source = {}\n", string(&m.source)));
    out.push_str(&format!("scene = {}\n", string(&m.scene)));
    if let Some(seed) = m.seed {
        out.push_str("# The seed of the recording's random draws.\n");
        // TOML's integers stop at 2^63 - 1; a seed above it is written as a string of digits.
        match i64::try_from(seed) {
            Ok(_) => out.push_str(&format!("seed = {seed}\n")),
            Err(_) => out.push_str(&format!("seed = \"{seed}\"\n")),
        }
    }
    out.push_str(&format!("sample_rate_hz = {}\n", float(m.sample_rate_hz)));
    if !m.description.is_empty() {
        out.push_str(&format!("description = {}\n", string(&m.description)));
    }
    out.push_str("\n# Fixed by the format version.\n[units]\n");
    for (key, unit) in UNITS {
        out.push_str(&format!("{key} = {}\n", string(unit)));
    }
    let s = &m.stitch;
    out.push_str("\n# world_from_stitch: x along the wound, y across it towards the tail's flap, z out of the tissue.\n");
    out.push_str("[stitch]\n");
    out.push_str(&format!(
        "position_m = [{}, {}, {}]\n",
        float(s.position_m[0]),
        float(s.position_m[1]),
        float(s.position_m[2])
    ));
    let q = s.quaternion_xyzw;
    out.push_str(&format!(
        "quaternion_xyzw = [{}, {}, {}, {}]\n",
        float(q[0]),
        float(q[1]),
        float(q[2]),
        float(q[3])
    ));
    for record in &demo.instruments {
        out.push_str("\n[[instrument]]\n");
        out.push_str(&format!("name = {}\n", string(record.instrument.as_str())));
        out.push_str(&format!("file = {}\n", string(&record.file_name())));
        out.push_str(&format!("samples = {}\n", record.samples.len()));
    }
    out
}
