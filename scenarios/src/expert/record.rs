//! Recording a demonstration: the controller runs the expert's skill on the simulated rig (the device
//! traits, as on the robots), and every 10th cycle (100 Hz at the scene's 1 ms step) what the devices
//! read is kept: tip pose, jaw angle, grasp state and force, per instrument. Then the knot the thread
//! holds is evaluated.

use std::time::Instant;

use super::diagnose::CoilsAtTake;
use knotlab_hw::controller::{ControllerError, CycleRecord, Status};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::{RigBuildError, RigConfig, build_rig};
use knotlab_hw::skill::Skill;
use knotlab_learner::demonstration::{
    Demonstration, FORMAT_VERSION, GraspState, InstrumentRecord, Metadata, Sample, StitchPose,
};
use knotlab_sim::backend::SimBackend;
use knotlab_sim::evaluate::{KnotEvaluation, KnotNow, evaluate_knot_watched, fault_evaluation, knot_now};
use knotlab_sim::shapes::{SceneShapes, scene_shapes};
use knotlab_sim::snapshot::{View, render_png};
use knotlab_sim::thread_watch::SelfCrossing;
use knotlab_sim::tissue::Flap;
use knotlab_sim::world::SimWorld;
use nalgebra::UnitQuaternion;

/// Why a recording could not be made (a knot that was not tied is a verdict, not an error).
#[derive(Debug, thiserror::Error)]
pub enum RecordError {
    /// The rig config does not build on the scene.
    #[error("the rig does not build on the scene")]
    Rig(#[from] RigBuildError),
    /// The controller refused the skill or could not start.
    #[error("the controller")]
    Controller(#[from] ControllerError),
}

/// What recording options ask for besides the demonstration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RecordOptions {
    /// Draw the scene at these times (from the recording's start), s.
    pub snapshot_times_s: Vec<f64>,
    /// Cycles between samples (10: 100 Hz at a 1 ms step).
    pub cycles_per_sample: u64,
    /// Half the width of each snapshot view, m (0: the default 8 cm).
    pub snapshot_half_width_m: f64,
    /// Stop at this time (from the recording's start, s) and evaluate what is there (a short trial, to
    /// debug).
    pub stop_after_s: Option<f64>,
    /// Take the knot as the thread lies ([`knot_now`]) every this many seconds of the skill (not the
    /// holding test after it) into [`DemoRun::knot_trace`] (none: no trace), to see when a throw
    /// loosens or a leg gathers slack.
    pub knot_trace_every_s: Option<f64>,
}

/// The knot and the gauges at one time of a run ([`RecordOptions::knot_trace_every_s`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct KnotTracePoint {
    /// Time from the recording's start, s.
    pub time_s: f64,
    /// The knot as the thread lies (none where the centreline or the tissue is degenerate).
    pub knot: Option<KnotNow>,
    /// The wound's gap between the flaps' inner faces, m.
    pub wound_gap_m: f64,
    /// The thread's arc length from the needle end at the stitch's exit and entry points, m: how the
    /// thread moves through the tissue.
    pub stitch_arcs_m: [Option<f64>; 2],
    /// What the left, right and assist instruments' gauges read, N (magnitudes, world frame).
    pub force_n: [f64; 3],
    /// How many segments of the long end (from the needle to the stitch's exit) and of the tail (from
    /// the stitch's entry to its free end) touch each of the left's, right's and assist's links, [long
    /// end, tail] each: turns lying on the jaws, or an end draped over an instrument's shaft.
    pub ends_on_instruments: [[usize; 2]; 3],
}

