//! The report of a Monte Carlo run (`knotlab report DIR`): one self-contained HTML file from
//! `DIR/results.jsonl` with per method the success rate, its 95 % Wilson interval and the failure
//! modes, the methods side by side, success against play, calibration error and the stitch's
//! displacement, turn and tilt in bins, and the workspace maps (success per cell of the stitch's
//! shift, and of its turn and tilt). The figures come from [`methods`], [`bins`] and [`map`];
//! [`plots`] only draws them.

pub mod bins;
pub mod html;
pub mod map;
pub mod methods;
pub mod plots;

use std::path::Path;

use serde::Serialize;

use crate::mc::{McError, TrialLine, read_results};

use bins::{BIN_COUNT, Parameter, SweepShape, sweep};
use html::{Section, note};
use map::{Axis, MAP_CELLS, MapShape, map};
use methods::{MethodStats, RunOverview, failure_modes, method_stats, run_overview, unique_lines};
use plots::{FAILURES_TITLE, METHODS_TITLE, PlotError};

/// Why no report was written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The results file could not be read, or a line of it is malformed.
    #[error(transparent)]
    Results(#[from] McError),
    /// The results file is missing or holds nothing to report.
    #[error("{file}: {reason}")]
    Input {
        /// The file.
        file: String,
        /// Why.
        reason: String,
    },
    /// No lines were given.
    #[error("no finished trials to report")]
    NoTrials,
    /// A trial's drawn parameter is not one the report can show.
    #[error(
        "{at}: draw.{field} = {value}: a drawn value must be finite and at most {MAX_DRAWN_SI:e} in magnitude"
    )]
    Draw {
        /// Which line (`FILE line N`) or trial (`trial N (method)`).
        at: String,
        /// The draw's field.
        field: &'static str,
        /// The value as written.
        value: String,
    },
    /// A chart could not be drawn.
    #[error(transparent)]
    Chart(#[from] PlotError),
    /// The report could not be written.
    #[error("{file}: {reason}")]
    Write {
        /// The file.
        file: String,
        /// Why.
        reason: String,
    },
}

/// The largest magnitude of a drawn parameter the report shows, SI: the charts show it in thousandths
/// (mrad, mm), and their ranges must stay finite.
pub const MAX_DRAWN_SI: f64 = 1e300;

/// The first of `lines` whose draw holds a parameter the report sweeps but cannot show (not a
/// number, not finite, or beyond [`MAX_DRAWN_SI`]), with the field and its value as written; `at`
/// names the line by its place among `lines`.
fn check_draws(lines: &[TrialLine], at: impl Fn(usize, &TrialLine) -> String) -> Result<(), ReportError> {
    for (k, line) in lines.iter().enumerate() {
        for parameter in Parameter::ALL {
            let Some(written) = line.draw.get(parameter.field()) else { continue };
            if parameter.value_si(line).is_none_or(|v| v.abs() > MAX_DRAWN_SI) {
                return Err(ReportError::Draw {
                    at: at(k, line),
                    field: parameter.field(),
                    value: written.to_string(),
                });
            }
        }
    }
    Ok(())
}

/// What was reported.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReportSummary {
    /// The HTML file written.
    pub report: String,
    /// Each chart written on its own as an SVG file (with `charts_dir`), in the report's order.
    pub charts: Vec<String>,
    /// The run.
    pub run: RunOverview,
    /// Per method.
    pub methods: Vec<MethodStats>,
}

/// Reads `dir/results.jsonl` and writes the report to `out`, and with `charts_dir` each of its charts
/// as an SVG file there (`methods.svg`, `failures.svg`, `play.svg`, ..., `map-shift-METHOD.svg`,
/// `map-turn-tilt-METHOD.svg`); the scene is taken from `dir/run.json` (or `dir/summary.json`) when
/// one names it.
pub fn write_report(dir: &Path, out: &Path, charts_dir: Option<&Path>) -> Result<ReportSummary, ReportError> {
    let results = dir.join("results.jsonl");
    let file = results.display().to_string();
    if !results.is_file() {
        let reason = if dir.is_dir() {
            "not found: is this a Monte Carlo run's directory (knotlab mc --out DIR)?".to_owned()
        } else {
            format!("not found: no directory {}", dir.display())
        };
        return Err(ReportError::Input { file, reason });
    }
    let lines = read_results(dir)?;
    // With the run's `run.json` there, a line of another run is refused rather than counted; without
    // it, a trial of a method given twice or a line of another seed than the first line's.
    match crate::mc::run_info::RunInfo::read(dir)? {
        Some(info) => crate::mc::check_lines(&lines, &info, &file)?,
        None => crate::mc::check_lines_alone(&lines, &file)?,
    }
    if lines.is_empty() {
        return Err(ReportError::Input { file, reason: "holds no finished trial".to_owned() });
    }
    // `read_results` keeps every line in order (but a last one cut short, after them all).
    check_draws(&lines, |k, _| format!("{file} line {}", k + 1))?;
    let scene = scene_of(dir);
    let title = format!("Monte Carlo run {}", dir.display());
    let (text, run, methods, charts) = render(&lines, &title, scene.as_deref())?;
    let written = write_file(out, &text)?;
    let mut chart_files = Vec::new();
    if let Some(charts_dir) = charts_dir {
        for (name, svg) in &charts {
            chart_files.push(write_file(&charts_dir.join(format!("{name}.svg")), svg)?);
        }
    }
    Ok(ReportSummary { report: written, charts: chart_files, run, methods })
}

