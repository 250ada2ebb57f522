//! `knotlab validate`: the suture checked against mechanics. Builds small experiments with a scene's
//! suture and prints each measured figure beside its reference, tolerance and source; exits 1 when
//! a judged figure is outside its tolerance.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use knotlab_sim::validation::{self, Check, EXPERIMENTS, Experiment, SutureUnderTest, figure_text};

use super::output::{Output, outln};
use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// The scene whose suture is checked (its `[thread]`, which must be the rope, and its step)
    /// [default: the shipped scenarios/default.toml, built in].
    #[arg(long, value_name = "SCENE")]
    suture_from: Option<PathBuf>,
    /// Also write `validation.json` and `validation.md` (the table) into this directory.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Run only this experiment (repeatable) [default: every experiment, in the table's order].
    #[arg(long, value_name = "EXPERIMENT", value_parser = experiment_names())]
    only: Vec<String>,
}

/// The names `--only` takes: the suite's experiments.
fn experiment_names() -> clap::builder::PossibleValuesParser {
    clap::builder::PossibleValuesParser::new(EXPERIMENTS.iter().map(|e| e.name()))
}

/// The checks as a Markdown table.
fn table(checks: &[Check]) -> String {
    let mut text = String::from(
        "| experiment | figure | measured | reference | tolerance | result | source |\n|---|---|---|---|---|---|---|\n",
    );
    for c in checks {
        let result = match c.passed {
            Some(true) => "pass",
            Some(false) => "FAIL",
            None => "reported",
        };
        let unit = if c.unit == "1" { String::new() } else { format!(" {}", c.unit) };
        let _ = writeln!(
            text,
            "| {} | {} | {}{unit} | {}{unit} | {} | {result} | {} |",
            c.experiment,
            c.figure,
            figure_text(c.measured),
            figure_text(c.reference),
            c.tolerance_text(),
            c.source
        );
    }
    text
}

pub fn run(args: ValidateArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let name = shipped::name(args.suture_from.as_deref(), &shipped::SCENE);
    let scene = shipped::scene(args.suture_from.as_deref(), &shipped::SCENE)?;
    let suture = SutureUnderTest::from_scene(&scene).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let chosen: Vec<Experiment> = EXPERIMENTS
        .into_iter()
        .filter(|e| args.only.is_empty() || args.only.iter().any(|o| o == e.name()))
        .collect();
    // Side by side, their checks in the table's order.
    let checks = validation::run(&suture, &chosen);
    let failed = checks.iter().filter(|c| c.passed == Some(false)).count();
    let judged = checks.iter().filter(|c| c.passed.is_some()).count();
    let report = serde_json::json!({
        "suture_from": name,
        "experiments": chosen.iter().map(|e| e.name()).collect::<Vec<_>>(),
        "judged": judged,
        "failed": failed,
        "checks": checks,
    });
    if let Some(dir) = &args.out {
        std::fs::create_dir_all(dir).with_context(|| format!("{}: cannot create", dir.display()))?;
        let json_path = dir.join("validation.json");
        std::fs::write(&json_path, serde_json::to_string_pretty(&report)? + "\n")
            .with_context(|| format!("{}: cannot write", json_path.display()))?;
        let md_path = dir.join("validation.md");
        std::fs::write(&md_path, table(&checks))
            .with_context(|| format!("{}: cannot write", md_path.display()))?;
    }
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&report)?);
    } else {
        out.line(table(&checks).trim_end());
        outln!(
            out,
            "{} of {judged} judged checks passed ({} reported only)",
            judged - failed,
            checks.len() - judged
        );
    }
    Ok(if failed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
