//! `knotlab demo`: the scripted expert ties the knot in the simulator; each run is recorded as a
//! demonstration and its knot evaluated. One seed writes one demonstration directory; `--seeds A..B`
//! runs seeds A to B-1 and reports the success rate.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use serde::Serialize;

use knotlab_learner::demonstration::write_demonstration;
use knotlab_scenarios::expert::{DemoRun, RecordOptions, demonstrate_with};

use super::csv_file;
use super::numbers::{Numbers, parse_list};
use super::output::{Output, outln};
use crate::rerun_log::{self, RerunArgs};
use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
pub struct DemoArgs {
    /// The scene file [default: the shipped scenarios/default.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    /// The seed of one run (without --seeds): its human-like variation and sensor noise.
    #[arg(long, default_value_t = 0, conflicts_with = "seeds")]
    seed: u64,
    /// Runs seeds A to B-1 (`A..B`), each recorded under OUT/seed-N.
    #[arg(long, value_parser = parse_seeds)]
    seeds: Option<(u64, u64)>,
    /// Where to write the demonstration (one seed) or the demonstrations (several).
    #[arg(long)]
    out: PathBuf,
    /// Perform like a machine: nominal speed, fixed pauses, no tremor.
    #[arg(long)]
    no_variation: bool,
    /// The expert's plan: where it puts things, from this TOML file (keys left out keep the base
    /// plan's, listed in scenarios/experts/base.toml). The shipped plan ties the double throw and
    /// cinches it by both ends [default: the shipped scenarios/experts/instrument-tie.toml, built in].
    #[arg(long, value_name = "FILE")]
    expert: Option<PathBuf>,
    /// Draw the scene into PNG files OUT/snapshot-T.png at these times, s from the start
    /// (comma-separated; times past the skill's end fall in the holding test, on the same clock), and
    /// write the thread's centreline beside each (OUT/centreline-T.csv, x_m,y_m,z_m from the needle end) and which of its
    /// segments touch which robot links (OUT/contacts-T.csv, segment,link).
    #[arg(long, value_parser = parse_list)]
    snapshots: Option<Numbers>,
    /// Half the width of each snapshot view, m (the views are centred 3 cm above the wound, or 0.6 of
    /// the half width for narrower views; 0.015 shows the knot).
    #[arg(long, value_name = "M", default_value_t = 0.08, value_parser = parse_half_width)]
    snapshot_half_width: f64,
    /// Stop at this time (s from the start) and evaluate what is there (a short trial, to debug).
    #[arg(long, value_name = "S")]
    until: Option<f64>,
    /// Every S seconds of the skill (not the holding test after it), take the knot as the thread lies
    /// and what the gauges read, into OUT/knot-trace.csv (time, knot, height, loop outside, radius,
    /// each leg's thread and span, the thread's arc from the needle end at the exit and entry points,
    /// wound gap, each instrument's force, how many segments of the long end and of the tail touch
    /// each instrument, how much each end bends inside the knot): when a throw loosens, a leg
    /// gathers slack, an end lies on an instrument, or the tail runs straight through the knot.
    #[arg(long, value_name = "S", value_parser = parse_trace_period)]
    knot_trace: Option<f64>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    rerun: RerunArgs,
}

fn parse_seeds(text: &str) -> Result<(u64, u64), String> {
    let (a, b) = text.split_once("..").ok_or_else(|| format!("`{text}` is not A..B"))?;
    let a: u64 = a.trim().parse().map_err(|e| format!("`{a}`: {e}"))?;
    let b: u64 = b.trim().parse().map_err(|e| format!("`{b}`: {e}"))?;
    if b <= a {
        return Err(format!("`{text}`: B must be greater than A"));
    }
    Ok((a, b))
}

#[derive(Serialize)]
struct RunLine {
    seed: u64,
    verdict: &'static str,
    success: bool,
    knot_before: Option<&'static str>,
    knot_after: Option<&'static str>,
    height_m: Option<f64>,
    stitch_distance_m: Option<f64>,
    loop_outside_m: Option<f64>,
    /// The knot as the thread lay when the left let go of it (before it could fall): its type,
    /// height and the thread between the stitch and it.
    knot_at_release: Option<knotlab_sim::evaluate::KnotNow>,
    /// How the long end lay when the left closed on the tail: turns round the left's jaws and round
    /// the right's (a throw wound round the left's only has about none round the right's).
    coils_at_take: Option<knotlab_scenarios::expert::diagnose::CoilsAtTake>,
    gap_before_m: f64,
    gap_after_m: Option<f64>,
    /// How much of each free end the knot drew in during the holding test (a knot that slips lets
    /// one through).
    slid: Option<knotlab_sim::evaluate::Slid>,
    thread_self_crossings: usize,
    /// The first few of them: when (s of the scene's simulated time) and which two segments (needle
    /// end counting from 0), to find the move that forced the thread through itself.
    first_self_crossings: Vec<knotlab_sim::thread_watch::SelfCrossing>,
    /// The suture at its most stretched (its most stretched segment beyond its rest length, a
    /// fraction of it, and when; and how long it was beyond 5 %); not part of the verdict.
    thread_most_stretched: Option<knotlab_sim::thread_watch::Stretch>,
    fault: Option<String>,
    simulated_s: f64,
    wall_s: f64,
    samples: usize,
    demonstration: String,
    events: Vec<String>,
    /// The skill's force events that fired: which instrument, which event, when (s), at what force.
    force_events: Vec<knotlab_scenarios::expert::record::ForceFired>,
}

