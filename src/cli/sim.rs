//! `knotlab sim`: runs the scene's scripted stress sequence headless and prints what the thread did;
//! optionally draws the scene at given times. The sequence measures the capsule chain (its joints'
//! stretch, segments tunnelling through each other and the shafts): a scene whose suture is the rope
//! is refused.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;

use knotlab_hw::rig::Rig;
use knotlab_scenarios::stress::run_stress;
use knotlab_sim::snapshot::{View, render_png};
use knotlab_sim::world::SimWorld;

use super::numbers::{Numbers, parse_list};
use super::output::{Output, outln};
use knotlab_scenarios::shipped;

#[derive(Debug, Args)]
pub struct SimArgs {
    /// The scene file (its suture the capsule chain: the nominal scene's rope has no joints to
    /// stretch) [default: the shipped scenarios/chain.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Simulated seconds of the stress sequence (its moves scale with it).
    #[arg(long, default_value_t = 6.0)]
    seconds: f64,
    /// Seed of the sensor noise.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Draw the scene (top, front and side views) into this PNG file; with several --at times, the
    /// time is added to the name (`snap.png` becomes `snap-1.500s.png`).
    #[arg(long)]
    snapshot: Option<PathBuf>,
    /// Simulated times of the snapshots, s (comma-separated); default: the end.
    #[arg(long, value_parser = parse_list, requires = "snapshot")]
    at: Option<Numbers>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

fn snapshot_path(base: &Path, time_s: f64, several: bool) -> PathBuf {
    if !several {
        return base.to_path_buf();
    }
    let stem = base.file_stem().map_or_else(|| "snapshot".to_owned(), |s| s.to_string_lossy().into_owned());
    base.with_file_name(format!("{stem}-{time_s:.3}s.png"))
}

pub fn run(args: SimArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if !(args.seconds.is_finite() && args.seconds > 0.0 && args.seconds <= 3600.0) {
        anyhow::bail!("--seconds: must be within 0..3600, got {}", args.seconds);
    }
    let scene_name = shipped::name(args.scene.as_deref(), &shipped::CHAIN_SCENE);
    let scene = shipped::scene(args.scene.as_deref(), &shipped::CHAIN_SCENE)?;
    let rig = Rig::shipped().context("the shipped rig")?;
    let mut world = SimWorld::new(scene, rig).with_context(|| scene_name.clone())?;
    world.reseed(args.seed);
    let times = match (&args.snapshot, &args.at) {
        (Some(_), Some(times)) => times.clone(),
        (Some(_), None) => vec![args.seconds],
        _ => Vec::new(),
    };
    if let Some(bad) = times.iter().find(|t| !(t.is_finite() && **t >= 0.0 && **t <= args.seconds)) {
        anyhow::bail!("--at: {bad} s is outside the run (0..{} s)", args.seconds);
    }
    let several = times.len() > 1;
    let mut written = Vec::new();
    let mut failed = None;
    let report = run_stress(&mut world, args.seconds, &times, &mut |time_s, w| {
        let Some(base) = &args.snapshot else { return };
        let path = snapshot_path(base, time_s, several);
        let result = render_png(w, &View::around_wound(w)).map_err(anyhow::Error::from).and_then(|png| {
            std::fs::write(&path, png).with_context(|| format!("writing {}", path.display()))
        });
        match result {
            Ok(()) => written.push(path.display().to_string()),
            Err(e) => failed = Some(e),
        }
    });
    if let Some(e) = failed {
        return Err(e);
    }
    if args.json {
        let mut value = serde_json::to_value(&report).context("report as JSON")?;
        if let Some(map) = value.as_object_mut() {
            map.insert("scene".into(), scene_name.clone().into());
            map.insert("snapshots".into(), written.clone().into());
        }
        out.line(serde_json::to_string_pretty(&value).context("writing JSON")?);
    } else {
        outln!(
            out,
            "scene {} ({} bodies), {} steps, {:.2} s simulated in {:.2} s: {:.2}x real time",
            scene_name,
            report.bodies,
            report.steps,
            report.simulated_s,
            report.wall_s,
            report.realtime_factor
        );
        outln!(out, "max stretch {:.3} % of a segment", 100.0 * report.max_stretch_ratio);
        outln!(
            out,
            "tunnelling events {} (through a shaft {})",
            report.tunnelling_events,
            report.shaft_tunnelling_events
        );
        outln!(
            out,
            "NaN or exploding bodies {}{}",
            report.nan_events,
            report.failure.as_ref().map_or_else(String::new, |f| format!(": {f}"))
        );
        outln!(
            out,
            "pulled through the stitch {:.1} mm; wound gap {:.2} -> {:.2} mm; grasp slips {}; unreachable targets {}",
            1e3 * report.pulled_through_m,
            1e3 * report.wound_gap_m[0],
            1e3 * report.wound_gap_m[1],
            report.slips,
            report.unreachable_targets
        );
        for path in &written {
            outln!(out, "snapshot {path}");
        }
    }
    Ok(if report.nan_events == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}