/// [`KnotTracePoint::ends_on_instruments`] for the world as it is, the stitch's points at `arcs_m`
/// (exit, entry) along the thread: none of an end while the thread is not through its point.
fn ends_on_instruments(world: &SimWorld, arcs_m: [Option<f64>; 2]) -> [[usize; 2]; 3] {
    let segment_m = world.suture().spacing_m();
    let contacts = world.thread_contacts();
    [ArmName::Left, ArmName::Right, ArmName::Assist].map(|arm| {
        let prefix = format!("{}_", arm.as_str());
        let on_arm = |keep: &dyn Fn(f64) -> bool| {
            let mut segments: Vec<usize> = contacts
                .iter()
                .filter(|(i, link)| link.starts_with(&prefix) && keep(segment_m * (*i as f64 + 0.5)))
                .map(|(i, _)| *i)
                .collect();
            segments.dedup();
            segments.len()
        };
        let [exit, entry] = arcs_m;
        [
            exit.map_or(0, |exit_m| on_arm(&|arc_m| arc_m < exit_m)),
            entry.map_or(0, |entry_m| on_arm(&|arc_m| arc_m > entry_m)),
        ]
    })
}

fn view(world: &SimWorld, options: &RecordOptions) -> View {
    if options.snapshot_half_width_m > 0.0 {
        View::around_wound_of_width(world, options.snapshot_half_width_m)
    } else {
        View::around_wound(world)
    }
}

/// The scene at one asked time.
pub struct Snapshot {
    /// Skill time, s.
    pub time_s: f64,
    /// Top, front and side views as a PNG picture.
    pub png: Vec<u8>,
    /// The thread's centreline, needle end first, world frame, m.
    pub centreline_m: Vec<nalgebra::Vector3<f64>>,
    /// Which thread segments touch which robot links ([`SimWorld::thread_contacts`]).
    pub contacts: Vec<(usize, String)>,
}

fn snapshot(world: &SimWorld, options: &RecordOptions, time_s: f64) -> Option<Snapshot> {
    let png = render_png(world, &view(world, options)).ok()?;
    Some(Snapshot { time_s, png, centreline_m: world.thread_centreline(), contacts: world.thread_contacts() })
}

/// How many of a run's self-crossings its reports list ([`DemoRun::first_self_crossings`]).
pub const LISTED_SELF_CROSSINGS: usize = 10;

/// One recorded run.
pub struct DemoRun {
    /// What the devices read.
    pub demonstration: Demonstration,
    /// The knot the run left.
    pub evaluation: KnotEvaluation,
    /// The knot as the thread lay in the cycle the left instrument let go of it, after holding it
    /// (the instrument tie's final release): where the pulls cinched it, before it could fall.
    pub knot_at_release: Option<KnotNow>,
    /// How the long end lay round the instruments when the left first closed on the thread.
    pub coils_at_take: Option<CoilsAtTake>,
    /// Why the controller stopped early, if it did.
    pub fault: Option<String>,
    /// Simulated time of the skill, s.
    pub simulated_s: f64,
    /// Wall-clock time, s.
    pub wall_s: f64,
    /// The scene at the asked times.
    pub snapshots: Vec<Snapshot>,
    /// Every time the thread passed through itself, in order (the evaluation counts them).
    pub self_crossings: Vec<SelfCrossing>,
    /// The scene's grasp events (grasped, released, slipped) in order, as text.
    pub events: Vec<String>,
    /// The skill's force events that fired (a pull stopping at its set force, say), in order.
    pub force_events: Vec<ForceFired>,
    /// The scene at the end, after the knot's holding test.
    pub final_scene: SceneShapes,
    /// The knot every [`RecordOptions::knot_trace_every_s`], in time order (empty when not asked).
    pub knot_trace: Vec<KnotTracePoint>,
}

/// A force event of the skill that fired.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ForceFired {
    /// The instrument (`left`, `right`, `assist`).
    pub arm: &'static str,
    /// The event's name in the skill.
    pub name: String,
    /// When, s from the start of the recording.
    pub time_s: f64,
    /// The force the gauges read, N.
    pub force_n: f64,
}

