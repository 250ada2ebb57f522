//! `knotlab run`: one trial end to end. The skill learned from the demonstration is synthesized at the
//! (moved) stitch by the chosen method, run by the controller on the simulated rig, and the knot it
//! leaves is evaluated; the verdict and its failure mode are printed. That simulated trial is the
//! skill's preview: with `--rig FILE` naming real devices, the skill is then executed there only if the
//! preview passed (or `--execute-despite-failed-preview` is given); a refusal exits with code 4.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::Args;
use nalgebra::Vector3;

use knotlab_bench::mc::{RunInfo, trial_of_run};
use knotlab_hw::controller::RunOutcome;
use knotlab_hw::gate::{PreviewOutcome, may_execute, real_devices};
use knotlab_hw::rig::Rig;
use knotlab_hw::rig_config::{RigConfig, build_rig, load_rig_config};
use knotlab_hw::skill::Skill;
use knotlab_learner::demonstration::write_demonstration;
use knotlab_learner::synthesis::Method;
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::report::{Execution, TrialReport};
use knotlab_scenarios::trial::{StitchMove, TrialRun, TrialSetup, run_trial};

use super::numbers::parse_vector3;
use super::output::{Output, outln};
use super::skill_source::SkillSource;
use crate::rerun_log::{self, RerunArgs};
use knotlab_scenarios::shipped;

/// The exit code of a skill refused by a failed preview (1 is an error, 2 a bad command line).
const REFUSED: u8 = 4;

#[derive(Debug, Args)]
pub struct RunArgs {
    #[command(flatten)]
    source: SkillSource,
    /// The scene file [default: the shipped scenarios/default.toml, built in].
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Seeds the trial's random draws (sensor noise).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// How the skill is carried to the stitch: fluid, dmp or replay.
    #[arg(long, default_value = "fluid")]
    method: Method,
    /// Runs trial `--trial` of this Monte Carlo run directory (`knotlab mc --out DIR`) alone: its draw,
    /// its scene and preset (give `--scene` if the run's scene file is not where run.json names it), the
    /// skill it played (give the same `--skill`/`--demo`), stopped where its trials stopped.
    #[arg(long, value_name = "DIR", requires = "trial", conflicts_with_all = ["seed", "stitch_offset", "stitch_rotate", "stitch_tilt", "until"])]
    from_mc: Option<PathBuf>,
    /// The trial of `--from-mc` to run.
    #[arg(long, requires = "from_mc")]
    trial: Option<u64>,
    /// Moves the stitch (the tissue) by this much, world frame, m: `dx,dy,dz`.
    #[arg(long, value_parser = parse_vector3, allow_hyphen_values = true)]
    stitch_offset: Option<Vector3<f64>>,
    /// Turns the stitch (the tissue) about its normal by this much, degrees.
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    stitch_rotate: f64,
    /// Tilts the tissue about the wound by this much, degrees (a wound on a sloped surface; the
    /// tail's flap raised for a positive tilt). With the scene's own tilt at most 45.
    #[arg(long, allow_hyphen_values = true, default_value_t = 0.0)]
    stitch_tilt: f64,
    /// Stop at this time (s from the start) and evaluate what is there (a short trial, to debug).
    #[arg(long, value_name = "S")]
    until: Option<f64>,
    /// The rig to execute on after the preview (a rig config, e.g. scenarios/rigs/melfa.toml, which
    /// `knotlab shipped dump` writes out). Without it, or for a rig of simulated and dummy devices, the
    /// simulated trial is all there is.
    #[arg(long)]
    rig: Option<PathBuf>,
    /// Execute on a rig's real devices even though the preview in the simulator failed.
    #[arg(long)]
    execute_despite_failed_preview: bool,
    /// Also write what the devices read during the trial as a demonstration directory here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    rerun: RerunArgs,
}

/// The synthesized skill for the Rerun viewer: each instrument's planned tip path
/// (`instruments/<arm>/planned`) and the fluid's regenerations of the 2D primitives
/// (`fluid/<primitive>/...`, the particle on the trial's clock).
#[cfg(feature = "rerun")]
fn log_synthesis(recording: Option<&rerun_log::Recording>, trial: &TrialRun) -> anyhow::Result<()> {
    let Some(rec) = recording else { return Ok(()) };
    for track in &trial.skill.tracks {
        let points: Vec<[f32; 3]> =
            track.poses.iter().map(|k| k.world_position_m.map(|x| x as f32)).collect();
        rec.log_static(
            format!("instruments/{}/planned", track.arm),
            &rerun_log::sdk::LineStrips3D::new([points]),
        )?;
    }
    for (name, inst, start_s) in &trial.fluid {
        rerun_log::log_instantiation(rec, inst, &format!("fluid/{name}"), *start_s)?;
    }
    Ok(())
}

#[cfg(not(feature = "rerun"))]
fn log_synthesis(_: Option<&rerun_log::Recording>, _: &TrialRun) -> anyhow::Result<()> {
    Ok(())
}

/// Runs `skill` on the devices of the rig config `path` (the shipped robot model).
fn execute_on_rig(config: &RigConfig, skill: Skill) -> anyhow::Result<&'static str> {
    let rig = Rig::shipped().context("the shipped rig")?;
    let (mut controller, _handles) = build_rig(config, &rig, None)?.into_controller()?;
    controller.load_skill(skill)?;
    let summary = controller.run_to_end(|_| {});
    let shutdown = controller.shutdown();
    let summary = summary?;
    shutdown?;
    Ok(match summary.outcome {
        RunOutcome::Completed => "completed",
        RunOutcome::EmergencyStopped => "emergency_stopped",
    })
}