/// Writes `text` to `path`, making its folder; returns the path as shown.
fn write_file(path: &Path, text: &str) -> Result<String, ReportError> {
    let written = path.display().to_string();
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| ReportError::Write { file: written.clone(), reason: e.to_string() })?;
    }
    std::fs::write(path, text)
        .map_err(|e| ReportError::Write { file: written.clone(), reason: e.to_string() })?;
    Ok(written)
}

/// A chart's file name from its words: lower case, letters, digits and dashes only.
fn file_stem(words: &str) -> String {
    let mut stem = String::new();
    for c in words.chars() {
        if c.is_ascii_alphanumeric() {
            stem.push(c.to_ascii_lowercase());
        } else if !stem.ends_with('-') && !stem.is_empty() {
            stem.push('-');
        }
    }
    let stem = stem.trim_end_matches('-').to_owned();
    if stem.is_empty() { "chart".to_owned() } else { stem }
}

/// The scene named by `dir/run.json` (with its preset) or else `dir/summary.json`, if either is there
/// and names one. Both are optional: the report is made from `results.jsonl` alone.
fn scene_of(dir: &Path) -> Option<String> {
    let read = |name: &str| -> Option<serde_json::Value> {
        serde_json::from_str(&std::fs::read_to_string(dir.join(name)).ok()?).ok()
    };
    if let Some(run) = read("run.json")
        && let Some(scene) = run.get("scene").and_then(serde_json::Value::as_str)
    {
        return Some(match run.get("preset").and_then(serde_json::Value::as_str) {
            Some(preset) => format!("{scene} (preset {preset})"),
            None => scene.to_owned(),
        });
    }
    read("summary.json")?.get("scene")?.as_str().map(str::to_owned)
}

/// The report's page for `lines` (any order; each (trial, method) counted once).
pub fn render_report(lines: &[TrialLine], title: &str) -> Result<String, ReportError> {
    render(lines, title, None).map(|(text, _, _, _)| text)
}

/// The page, the run, the methods' figures, and each chart with its file name (no extension).
type Rendered = (String, RunOverview, Vec<MethodStats>, Vec<(String, String)>);