#[derive(Serialize)]
struct Report {
    scene: String,
    /// The expert's geometry file.
    expert: String,
    human_variation: bool,
    runs: usize,
    successes: usize,
    success_rate: f64,
    results: Vec<RunLine>,
}

fn line(seed: u64, run: &DemoRun, dir: &Path) -> RunLine {
    let e = &run.evaluation;
    RunLine {
        seed,
        verdict: e.verdict.label(),
        success: e.verdict == knotlab_sim::knot::Verdict::Success,
        knot_before: e.knot_before.map(|k| k.name()),
        knot_after: e.knot_after.map(|k| k.name()),
        height_m: e.height_m,
        stitch_distance_m: e.stitch_distance_m,
        loop_outside_m: e.loop_outside_m,
        knot_at_release: run.knot_at_release.clone(),
        coils_at_take: run.coils_at_take.clone(),
        gap_before_m: e.gap_before_m,
        gap_after_m: e.gap_after_m,
        slid: e.slid,
        thread_self_crossings: e.thread_self_crossings,
        first_self_crossings: run.first_self_crossings().to_vec(),
        thread_most_stretched: e.thread_most_stretched,
        fault: run.fault.clone(),
        simulated_s: run.simulated_s,
        wall_s: run.wall_s,
        samples: run.demonstration.instruments.iter().map(|r| r.samples.len()).sum(),
        demonstration: dir.display().to_string(),
        events: run.events.clone(),
        force_events: run.force_events.clone(),
    }
}

pub fn run(args: DemoArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    let (first, end) = args.seeds.unwrap_or((args.seed, args.seed + 1));
    let several = args.seeds.is_some();
    if several && args.rerun.wanted() {
        anyhow::bail!("--rerun/--rerun-connect records one trial: give --seed N, not --seeds");
    }
    if let Some(t) = args.until
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--until {t}: must be a positive number of seconds");
    }
    let recording = args.rerun.open("demo")?;
    let scene = shipped::scene(args.scene.as_deref(), &shipped::SCENE)?;
    let scene_name = shipped::name(args.scene.as_deref(), &shipped::SCENE);
    let options = RecordOptions {
        snapshot_times_s: args.snapshots.clone().unwrap_or_default(),
        cycles_per_sample: 10,
        snapshot_half_width_m: args.snapshot_half_width,
        stop_after_s: args.until,
        knot_trace_every_s: args.knot_trace,
    };
    let geometry = shipped::tie_geometry(args.expert.as_deref())?;
    let mut results = Vec::new();
    for seed in first..end {
        let dir = if several { args.out.join(format!("seed-{seed}")) } else { args.out.clone() };
        let run = rerun_log::record_trial(
            recording.as_ref(),
            |observer| {
                demonstrate_with(
                    scene.clone(),
                    &scene_name,
                    seed,
                    !args.no_variation,
                    &geometry,
                    &options,
                    observer,
                )
            },
            |run| run,
        )?;
        write_demonstration(&dir, &run.demonstration)
            .with_context(|| format!("writing the demonstration to {}", dir.display()))?;
        for snapshot in &run.snapshots {
            let t = snapshot.time_s;
            let path = dir.join(format!("snapshot-{t:.3}s.png"));
            std::fs::write(&path, &snapshot.png).with_context(|| path.display().to_string())?;
            // The thread as `knotlab knot` reads it.
            let path = dir.join(format!("centreline-{t:.3}s.csv"));
            let points = snapshot.centreline_m.iter().map(|p| (p.x, p.y, p.z));
            csv_file::write_rows(&path, &["x_m", "y_m", "z_m"], points)?;
            // Where the thread lies on the instruments.
            let path = dir.join(format!("contacts-{t:.3}s.csv"));
            csv_file::write_rows(&path, &["segment", "link"], &snapshot.contacts)?;
        }
        if args.knot_trace.is_some() {
            write_knot_trace(&dir.join("knot-trace.csv"), &run)?;
        }
        let l = line(seed, &run, &dir);
        if !args.json {
            outln!(
                out,
                "seed {seed}: {} (knot {}, gap {:.2} mm{}), {:.1} s simulated in {:.1} s -> {}",
                l.verdict,
                l.knot_before.unwrap_or("-"),
                l.gap_before_m * 1e3,
                l.fault.as_deref().map(|f| format!(", fault: {f}")).unwrap_or_default(),
                l.simulated_s,
                l.wall_s,
                l.demonstration
            );
        }
        results.push(l);
    }
    rerun_log::finish(recording)?;
    let successes = results.iter().filter(|r| r.success).count();
    let report = Report {
        scene: scene_name,
        expert: shipped::name(args.expert.as_deref(), &shipped::EXPERT),
        human_variation: !args.no_variation,
        runs: results.len(),
        successes,
        success_rate: successes as f64 / results.len().max(1) as f64,
        results,
    };
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&report)?);
    } else {
        outln!(
            out,
            "{} of {} runs tied an accepted knot ({:.0} %)",
            report.successes,
            report.runs,
            100.0 * report.success_rate
        );
    }
    Ok(ExitCode::SUCCESS)
}

