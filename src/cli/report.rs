//! `knotlab report DIR`: a self-contained HTML report of a Monte Carlo run (DIR/results.jsonl), written
//! to DIR/report.html or `--out`; prints where it went and a line per method (or JSON with `--json`).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use knotlab_bench::report::write_report;

use super::output::{Output, outln};

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// The Monte Carlo run's directory (`knotlab mc --out DIR`), holding results.jsonl.
    dir: PathBuf,
    /// Where the HTML goes (default: DIR/report.html).
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also write each chart as its own SVG file in this folder (for a paper or the docs):
    /// methods.svg, failures.svg, play.svg, ..., map-shift-METHOD.svg, map-turn-tilt-METHOD.svg.
    #[arg(long, value_name = "DIR")]
    charts: Option<PathBuf>,
    /// Print the report's path and the per-method figures as JSON.
    #[arg(long)]
    json: bool,
}

pub fn run(args: ReportArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let path = args.out.clone().unwrap_or_else(|| args.dir.join("report.html"));
    let summary = write_report(&args.dir, &path, args.charts.as_deref())?;
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&summary)?);
    } else {
        outln!(out, "report: {}", summary.report);
        if !summary.charts.is_empty() {
            outln!(
                out,
                "charts: {} SVG files in {}",
                summary.charts.len(),
                args.charts.as_deref().unwrap_or(&path).display()
            );
        }
        for m in &summary.methods {
            outln!(
                out,
                "{}: {} of {} trials tied the knot ({:.1} %, 95 % Wilson {:.1}-{:.1} %)",
                m.method,
                m.tally.successes,
                m.tally.trials,
                100.0 * m.tally.success_rate,
                100.0 * m.tally.wilson_95[0],
                100.0 * m.tally.wilson_95[1]
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}
