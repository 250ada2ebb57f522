//! Reading a task pattern file (TOML): the format and its version first, then the schema (unknown keys
//! and wrong types, with the key's path), then the meaning (known feature kinds, unique ids, references
//! that exist, spans in order, no circular `after`). Every error names the file, the line and the field.

use std::collections::{HashMap, HashSet};
use std::ops::Range;
use std::path::Path;

use serde::Deserialize;
use thiserror::Error;
use toml::Spanned;

use knotlab_hw::rig::ArmName;
use knotlab_hw::toml_file::line_of;

use super::{Element, InstrumentPattern, PrimitiveSpec, PrimitiveType, TaskPattern};
use crate::demonstration::GraspState;
use crate::features::{DetectorParams, FeatureKind};

/// The value of a pattern file's `format` key.
pub const PATTERN_FORMAT: &str = "knotlab-task-pattern";

/// The pattern format version this knotlab reads.
pub const PATTERN_FORMAT_VERSION: i64 = 1;

/// Why a pattern file was refused.
#[derive(Debug, Error)]
pub enum PatternError {
    /// The file could not be read.
    #[error("{file}: cannot read: {error}")]
    Read {
        /// The file.
        file: String,
        /// The I/O error.
        error: std::io::Error,
    },
    /// The file is malformed.
    #[error("{}: {field}: {reason}", knotlab_hw::toml_file::located(file, *line))]
    Invalid {
        /// The file.
        file: String,
        /// 1-based line (0 when not on one line).
        line: usize,
        /// The key, e.g. `left.feature[2].kind`.
        field: String,
        /// What is wrong.
        reason: String,
    },
}

impl PatternError {
    /// The line an error names (0 for read errors).
    pub fn line(&self) -> usize {
        match self {
            PatternError::Invalid { line, .. } => *line,
            PatternError::Read { .. } => 0,
        }
    }

    /// The field an error names (empty for read errors).
    pub fn field(&self) -> &str {
        match self {
            PatternError::Invalid { field, .. } => field,
            PatternError::Read { .. } => "",
        }
    }
}

