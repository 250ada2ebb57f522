//! `knotlab knot`: which knot a thread's centreline holds, where it sits, whether it is down; and which
//! knot a draw of the tail back through the left's jaws would make (`draw-through`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Subcommand, ValueEnum};
use nalgebra::Vector3;
use serde::Serialize;

use knotlab_hw::rig::ArmName;
use knotlab_learner::demonstration::load_demonstration;
use knotlab_sim::knot::{
    Classification, DownLimits, KnotPlacement, KnotType, TissueSurface, classify, drawn_through, read_points,
};

use super::numbers::parse_vector3;
use super::output::{Output, outln};

#[derive(Debug, Subcommand)]
pub enum KnotCommand {
    /// Classify the knot in a centreline file: CSV, `x,y,z` per line in metres, needle end first; a
    /// header line, blank lines and `#` comments allowed. Exits 1 on a bad file.
    Classify {
        /// The centreline CSV file.
        file: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// A point x,y,z on the tissue surface (m); with --tissue-normal and --stitch, says whether
        /// the knot is down.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, requires_all = ["tissue_normal", "stitch"])]
        tissue_point: Option<Vector3<f64>>,
        /// The tissue surface's outward normal x,y,z.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, requires_all = ["tissue_point", "stitch"])]
        tissue_normal: Option<Vector3<f64>>,
        /// The stitch point x,y,z (m), where the knot should sit.
        #[arg(long, allow_hyphen_values = true, value_parser = parse_vector3, requires_all = ["tissue_point", "tissue_normal"])]
        stitch: Option<Vector3<f64>>,
    },
    /// Which knot the thread of a `knotlab demo --snapshots` run would hold if the left (or the arm
    /// given) drew the tail straight back along its jaws from where it holds it, the rest of the tail
    /// following: a throw checked before any physics. Reads DIR/centreline-T.csv (T as written,
    /// three decimals) and the arm's pose at T from the demonstration in DIR.
    DrawThrough {
        /// The run's directory (a demonstration with snapshots).
        dir: PathBuf,
        /// The snapshot's time, s.
        #[arg(long)]
        at: f64,
        /// The tail segment the arm holds (the `segment` of its `Grasped` event); the tail is
        /// replaced from this segment's first point on.
        #[arg(long)]
        grip: usize,
        /// The arm whose jaws draw the tail (the assist, for a second throw wound on its jaws).
        #[arg(long, value_enum, default_value_t = DrawingArm::Left)]
        arm: DrawingArm,
        /// How far back along the jaws the tail is drawn, m.
        #[arg(long, default_value_t = 0.045)]
        length_m: f64,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

pub fn run(command: KnotCommand, out: &mut Output) -> anyhow::Result<ExitCode> {
    match command {
        KnotCommand::Classify { file, json, tissue_point, tissue_normal, stitch } => {
            let site = match (tissue_point, tissue_normal, stitch) {
                (Some(point), Some(normal), Some(stitch)) => {
                    Some((TissueSurface::new(point, normal).context("--tissue-normal")?, stitch))
                }
                _ => None,
            };
            match report(&file, site) {
                Ok(report) => {
                    print(&report, json, out)?;
                    Ok(ExitCode::SUCCESS)
                }
                Err(error) if json => {
                    let text = format!("{error:#}");
                    print_json(
                        out,
                        &serde_json::json!({ "ok": false, "file": file.display().to_string(), "error": text }),
                    )?;
                    Ok(ExitCode::FAILURE)
                }
                Err(error) => Err(error),
            }
        }
        KnotCommand::DrawThrough { dir, at, grip, arm, length_m, json } => {
            let report = draw_through_report(&dir, at, grip, arm, length_m)?;
            if json {
                print_json(out, &report)?;
            } else {
                outln!(
                    out,
                    "{} at {:.3} s: {} as it lies; {} ({}, writhe {:+}) with the tail drawn {:.3} m back along the {}'s jaws from point {}",
                    report.dir,
                    report.at_s,
                    report.as_it_lies,
                    report.drawn_through,
                    report
                        .drawn_determinant
                        .map_or("determinant unknown".to_string(), |d| format!("determinant {d}")),
                    report.drawn_writhe,
                    report.length_m,
                    report.arm,
                    report.grip
                );
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}

#[derive(Serialize)]
struct DrawThroughReport {
    dir: String,
    at_s: f64,
    grip: usize,
    arm: String,
    length_m: f64,
    as_it_lies: KnotType,
    drawn_through: KnotType,
    drawn_determinant: Option<u64>,
    drawn_writhe: i32,
}

/// The arms that take the tail and draw it through a turn on their jaws.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum DrawingArm {
    Left,
    Assist,
}

impl DrawingArm {
    fn arm(self) -> ArmName {
        match self {
            DrawingArm::Left => ArmName::Left,
            DrawingArm::Assist => ArmName::Assist,
        }
    }
}

fn draw_through_report(
    dir: &Path,
    at_s: f64,
    grip: usize,
    arm: DrawingArm,
    length_m: f64,
) -> anyhow::Result<DrawThroughReport> {
    let file = dir.join(format!("centreline-{at_s:.3}s.csv"));
    let points = read_points(&file)?;
    let demo = load_demonstration(dir).with_context(|| format!("{}", dir.display()))?;
    let name = arm.arm();
    let instrument = demo
        .instrument(name)
        .with_context(|| format!("{}: no {name} instrument in the demonstration", dir.display()))?;
    let sample = instrument
        .sample_nearest(at_s)
        .with_context(|| format!("{}: the {name} has no sample near {at_s} s", dir.display()))?;
    let jaws = sample.world_from_tip() * Vector3::z_axis();
    let drawn = drawn_through(&points, grip, &sample.position_m, &jaws, length_m, 0.003)
        .with_context(|| format!("{}: --grip/--length-m", file.display()))?;
    let as_it_lies = classify(&points).with_context(|| file.display().to_string())?;
    let through = classify(&drawn).with_context(|| format!("{} drawn through", file.display()))?;
    Ok(DrawThroughReport {
        dir: dir.display().to_string(),
        at_s,
        grip,
        arm: name.to_string(),
        length_m,
        as_it_lies: as_it_lies.knot,
        drawn_through: through.knot,
        drawn_determinant: through.determinant,
        drawn_writhe: through.writhe,
    })
}

#[derive(Serialize)]
struct VoteReport {
    direction: [f64; 3],
    knot: KnotType,
    determinant: Option<u64>,
    writhe: i32,
    crossings: usize,
    raw_crossings: usize,
    searched: bool,
}

#[derive(Serialize)]
struct SpanReport {
    /// Arc length from the needle end to the first and last crossing, m.
    start_m: f64,
    end_m: f64,
    thread_length_m: f64,
    centre_m: [f64; 3],
    radius_m: f64,
}

#[derive(Serialize)]
struct PlacementReport {
    down: bool,
    height_m: f64,
    top_height_m: f64,
    stitch_distance_m: f64,
    centre_stitch_distance_m: f64,
    max_height_m: f64,
    max_stitch_distance_m: f64,
}

#[derive(Serialize)]
struct ClassifyReport {
    ok: bool,
    file: String,
    points: usize,
    knot: KnotType,
    determinant: Option<u64>,
    writhe: i32,
    crossings: usize,
    /// Whether the representative direction's picture was searched and reduced.
    searched: bool,
    agreement: f64,
    directions: Vec<VoteReport>,
    span: Option<SpanReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    placement: Option<PlacementReport>,
}

fn report(file: &Path, site: Option<(TissueSurface, Vector3<f64>)>) -> anyhow::Result<ClassifyReport> {
    let points = read_points(file)?;
    let c: Classification = classify(&points).with_context(|| file.display().to_string())?;
    let limits = DownLimits::default();
    let placement = match (&c.span, site) {
        (Some(span), Some((surface, stitch))) => {
            let p = KnotPlacement::measure(span, &surface, &stitch);
            Some(PlacementReport {
                down: p.is_down(&limits),
                height_m: p.height_m,
                top_height_m: p.top_height_m,
                stitch_distance_m: p.stitch_distance_m,
                centre_stitch_distance_m: p.centre_stitch_distance_m,
                max_height_m: limits.max_height_m,
                max_stitch_distance_m: limits.max_stitch_distance_m,
            })
        }
        _ => None,
    };
    Ok(ClassifyReport {
        ok: true,
        file: file.display().to_string(),
        points: points.len(),
        knot: c.knot,
        determinant: c.determinant,
        writhe: c.writhe,
        crossings: c.crossings,
        searched: c.votes[c.representative].searched,
        agreement: c.agreement,
        directions: c
            .votes
            .iter()
            .map(|v| VoteReport {
                direction: v.direction,
                knot: v.knot,
                determinant: v.determinant,
                writhe: v.writhe,
                crossings: v.crossings,
                raw_crossings: v.raw_crossings,
                searched: v.searched,
            })
            .collect(),
        span: c.span.as_ref().map(|s| SpanReport {
            start_m: s.start_m,
            end_m: s.end_m,
            thread_length_m: s.thread_length_m,
            centre_m: [s.centre_m.x, s.centre_m.y, s.centre_m.z],
            radius_m: s.radius_m,
        }),
        placement,
    })
}

fn print_json<T: Serialize>(out: &mut Output, value: &T) -> anyhow::Result<()> {
    out.line(serde_json::to_string_pretty(value).context("writing JSON")?);
    Ok(())
}

fn print(r: &ClassifyReport, json: bool, out: &mut Output) -> anyhow::Result<()> {
    if json {
        return print_json(out, r);
    }
    let det = r.determinant.map_or_else(|| "too large".to_owned(), |d| d.to_string());
    let agree = r.directions.iter().filter(|v| v.knot == r.knot).count();
    if !r.searched {
        outln!(
            out,
            "{}: {} (too tangled to reduce: over {} crossings, or over {} pairs of segments to look at, in a picture); {agree} of {} directions agree",
            r.file,
            r.knot,
            knotlab_sim::knot::crossings::MAX_CROSSINGS,
            knotlab_sim::knot::crossings::MAX_PAIR_TESTS,
            r.directions.len()
        );
    } else {
        outln!(
            out,
            "{}: {} ({} crossings after reduction, determinant {det}, writhe {:+}); {agree} of {} directions agree",
            r.file,
            r.knot,
            r.crossings,
            r.writhe,
            r.directions.len()
        );
    }
    match &r.span {
        Some(s) => {
            let [x, y, z] = s.centre_m;
            outln!(
                out,
                "knot from {:.4} m to {:.4} m along the {:.4} m thread (from the needle end), centre ({x:.4}, {y:.4}, {z:.4}) m, radius {:.4} m",
                s.start_m,
                s.end_m,
                s.thread_length_m,
                s.radius_m
            );
        }
        None if r.knot == KnotType::Unknot => outln!(out, "{} points, no knot", r.points),
        None => outln!(out, "{} points, the knot not located", r.points),
    }
    if let Some(p) = &r.placement {
        outln!(
            out,
            "{}: lowest crossing {:.4} m above the tissue (limit {:.4}), nearest {:.4} m from the stitch (limit {:.4})",
            if p.down { "down" } else { "not down" },
            p.height_m,
            p.max_height_m,
            p.stitch_distance_m,
            p.max_stitch_distance_m
        );
    }
    Ok(())
}