/// The events `controller` fired during `skill`, which started `start_s` into the recording.
fn fired_in(controller: &knotlab_hw::controller::Controller, skill: &Skill, start_s: f64) -> Vec<ForceFired> {
    controller
        .fired_events()
        .iter()
        .map(|f| ForceFired {
            arm: f.arm.as_str(),
            name: skill
                .track(f.arm)
                .and_then(|t| t.events.get(f.event))
                .map_or_else(String::new, |e| e.name.clone()),
            time_s: start_s + f.time_s,
            force_n: f.force_n,
        })
        .collect()
}

impl DemoRun {
    /// The first [`LISTED_SELF_CROSSINGS`] times the thread passed through itself: when and which two
    /// segments, to find the move that forced them.
    pub fn first_self_crossings(&self) -> &[SelfCrossing] {
        &self.self_crossings[..self.self_crossings.len().min(LISTED_SELF_CROSSINGS)]
    }
}

fn grasp_state(world: &SimWorld, arm: ArmName) -> GraspState {
    let a = world.arm(arm);
    if a.holds() {
        GraspState::Holding
    } else if a.actual().tool.jaw_rad < world.jaw_closed_rad() {
        GraspState::ClosedEmpty
    } else {
        GraspState::Open
    }
}

/// The instruments a demonstration records, each with no samples yet.
pub fn empty_records() -> Vec<InstrumentRecord> {
    [ArmName::Left, ArmName::Right, ArmName::Assist]
        .iter()
        .map(|&instrument| InstrumentRecord { instrument, samples: Vec::new() })
        .collect()
}

/// Appends what the devices read this cycle (tip pose, jaw, grasp, force) to each instrument's record.
pub fn sample_instruments(record: &CycleRecord, world: &SimWorld, records: &mut [InstrumentRecord]) {
    for r in records {
        let Some(a) = record.arm(r.instrument) else { continue };
        let q = UnitQuaternion::from_rotation_matrix(&a.world_from_tip.rotation);
        r.samples.push(Sample {
            time_s: record.time_s,
            position_m: a.world_from_tip.translation.vector,
            quaternion_xyzw: [q.i, q.j, q.k, q.w],
            jaw_rad: a.measured.tool.jaw_rad,
            grasp: grasp_state(world, r.instrument),
            force_n: a.world_force_n,
        });
    }
}

/// Sees every control cycle's record and the scene after it (for debugging, logging, diagnostics).
pub type CycleObserver<'a> = dyn FnMut(&CycleRecord, &SimWorld) + 'a;

/// Plans the skill that follows the one just finished, from the world it left (`None`: no more).
pub type NextSkill<'a> = dyn FnMut(&SimWorld) -> Option<Skill> + 'a;