#[derive(Deserialize)]
struct VersionProbe {
    format: Option<Spanned<String>>,
    format_version: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPattern {
    #[serde(rename = "format")]
    _format: String,
    #[serde(rename = "format_version")]
    _format_version: i64,
    name: Spanned<String>,
    #[serde(default)]
    description: String,
    #[serde(default)]
    order_slack_s: Option<Spanned<f64>>,
    #[serde(default)]
    detector: Option<Spanned<DetectorParams>>,
    left: Option<RawInstrument>,
    right: Option<RawInstrument>,
    assist: Option<RawInstrument>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInstrument {
    #[serde(default)]
    feature: Vec<Spanned<RawElement>>,
    #[serde(default)]
    primitive: Vec<Spanned<RawPrimitive>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawElement {
    id: Spanned<String>,
    kind: Spanned<String>,
    #[serde(default)]
    description: String,
    min_magnitude: Option<Spanned<f64>>,
    max_magnitude: Option<Spanned<f64>>,
    slack_s: Option<Spanned<f64>>,
    #[serde(default)]
    after: Option<Spanned<Vec<String>>>,
    grasp: Option<Spanned<String>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPrimitive {
    name: Spanned<String>,
    #[serde(rename = "type")]
    kind: Spanned<String>,
    from: Option<Spanned<String>>,
    to: Option<Spanned<String>>,
    reference: Option<Spanned<String>>,
    #[serde(default)]
    description: String,
}

/// Reads and parses a pattern file.
pub fn load_pattern(path: &Path) -> Result<TaskPattern, PatternError> {
    let file = path.display().to_string();
    let text =
        std::fs::read_to_string(path).map_err(|error| PatternError::Read { file: file.clone(), error })?;
    parse_pattern(&text, &file)
}

/// Parses pattern TOML; `file` names it in errors.
pub fn parse_pattern(text: &str, file: &str) -> Result<TaskPattern, PatternError> {
    let err = |line: usize, field: &str, reason: String| PatternError::Invalid {
        file: file.to_owned(),
        line,
        field: field.to_owned(),
        reason,
    };
    let line = |span: Range<usize>| line_of(text, span.start);
    let syntax = |e: toml::de::Error| err(e.span().map_or(0, &line), "(syntax)", e.message().to_owned());

    knotlab_hw::toml_file::check_bounds(text).map_err(|p| err(p.line, &p.key, p.reason))?;
    let probe: VersionProbe = toml::from_str(text).map_err(syntax)?;
    let Some(format) = probe.format else {
        return Err(err(0, "format", format!("missing (a task pattern says format = \"{PATTERN_FORMAT}\")")));
    };
    if format.get_ref() != PATTERN_FORMAT {
        return Err(err(
            line(format.span()),
            "format",
            format!("'{}' is not a task pattern (expected '{PATTERN_FORMAT}')", format.get_ref()),
        ));
    }
    let Some(version) = probe.format_version else {
        return Err(err(0, "format_version", "missing".to_owned()));
    };
    if *version.get_ref() != PATTERN_FORMAT_VERSION {
        return Err(err(
            line(version.span()),
            "format_version",
            format!(
                "version {} is not supported (this knotlab reads version {PATTERN_FORMAT_VERSION})",
                version.get_ref()
            ),
        ));
    }

    let raw: RawPattern =
        knotlab_hw::toml_file::deserialize(text).map_err(|p| err(p.line, &p.key, p.reason))?;

    if raw.name.get_ref().trim().is_empty() {
        return Err(err(line(raw.name.span()), "name", "must not be empty".to_owned()));
    }
    let default_slack = match &raw.order_slack_s {
        Some(s) => non_negative(*s.get_ref()).map_err(|r| err(line(s.span()), "order_slack_s", r))?,
        None => 0.0,
    };
    let detector = match &raw.detector {
        Some(d) => {
            d.get_ref()
                .check()
                .map_err(|(field, reason)| err(line(d.span()), &format!("detector.{field}"), reason))?;
            *d.get_ref()
        }
        None => DetectorParams::default(),
    };

    let mut instruments = Vec::new();
    let mut ids: HashMap<String, (ArmName, usize)> = HashMap::new();
    let mut names: HashSet<String> = HashSet::new();
    // Pass 1: elements (ids must be known before references are checked).
    let present: Vec<(ArmName, &RawInstrument)> =
        [(ArmName::Left, &raw.left), (ArmName::Right, &raw.right), (ArmName::Assist, &raw.assist)]
            .into_iter()
            .filter_map(|(a, r)| r.as_ref().map(|r| (a, r)))
            .collect();
    if present.is_empty() {
        return Err(err(
            0,
            "(top level)",
            "no instrument: expected [[left.feature]], [[right.feature]] or [[assist.feature]]".to_owned(),
        ));
    }
    for (arm, ri) in &present {
        if ri.feature.is_empty() {
            return Err(err(
                0,
                &format!("{arm}.feature"),
                "an instrument needs at least one feature".to_owned(),
            ));
        }
        let mut elements = Vec::new();
        for (k, re) in ri.feature.iter().enumerate() {
            let field = |name: &str| format!("{arm}.feature[{k}].{name}");
            let e = re.get_ref();
            let id = e.id.get_ref().clone();
            check_name(&id).map_err(|r| err(line(e.id.span()), &field("id"), r))?;
            if let Some((other, _)) = ids.get(&id) {
                return Err(err(
                    line(e.id.span()),
                    &field("id"),
                    format!("'{id}' is already an id of {other}"),
                ));
            }
            ids.insert(id.clone(), (*arm, k));
            let kind = FeatureKind::parse(e.kind.get_ref()).ok_or_else(|| {
                let known: Vec<&str> = FeatureKind::ALL.iter().map(|k| k.as_str()).collect();
                err(
                    line(e.kind.span()),
                    &field("kind"),
                    format!(
                        "unknown feature kind '{}' (expected one of {})",
                        e.kind.get_ref(),
                        known.join(", ")
                    ),
                )
            })?;
            let bound = |b: &Option<Spanned<f64>>, name: &str| -> Result<Option<f64>, PatternError> {
                b.as_ref()
                    .map(|s| non_negative(*s.get_ref()).map_err(|r| err(line(s.span()), &field(name), r)))
                    .transpose()
            };
            let min_magnitude = bound(&e.min_magnitude, "min_magnitude")?;
            let max_magnitude = bound(&e.max_magnitude, "max_magnitude")?;
            if let (Some(lo), Some(hi), Some(s)) = (min_magnitude, max_magnitude, &e.max_magnitude)
                && hi < lo
            {
                return Err(err(
                    line(s.span()),
                    &field("max_magnitude"),
                    format!("{hi} is below min_magnitude {lo}"),
                ));
            }
            let slack_s = bound(&e.slack_s, "slack_s")?.unwrap_or(default_slack);
            let grasp = e
                .grasp
                .as_ref()
                .map(|g| {
                    GraspState::parse(g.get_ref()).ok_or_else(|| {
                        err(
                            line(g.span()),
                            &field("grasp"),
                            format!("'{}' is not one of open, holding, closed_empty", g.get_ref()),
                        )
                    })
                })
                .transpose()?;
            elements.push(Element {
                id,
                kind,
                description: e.description.clone(),
                min_magnitude,
                max_magnitude,
                slack_s,
                after: e.after.as_ref().map(|a| a.get_ref().clone()).unwrap_or_default(),
                grasp,
                line: line(re.span()),
            });
        }
        instruments.push(InstrumentPattern { instrument: *arm, elements, primitives: Vec::new() });
    }

    // Pass 2: references between elements.
    for (arm, ri) in &present {
        for (k, re) in ri.feature.iter().enumerate() {
            let Some(after) = &re.get_ref().after else { continue };
            for target in after.get_ref() {
                let field = format!("{arm}.feature[{k}].after");
                match ids.get(target) {
                    None => {
                        return Err(err(
                            line(after.span()),
                            &field,
                            format!("no feature has the id '{target}'"),
                        ));
                    }
                    Some((other, index)) if other == arm && *index >= k => {
                        return Err(err(
                            line(after.span()),
                            &field,
                            format!("'{target}' is this instrument's own feature at or after this one"),
                        ));
                    }
                    Some(_) => {}
                }
            }
        }
    }
    if let Some((arm, k)) = circular_after(&instruments) {
        let ip = instruments.iter().find(|i| i.instrument == arm);
        let l = ip.map_or(0, |i| i.elements[k].line);
        return Err(err(
            l,
            &format!("{arm}.feature[{k}].after"),
            "the 'after' references form a cycle".to_owned(),
        ));
    }

    // Pass 3: primitives.
    let mut primitive_types: HashMap<String, (ArmName, PrimitiveType)> = HashMap::new();
    for (arm, ri) in &present {
        for (k, rp) in ri.primitive.iter().enumerate() {
            let p = rp.get_ref();
            let kind = PrimitiveType::parse(p.kind.get_ref()).ok_or_else(|| {
                err(
                    line(p.kind.span()),
                    &format!("{arm}.primitive[{k}].type"),
                    format!(
                        "unknown primitive type '{}' (expected 2d, linear, force or synchronized)",
                        p.kind.get_ref()
                    ),
                )
            })?;
            primitive_types.insert(p.name.get_ref().clone(), (*arm, kind));
        }
    }
    for (j, (arm, ri)) in present.iter().enumerate() {
        let mut primitives = Vec::new();
        let mut last_end: Option<usize> = None;
        for (k, rp) in ri.primitive.iter().enumerate() {
            let field = |name: &str| format!("{arm}.primitive[{k}].{name}");
            let p = rp.get_ref();
            let name = p.name.get_ref().clone();
            check_name(&name).map_err(|r| err(line(p.name.span()), &field("name"), r))?;
            if !names.insert(name.clone()) {
                return Err(err(
                    line(p.name.span()),
                    &field("name"),
                    format!("a primitive '{name}' exists already"),
                ));
            }
            let kind = primitive_types.get(&name).map_or(PrimitiveType::Linear, |(_, k)| *k);
            let ip = &instruments[j];
            let endpoint = |s: &Option<Spanned<String>>, name: &str| -> Result<Option<usize>, PatternError> {
                let Some(s) = s else { return Ok(None) };
                ip.element_index(s.get_ref()).map(Some).ok_or_else(|| {
                    err(line(s.span()), &field(name), format!("'{}' is no feature of {arm}", s.get_ref()))
                })
            };
            let from = endpoint(&p.from, "from")?;
            let to = endpoint(&p.to, "to")?;
            let here = line(rp.span());
            if kind == PrimitiveType::Synchronized {
                let Some(reference) = &p.reference else {
                    return Err(err(
                        here,
                        &field("reference"),
                        "a synchronized primitive names its reference 2D primitive".to_owned(),
                    ));
                };
                match primitive_types.get(reference.get_ref()) {
                    Some((other, PrimitiveType::TwoD)) if other != arm => {}
                    Some((other, t)) => {
                        return Err(err(
                            line(reference.span()),
                            &field("reference"),
                            format!(
                                "'{}' is a {t} primitive of {other}: the reference must be another instrument's 2d primitive",
                                reference.get_ref()
                            ),
                        ));
                    }
                    None => {
                        return Err(err(
                            line(reference.span()),
                            &field("reference"),
                            format!("no primitive is named '{}'", reference.get_ref()),
                        ));
                    }
                }
                if from.is_some() != to.is_some() {
                    return Err(err(
                        here,
                        &field("from"),
                        "give both from and to, or neither (the reference's span)".to_owned(),
                    ));
                }
            } else {
                if let Some(reference) = &p.reference {
                    return Err(err(
                        line(reference.span()),
                        &field("reference"),
                        format!("only synchronized primitives have a reference, this one is {kind}"),
                    ));
                }
                if from.is_none() {
                    return Err(err(
                        here,
                        &field("from"),
                        "missing: the feature that starts the primitive".to_owned(),
                    ));
                }
                if to.is_none() {
                    return Err(err(
                        here,
                        &field("to"),
                        "missing: the feature that ends the primitive".to_owned(),
                    ));
                }
            }
            if let (Some(a), Some(b)) = (from, to) {
                if a >= b {
                    return Err(err(
                        here,
                        &field("to"),
                        format!("'{}' must come after '{}'", ip.elements[b].id, ip.elements[a].id),
                    ));
                }
                if last_end.is_some_and(|e| a < e) {
                    return Err(err(
                        here,
                        &field("from"),
                        "primitives of an instrument must not overlap or go back in time".to_owned(),
                    ));
                }
                last_end = Some(b);
            }
            primitives.push(PrimitiveSpec {
                name,
                kind,
                from: p.from.as_ref().map(|s| s.get_ref().clone()),
                to: p.to.as_ref().map(|s| s.get_ref().clone()),
                reference: p.reference.as_ref().map(|s| s.get_ref().clone()),
                description: p.description.clone(),
                line: here,
            });
        }
        instruments[j].primitives = primitives;
    }
    Ok(TaskPattern { name: raw.name.get_ref().clone(), description: raw.description, detector, instruments })
}

fn non_negative(x: f64) -> Result<f64, String> {
    if x.is_finite() && x >= 0.0 { Ok(x) } else { Err(format!("must be a finite number >= 0, got {x}")) }
}

fn check_name(name: &str) -> Result<(), String> {
    if !name.is_empty() && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-') {
        Ok(())
    } else {
        Err(format!("'{name}' must be letters, digits, '_' or '-'"))
    }
}

/// An element on a cycle of "comes after" edges (each element after its predecessor in its instrument,
/// and after its `after` references), if any.
fn circular_after(instruments: &[InstrumentPattern]) -> Option<(ArmName, usize)> {
    let nodes: Vec<(ArmName, usize)> =
        instruments.iter().flat_map(|i| (0..i.elements.len()).map(move |k| (i.instrument, k))).collect();
    let index: HashMap<(ArmName, usize), usize> = nodes.iter().enumerate().map(|(n, &x)| (x, n)).collect();
    let mut incoming = vec![0usize; nodes.len()];
    let mut edges: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    let id_of: HashMap<&str, (ArmName, usize)> = instruments
        .iter()
        .flat_map(|i| i.elements.iter().enumerate().map(move |(k, e)| (e.id.as_str(), (i.instrument, k))))
        .collect();
    for i in instruments {
        for (k, e) in i.elements.iter().enumerate() {
            let me = index[&(i.instrument, k)];
            let mut before: Vec<usize> =
                e.after.iter().filter_map(|id| id_of.get(id.as_str())).map(|x| index[x]).collect();
            if k > 0 {
                before.push(index[&(i.instrument, k - 1)]);
            }
            for b in before {
                edges[b].push(me);
                incoming[me] += 1;
            }
        }
    }
    let mut ready: Vec<usize> = (0..nodes.len()).filter(|&n| incoming[n] == 0).collect();
    let mut done = 0;
    while let Some(n) = ready.pop() {
        done += 1;
        for &m in &edges[n] {
            incoming[m] -= 1;
            if incoming[m] == 0 {
                ready.push(m);
            }
        }
    }
    if done == nodes.len() { None } else { (0..nodes.len()).find(|&n| incoming[n] > 0).map(|n| nodes[n]) }
}