/// The knot trace's columns.
const KNOT_TRACE: [&str; 23] = [
    "time_s",
    "knot",
    "height_m",
    "loop_outside_m",
    "radius_m",
    "exit_leg_thread_m",
    "exit_leg_span_m",
    "entry_leg_thread_m",
    "entry_leg_span_m",
    "exit_arc_m",
    "entry_arc_m",
    "wound_gap_m",
    "left_force_n",
    "right_force_n",
    "assist_force_n",
    "long_end_on_left",
    "tail_on_left",
    "long_end_on_right",
    "tail_on_right",
    "long_end_on_assist",
    "tail_on_assist",
    "long_end_bend_rad",
    "tail_bend_rad",
];

/// Writes the run's knot trace as CSV: one row per time, empty fields where there is no knot or leg.
fn write_knot_trace(path: &Path, run: &DemoRun) -> anyhow::Result<()> {
    let opt = |v: Option<f64>| v.map(|v| format!("{v:.5}")).unwrap_or_default();
    let rows = run.knot_trace.iter().map(|p| {
        let k = p.knot.as_ref();
        let leg =
            |l: Option<knotlab_sim::knot::legs::Leg>| [opt(l.map(|l| l.thread_m)), opt(l.map(|l| l.span_m))];
        let [exit_thread, exit_span] = leg(k.and_then(|k| k.exit_leg));
        let [entry_thread, entry_span] = leg(k.and_then(|k| k.entry_leg));
        let mut row = vec![
            format!("{:.3}", p.time_s),
            k.map_or("", |k| k.knot.name()).to_owned(),
            opt(k.and_then(|k| k.height_m)),
            opt(k.and_then(|k| k.loop_outside_m)),
            opt(k.and_then(|k| k.radius_m)),
            exit_thread,
            exit_span,
            entry_thread,
            entry_span,
            opt(p.stitch_arcs_m[0]),
            opt(p.stitch_arcs_m[1]),
            format!("{:.5}", p.wound_gap_m),
            format!("{:.3}", p.force_n[0]),
            format!("{:.3}", p.force_n[1]),
            format!("{:.3}", p.force_n[2]),
        ];
        row.extend(p.ends_on_instruments.iter().flatten().map(|n| n.to_string()));
        row.push(opt(k.and_then(|k| k.bending).map(|b| b.long_end_rad)));
        row.push(opt(k.and_then(|k| k.bending).map(|b| b.tail_rad)));
        row
    });
    csv_file::write_rows(path, &KNOT_TRACE, rows)
}

/// The knot trace's period: more than 0 s.
fn parse_trace_period(text: &str) -> Result<f64, String> {
    let s: f64 = text.parse().map_err(|_| format!("'{text}' is not a number of seconds"))?;
    if s.is_finite() && s > 0.0 {
        Ok(s)
    } else {
        Err(format!("{s} s: the trace's period must be more than 0 s"))
    }
}

/// A snapshot view's half width: more than 0, at most 1 m.
fn parse_half_width(text: &str) -> Result<f64, String> {
    let m: f64 = text.parse().map_err(|_| format!("'{text}' is not a number of metres"))?;
    if m.is_finite() && m > 0.0 && m <= 1.0 {
        Ok(m)
    } else {
        Err(format!("{m} m: a view's half width must be more than 0 and at most 1 m"))
    }
}