/// The trial the command line asks for: the scene (shipped or `--scene`) with its stitch moved by
/// `--stitch-*`, seeded by `--seed`.
fn moved_setup(args: &RunArgs) -> anyhow::Result<TrialSetup> {
    let scene_name = shipped::name(args.scene.as_deref(), &shipped::SCENE);
    let scene = shipped::scene(args.scene.as_deref(), &shipped::SCENE)?;
    let tilt_deg = scene.tissue.tilt_rad.to_degrees() + args.stitch_tilt;
    let most_deg = knotlab_sim::scene::MAX_TILT_RAD.to_degrees();
    if !(tilt_deg.is_finite() && tilt_deg.abs() <= most_deg) {
        anyhow::bail!(
            "--stitch-tilt {}: with the scene's tilt ({} degrees) the tissue would tilt {tilt_deg} degrees; at most {most_deg} either way",
            args.stitch_tilt,
            scene.tissue.tilt_rad.to_degrees()
        );
    }
    Ok(TrialSetup {
        scene,
        scene_name: scene_name.clone(),
        seed: args.seed,
        stitch: StitchMove {
            offset_m: args.stitch_offset.unwrap_or_else(Vector3::zeros),
            rotate_rad: args.stitch_rotate.to_radians(),
            tilt_rad: args.stitch_tilt.to_radians(),
        },
        method: args.method,
        offsets: Vec::new(),
    })
}

/// Trial `trial` of the Monte Carlo run in `dir`, its scene read from `scene` if given, else from where
/// its run.json names it (the shipped scene by its name).
fn mc_trial(
    dir: &std::path::Path,
    scene: Option<&std::path::Path>,
    learned: &knotlab_scenarios::trial::Learned,
    trial: u64,
    method: Method,
) -> anyhow::Result<(TrialSetup, knotlab_bench::mc::Draw, Option<f64>)> {
    let info = RunInfo::read(dir)?
        .with_context(|| format!("{}: no such file: not a Monte Carlo run", RunInfo::path(dir).display()))?;
    let named = PathBuf::from(&info.scene);
    let path = match scene {
        Some(path) => Some(path),
        None if info.scene == shipped::SCENE.path => None,
        None => Some(named.as_path()),
    };
    let scene = shipped::scene(path, &shipped::SCENE)?;
    Ok(trial_of_run(dir, &scene, learned, trial, method)?)
}

pub fn run(args: RunArgs, out: &mut Output) -> anyhow::Result<ExitCode> {
    if !args.stitch_rotate.is_finite() {
        anyhow::bail!("--stitch-rotate {}: not a number of degrees", args.stitch_rotate);
    }
    if let Some(t) = args.until
        && !(t.is_finite() && t > 0.0)
    {
        anyhow::bail!("--until {t}: must be a positive number of seconds");
    }
    // The rig config is read before the trial runs: a bad one is reported at once, not after it.
    let rig_config = args.rig.as_ref().map(|path| load_rig_config(path)).transpose()?;
    let learned = args.source.learned()?;
    let (setup, until) = match (&args.from_mc, args.trial) {
        (Some(dir), Some(trial)) => {
            let (setup, _, until) = mc_trial(dir, args.scene.as_deref(), &learned, trial, args.method)?;
            (setup, until)
        }
        _ => (moved_setup(&args)?, args.until),
    };
    let options = RecordOptions { cycles_per_sample: 10, stop_after_s: until, ..RecordOptions::default() };
    let recording = args.rerun.open("run")?;
    let trial = rerun_log::record_trial(
        recording.as_ref(),
        |observer| run_trial(&learned, &setup, &options, observer),
        |trial| &trial.run,
    )?;
    log_synthesis(recording.as_ref(), &trial)?;
    rerun_log::finish(recording)?;
    if let Some(dir) = &args.out {
        write_demonstration(dir, &trial.run.demonstration)
            .with_context(|| format!("writing the trial's recording to {}", dir.display()))?;
    }
    let simulated = TrialReport::new(&setup, &trial, Execution::simulated());
    let preview = &simulated.preview;
    let mut code = ExitCode::SUCCESS;
    let execution = match (&args.rig, rig_config) {
        (None, _) | (_, None) => Execution::simulated(),
        (Some(path), Some(config)) => {
            let rig_name = Some(path.display().to_string());
            if real_devices(&config).is_empty() {
                Execution { status: "simulated".into(), rig: rig_name, message: "no real devices".into() }
            } else {
                let outcome = PreviewOutcome { passed: preview.passed, reason: preview.reason.clone() };
                match may_execute(&config, &outcome, args.execute_despite_failed_preview) {
                    Err(refused) => {
                        out.error(format!(
                            "{}: {refused} (--execute-despite-failed-preview)",
                            path.display()
                        ));
                        code = ExitCode::from(REFUSED);
                        Execution { status: "refused".into(), rig: rig_name, message: refused.to_string() }
                    }
                    Ok(()) => {
                        let status = execute_on_rig(&config, trial.skill.clone())
                            .with_context(|| format!("executing on {}", path.display()))?;
                        Execution { status: status.into(), rig: rig_name, message: String::new() }
                    }
                }
            }
        }
    };
    let report = TrialReport { execution, ..simulated };
    if args.json {
        outln!(out, "{}", serde_json::to_string_pretty(&report)?);
    } else {
        outln!(
            out,
            "{} ({}): knot {}, wound gap {:.2} mm{}; {:.1} s simulated in {:.1} s",
            report.verdict,
            report.method,
            report.knot.as_deref().unwrap_or("-"),
            report.wound_gap_m * 1e3,
            report.fault.as_deref().map(|f| format!(", fault: {f}")).unwrap_or_default(),
            report.sim_seconds,
            report.wall_seconds
        );
    }
    Ok(code)
}
