//! `knotlab learn`: one demonstration cut into motion primitives by a task pattern, the primitives
//! stored as a knowledge base; a demonstration that does not match the pattern is rejected with the
//! reason (exit code 3).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use serde::Serialize;

use knotlab_learner::demonstration::Demonstration;
use knotlab_learner::features::{FeatureKind, FeatureSet, detect};
use knotlab_learner::pattern::TaskPattern;
use knotlab_learner::primitive::{extract, write_knowledge_base};
use knotlab_learner::segment::{Decomposition, FailureReason, Rejection, decompose};

use super::output::{Output, outln};
use crate::rerun_log::{self, RerunArgs};
use knotlab_scenarios::shipped;

/// The exit code of a rejected demonstration (1 is a bad file, 2 a bad command line).
const REJECTED: u8 = 3;

#[derive(Debug, Args)]
pub struct LearnArgs {
    /// The demonstration: a directory with demo.toml and one CSV file per instrument (see
    /// learner/src/demonstration/FORMAT.md); by default the canonical one the scripted expert recorded,
    /// which `knotlab demo --seed 0 --out DIR` records again [default: the shipped
    /// scenarios/demos/instrument-tie, built in].
    #[arg(long)]
    demo: Option<PathBuf>,
    /// The task pattern (TOML) [default: the shipped scenarios/patterns/knot_tying.toml, built in].
    #[arg(long)]
    pattern: Option<PathBuf>,
    /// Where to write the knowledge base (JSON); nothing is written for a rejected demonstration.
    #[arg(long)]
    out: PathBuf,
    /// Print JSON instead of text (with every detected feature: instrument, kind, time, magnitude, grasp)
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    rerun: RerunArgs,
}

#[derive(Serialize)]
struct PrimitiveLine {
    name: String,
    #[serde(rename = "type")]
    kind: &'static str,
    start_s: f64,
    end_s: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    reference: Option<String>,
}

#[derive(Serialize)]
struct InstrumentLines {
    instrument: &'static str,
    primitives: Vec<PrimitiveLine>,
    /// Detected features the pattern did not use, before its last element (spurious ones).
    skipped_features: usize,
}

/// One detected feature, for whoever writes a pattern.
#[derive(Serialize)]
struct FeatureLine {
    instrument: &'static str,
    kind: &'static str,
    time_s: f64,
    /// In the kind's unit (m, m/s^2, 1/m, N or rad).
    magnitude: f64,
    /// What the jaws hold once settled after it.
    grasp: &'static str,
}

#[derive(Serialize)]
struct FailureLine {
    instrument: &'static str,
    element: String,
    kind: &'static str,
    description: String,
    primitive: Option<String>,
    stopped_at_s: f64,
    recording_end_s: f64,
    /// `not_found`, `needs_unmatched` or `too_early`.
    cause: &'static str,
    reason: String,
}