fn render(lines: &[TrialLine], title: &str, scene: Option<&str>) -> Result<Rendered, ReportError> {
    check_draws(lines, |_, l| format!("trial {} ({})", l.trial, l.method))?;
    let lines = unique_lines(lines);
    let info = run_overview(&lines).ok_or(ReportError::NoTrials)?;
    let stats = method_stats(&lines, &info.methods);
    let mut charts: Vec<(String, String)> = Vec::new();
    // Each chart under a name of its own: a name already taken (two methods whose names differ only
    // in what a file name leaves out) gets -2, -3, ...
    let mut chart = |name: String, svg: String| {
        let mut unique = name.clone();
        let mut k = 1;
        while charts.iter().any(|(taken, _)| *taken == unique) {
            k += 1;
            unique = format!("{name}-{k}");
        }
        charts.push((unique, svg.clone()));
        svg
    };
    let mut sections = vec![
        Section { title: "Per method".to_owned(), body: html::method_tables(&stats) },
        Section {
            title: METHODS_TITLE.to_owned(),
            body: chart("methods".to_owned(), plots::methods_chart(&stats)?),
        },
    ];
    let modes = failure_modes(&stats);
    sections.push(Section {
        title: FAILURES_TITLE.to_owned(),
        body: if modes.is_empty() {
            note("No failures: every trial of every method tied the knot.")
        } else {
            chart("failures".to_owned(), plots::failures_chart(&stats, &modes)?)
        },
    });
    for parameter in Parameter::ALL {
        let s = sweep(&lines, &info.methods, parameter, BIN_COUNT);
        let shown = |si: f64| format!("{:.3} {}", si * parameter.shown_per_si(), parameter.shown_unit());
        let mut body = match &s.shape {
            SweepShape::NoValues => {
                note(&format!("No line's draw has {}: nothing to plot.", parameter.field()))
            }
            SweepShape::Constant(value) => note(&format!(
                "The {} was the same in every trial ({}): no chart.",
                parameter.name(),
                shown(*value)
            )),
            SweepShape::Binned { lo, hi, methods } => format!(
                "{}{}{}{}",
                html::legend(&info.methods),
                chart(file_stem(parameter.name()), plots::sweep_chart(parameter, *lo, *hi, methods)?),
                note(&format!(
                    "{BIN_COUNT} equal-width bins over {} to {}; bins without trials left out.",
                    shown(*lo),
                    shown(*hi)
                )),
                html::sweep_table(parameter, methods)
            ),
        };
        if s.lines_without_value > 0 {
            body.push_str(&note(&format!(
                "{} line(s) without {} in their draw left out.",
                s.lines_without_value,
                parameter.field()
            )));
        }
        sections.push(Section { title: plots::sweep_title(parameter), body });
    }
    for (x, y, name) in [(Axis::ShiftX, Axis::ShiftY, "map-shift"), (Axis::Turn, Axis::Tilt, "map-turn-tilt")]
    {
        let m = map(&lines, &info.methods, x, y, MAP_CELLS);
        let mut body = match &m.shape {
            MapShape::Flat => note(&format!(
                "The {} and the {} did not both vary across the trials: no map.",
                x.name(),
                y.name()
            )),
            MapShape::Grid { x: x_range, y: y_range, cells, methods } => {
                let mut body = note(&format!(
                    "{cells} by {cells} equal cells over the values drawn; cells without trials left out. \
                     Outlined: cells with trials the arms could not do ({}).",
                    map::OUT_OF_REACH.join(", ")
                ));
                for method in methods {
                    body.push_str(&chart(
                        file_stem(&format!("{name} {}", method.method)),
                        plots::map_chart(x, y, *x_range, *y_range, method)?,
                    ));
                    body.push_str(&html::map_table(x, y, method));
                }
                body
            }
        };
        if m.lines_without_value > 0 {
            body.push_str(&note(&format!(
                "{} line(s) without both values in their draw left out.",
                m.lines_without_value
            )));
        }
        sections.push(Section { title: plots::map_title(x, y), body });
    }
    let page = html::page(title, &html::header(&info, scene), &sections);
    Ok((page, info, stats, charts))
}

/// A results line for the report's unit tests: trial 0 of seed 1, `method`, `draw`, `verdict`.
#[cfg(test)]
pub(crate) fn test_line(method: &str, draw: serde_json::Value, verdict: &str) -> TrialLine {
    TrialLine {
        trial: 0,
        seed: 1,
        method: method.to_owned(),
        draw,
        verdict: verdict.to_owned(),
        knot: None,
        wound_gap_m: None,
        thread_max_stretch: None,
        thread_stretched_s: None,
        thread_self_crossings: None,
        first_self_crossing: None,
        slid: None,
        sim_seconds: 0.0,
        wall_seconds: 0.0,
        error: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two methods whose names differ only in what a file name leaves out get charts of their own, not
    /// one file written over the other.
    #[test]
    fn charts_of_methods_alike_in_file_names_do_not_overwrite_each_other() {
        let draw = |x: f64| {
            serde_json::json!({
                "stitch_offset_m": [x, -x, 0.0], "stitch_rotate_rad": x, "stitch_tilt_rad": -x,
                "play_rad": 0.0, "calibration_max_rad": 0.0
            })
        };
        let mut lines = Vec::new();
        for method in ["a b", "a-b"] {
            for trial in 0..3u64 {
                let mut line = test_line(
                    method,
                    draw(0.01 * trial as f64),
                    if trial == 0 { "success" } else { "no_knot" },
                );
                line.trial = trial;
                lines.push(line);
            }
        }
        let (_, _, _, charts) = render(&lines, "two methods", None).expect("rendered");
        let names: Vec<&str> = charts.iter().map(|(name, _)| name.as_str()).collect();
        assert!(names.contains(&"map-shift-a-b") && names.contains(&"map-shift-a-b-2"), "{names:?}");
        let mut unique = names.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), names.len(), "{names:?}");
    }
}