/// Runs `skill` on `world` through the rig `config` and records it; `observer`, if any, sees every
/// cycle. When a skill finishes, `next`, if any, may give another to run on (one recording).
#[allow(clippy::too_many_arguments)]
pub fn record_demonstration(
    world: SimWorld,
    rig: &Rig,
    config: &RigConfig,
    skill: Skill,
    metadata: Metadata,
    options: &RecordOptions,
    mut observer: Option<&mut CycleObserver<'_>>,
    mut next: Option<&mut NextSkill<'_>>,
) -> Result<DemoRun, RecordError> {
    let started = Instant::now();
    let mut backend = SimBackend::new(world);
    let (mut controller, _handles) = build_rig(config, rig, Some(&mut backend))?.into_controller()?;
    let mut running = skill.clone();
    controller.load_skill(skill)?;
    let (mut force_events, mut skill_start_s) = (Vec::new(), 0.0);
    let mut records = empty_records();
    let every = options.cycles_per_sample.max(1);
    let mut snapshot_times = options.snapshot_times_s.clone();
    snapshot_times.sort_by(f64::total_cmp);
    let mut snapshots = Vec::new();
    let mut fault = None;
    let (mut left_held, mut knot_at_release, mut coils_at_take) = (false, None, None);
    let mut knot_trace = Vec::new();
    let mut next_trace_s = 0.0;
    loop {
        let record = match controller.step() {
            Ok(record) => record.clone(),
            Err(error) => {
                fault = Some(error.to_string());
                break;
            }
        };
        let world = backend.world();
        if let Some(observe) = observer.as_mut() {
            observe(&record, &world);
        }
        // The knot as the left last lets go of the tail.
        let left_holds = world.arm(ArmName::Left).holds();
        if left_held && !left_holds {
            knot_at_release = Some(knot_now(&world));
        }
        if !left_held && left_holds && coils_at_take.is_none() {
            coils_at_take = Some(CoilsAtTake::now(&world, record.time_s));
        }
        left_held = left_holds;
        if let Some(every_s) = options.knot_trace_every_s.filter(|s| *s > 0.0)
            && record.time_s >= next_trace_s
        {
            // On a fixed grid from 0 (not from the last point), so the times do not drift by a cycle each.
            while next_trace_s <= record.time_s {
                next_trace_s += every_s;
            }
            let force = |arm| record.arm(arm).map_or(0.0, |a| a.world_force_n.norm());
            let stitch_arcs_m = [Flap::B, Flap::A].map(|flap| world.stitch_arc_at_m(flap));
            knot_trace.push(KnotTracePoint {
                time_s: record.time_s,
                knot: knot_now(&world),
                wound_gap_m: world.wound_gap_m(),
                stitch_arcs_m,
                force_n: [force(ArmName::Left), force(ArmName::Right), force(ArmName::Assist)],
                ends_on_instruments: ends_on_instruments(&world, stitch_arcs_m),
            });
        }
        if record.cycle % every == 0 {
            sample_instruments(&record, &world, &mut records);
        }
        while snapshot_times.first().is_some_and(|t| *t <= record.time_s) {
            let t = snapshot_times.remove(0);
            snapshots.extend(snapshot(&world, options, t));
        }
        let following = match (&record.status, next.as_mut()) {
            (Status::Finished, Some(next)) => next(&world),
            _ => None,
        };
        drop(world);
        skill_start_s = record.time_s - record.skill_time_s;
        if let Some(skill) = following {
            force_events.extend(fired_in(&controller, &running, skill_start_s));
            running = skill.clone();
            controller.load_skill(skill)?;
            continue;
        }
        if matches!(record.status, Status::Finished)
            || options.stop_after_s.is_some_and(|t| record.time_s >= t)
        {
            break;
        }
    }
    let simulated_s = controller.record().time_s;
    force_events.extend(fired_in(&controller, &running, skill_start_s));
    drop(controller);
    let mut world = backend.world();
    let evaluation = if fault.is_some() {
        fault_evaluation(&world)
    } else {
        let params = world.config().evaluation.clone();
        // Snapshots past the skill's end show the holding test, on the same clock.
        evaluate_knot_watched(&mut world, &params, &mut |world, held_s| {
            while snapshot_times.first().is_some_and(|t| *t <= simulated_s + held_s) {
                let t = snapshot_times.remove(0);
                snapshots.extend(snapshot(world, options, t));
            }
        })
    };
    for t in snapshot_times {
        snapshots.extend(snapshot(&world, options, t));
    }
    let events = world.events().iter().map(|e| format!("{e:?}")).collect();
    let final_scene = scene_shapes(&world);
    let demonstration = Demonstration { metadata, instruments: records };
    let wall_s = started.elapsed().as_secs_f64();
    Ok(DemoRun {
        demonstration,
        evaluation,
        knot_at_release: knot_at_release.flatten(),
        coils_at_take: coils_at_take.flatten(),
        fault,
        simulated_s,
        wall_s,
        snapshots,
        self_crossings: world.suture().self_crossings().to_vec(),
        events,
        force_events,
        final_scene,
        knot_trace,
    })
}