#[derive(Serialize)]
struct Report {
    accepted: bool,
    demo: String,
    pattern: String,
    task: String,
    source: String,
    sample_rate_hz: f64,
    duration_s: f64,
    /// Features detected, per kind.
    features: Vec<(&'static str, usize)>,
    /// Every feature detected, per instrument in time order (JSON only).
    detected: Vec<FeatureLine>,
    #[serde(skip_serializing_if = "Option::is_none")]
    out: Option<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    instruments: Vec<InstrumentLines>,
    #[serde(skip_serializing_if = "Option::is_none")]
    reason: Option<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    failures: Vec<FailureLine>,
}

pub fn run(args: LearnArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    match learn(&args) {
        Ok(report) => {
            print(&report, args.json, out)?;
            Ok(if report.accepted { ExitCode::SUCCESS } else { ExitCode::from(REJECTED) })
        }
        Err(error) if args.json => {
            let text = format!("{error:#}");
            out.line(
                serde_json::to_string_pretty(&serde_json::json!({ "ok": false, "error": text }))
                    .context("writing JSON")?,
            );
            Ok(ExitCode::FAILURE)
        }
        Err(error) => Err(error),
    }
}

fn learn(args: &LearnArgs) -> anyhow::Result<Report> {
    let demo = shipped::demonstration(args.demo.as_deref())?;
    let pattern = shipped::pattern(args.pattern.as_deref())?;
    let features = detect(&demo, &pattern.detector).context("detecting features")?;
    let mut report = base_report(args, &demo, &pattern, &features);
    let recording = args.rerun.open("learn")?;
    let decomposition = decompose(&pattern, &features);
    log_to_rerun(recording.as_ref(), &demo, &features, decomposition.as_ref().ok())?;
    rerun_log::finish(recording)?;
    match decomposition {
        Ok(decomposition) => {
            let kb = extract(&demo, &pattern, &features, &decomposition)?;
            write_knowledge_base(&args.out, &kb)?;
            report.accepted = true;
            report.out = Some(args.out.display().to_string());
            report.instruments = lines(&pattern, &decomposition);
        }
        Err(rejection) => {
            report.reason = Some(rejection.to_string());
            report.failures = failure_lines(&rejection);
        }
    }
    Ok(report)
}

/// The demonstration, its features and (if it was cut) its primitives, for the Rerun viewer.
#[cfg(feature = "rerun")]
fn log_to_rerun(
    recording: Option<&rerun_log::Recording>,
    demo: &Demonstration,
    features: &FeatureSet,
    decomposition: Option<&Decomposition>,
) -> anyhow::Result<()> {
    if let Some(rec) = recording {
        rerun_log::log_demonstration(rec, demo)?;
        rerun_log::log_decomposition(rec, demo, features, decomposition)?;
    }
    Ok(())
}

#[cfg(not(feature = "rerun"))]
fn log_to_rerun(
    _: Option<&rerun_log::Recording>,
    _: &Demonstration,
    _: &FeatureSet,
    _: Option<&Decomposition>,
) -> anyhow::Result<()> {
    Ok(())
}

fn base_report(
    args: &LearnArgs,
    demo: &Demonstration,
    pattern: &TaskPattern,
    features: &FeatureSet,
) -> Report {
    Report {
        accepted: false,
        demo: shipped::demo_name(args.demo.as_deref()),
        pattern: shipped::name(args.pattern.as_deref(), &shipped::PATTERN),
        task: pattern.name.clone(),
        source: demo.metadata.source.clone(),
        sample_rate_hz: demo.metadata.sample_rate_hz,
        duration_s: demo.duration_s(),
        features: FeatureKind::ALL
            .iter()
            .map(|k| (k.as_str(), features.count(*k)))
            .filter(|(_, n)| *n > 0)
            .collect(),
        detected: features
            .instruments
            .iter()
            .flat_map(|a| &a.features)
            .map(|f| FeatureLine {
                instrument: f.instrument.as_str(),
                kind: f.kind.as_str(),
                time_s: f.time_s,
                magnitude: f.magnitude,
                grasp: f.grasp_after.as_str(),
            })
            .collect(),
        out: None,
        instruments: Vec::new(),
        reason: None,
        failures: Vec::new(),
    }
}

fn lines(pattern: &TaskPattern, d: &Decomposition) -> Vec<InstrumentLines> {
    pattern
        .instruments
        .iter()
        .map(|ip| InstrumentLines {
            instrument: ip.instrument.as_str(),
            primitives: d
                .segments
                .iter()
                .filter(|s| s.instrument == ip.instrument)
                .map(|s| PrimitiveLine {
                    name: s.name.clone(),
                    kind: s.kind.as_str(),
                    start_s: s.start_s,
                    end_s: s.end_s,
                    reference: s.reference.clone(),
                })
                .collect(),
            skipped_features: d
                .matches
                .iter()
                .find(|m| m.instrument == ip.instrument)
                .map_or(0, |m| m.skipped),
        })
        .collect()
}

fn failure_lines(r: &Rejection) -> Vec<FailureLine> {
    r.failures
        .iter()
        .map(|f| FailureLine {
            instrument: f.instrument.as_str(),
            element: f.element.clone(),
            kind: f.kind.as_str(),
            description: f.description.clone(),
            primitive: f.primitive.clone(),
            stopped_at_s: f.stopped_at_s,
            recording_end_s: f.recording_end_s,
            cause: match f.reason {
                FailureReason::NotFound { .. } => "not_found",
                FailureReason::NeedsUnmatched { .. } => "needs_unmatched",
                FailureReason::TooEarly { .. } => "too_early",
            },
            reason: f.to_string(),
        })
        .collect()
}

fn print(r: &Report, json: bool, out: &mut Output) -> anyhow::Result<()> {
    if json {
        out.line(serde_json::to_string_pretty(r).context("writing JSON")?);
        return Ok(());
    }
    outln!(
        out,
        "demonstration {} ({}, {} Hz, {:.2} s); pattern {} ({})",
        r.demo,
        r.source,
        r.sample_rate_hz,
        r.duration_s,
        r.task,
        Path::new(&r.pattern).display()
    );
    let counts: Vec<String> = r.features.iter().map(|(k, n)| format!("{k} {n}")).collect();
    outln!(out, "features: {}", counts.join(", "));
    if !r.accepted {
        out.error(format!("rejected: {}", r.reason.as_deref().unwrap_or("")));
        for f in &r.failures {
            outln!(out, "rejected: {}", f.reason);
        }
        return Ok(());
    }
    for i in &r.instruments {
        outln!(out, "{}", i.instrument);
        for p in &i.primitives {
            let with = p.reference.as_ref().map_or(String::new(), |r| format!("  (with {r})"));
            outln!(
                out,
                "  {:<4} {:<13} {:>8.3} s - {:>8.3} s  ({:.3} s){with}",
                p.name,
                p.kind,
                p.start_s,
                p.end_s,
                p.end_s - p.start_s
            );
        }
    }
    outln!(out, "knowledge base: {}", r.out.as_deref().unwrap_or(""));
    Ok(())
}