/// The metadata of a scripted-expert recording.
pub fn expert_metadata(world: &SimWorld, scene: &str, seed: Option<u64>, sample_rate_hz: f64) -> Metadata {
    Metadata {
        format_version: FORMAT_VERSION,
        source: "scripted expert".into(),
        scene: scene.into(),
        seed,
        sample_rate_hz,
        stitch: StitchPose::from_isometry(&world.tissue().world_from_tissue),
        description: "instrument tie of a surgeon's knot (knotlab's scripted expert)".into(),
    }
}

/// The simulated rig the expert performs on (`scenarios/rigs/sim.toml`).
pub const SIM_RIG_TOML: &str = include_str!("../../rigs/sim.toml");

/// Why the expert could not perform at all.
#[derive(Debug, thiserror::Error)]
pub enum ExpertError {
    /// The scene cannot be built.
    #[error("{scene}: {reason}")]
    World {
        /// The scene file.
        scene: String,
        /// Why.
        reason: knotlab_sim::world::WorldError,
    },
    /// The shipped rig or its config is broken.
    #[error("the shipped rig: {0}")]
    Rig(String),
    /// The recording failed.
    #[error(transparent)]
    Record(#[from] RecordError),
}

/// The scripted expert performs the task once in `scene` (named `scene_name` in the metadata), by the
/// base plan ([`super::TieGeometry::default`]; the shipped plan is a file,
/// `scenarios/experts/instrument-tie.toml`, for [`demonstrate_with`]): with human-like variation drawn
/// from `seed` (or none), the sensor noise seeded by `seed` too. `observer`, if any, sees every control
/// cycle.
pub fn demonstrate(
    scene: knotlab_sim::scene::SceneConfig,
    scene_name: &str,
    seed: u64,
    human: bool,
    options: &RecordOptions,
    observer: Option<&mut CycleObserver<'_>>,
) -> Result<DemoRun, ExpertError> {
    demonstrate_with(scene, scene_name, seed, human, &super::TieGeometry::default(), options, observer)
}

/// [`demonstrate`] with the expert placing things by `geometry` instead of the base plan's.
pub fn demonstrate_with(
    scene: knotlab_sim::scene::SceneConfig,
    scene_name: &str,
    seed: u64,
    human: bool,
    geometry: &super::TieGeometry,
    options: &RecordOptions,
    observer: Option<&mut CycleObserver<'_>>,
) -> Result<DemoRun, ExpertError> {
    let rig = Rig::shipped().map_err(|e| ExpertError::Rig(e.to_string()))?;
    let config = knotlab_hw::rig_config::parse_rig_config(SIM_RIG_TOML, "scenarios/rigs/sim.toml")
        .map_err(|e| ExpertError::Rig(e.to_string()))?;
    let mut world = SimWorld::new(scene, rig.clone())
        .map_err(|reason| ExpertError::World { scene: scene_name.to_owned(), reason })?;
    world.reseed(seed);
    let variation = if human { super::Variation::human(seed) } else { super::Variation::none() };
    let skill = super::plan_instrument_tie(&world, geometry, &variation);
    let rate_hz = 1.0 / (world.config().solver.dt_s * options.cycles_per_sample.max(1) as f64);
    let metadata = expert_metadata(&world, scene_name, Some(seed), rate_hz);
    // After the first plan, each of these in turn, planned from the world as it stands then, those
    // a geometry does not ask for skipped: the rest of the first throw once the right has wound
    // keeping the long end's tension, the rest once the left's jaws are over
    // the tail (if it looks before it takes it), the tail's hand-over to the assist, the second
    // throw, and its rest once the left's jaws are over the tail.
    let planners: [super::Planner; 5] = [
        super::plan_after_wind,
        super::plan_tail_take,
        super::plan_tail_hand_over,
        super::plan_second_throw,
        super::plan_second_tail_take,
    ];
    let mut planners = planners.into_iter();
    let mut second = |world: &SimWorld| planners.by_ref().find_map(|plan| plan(world, geometry, &variation));
    Ok(record_demonstration(world, &rig, &config, skill, metadata, options, observer, Some(&mut second))?)
}
