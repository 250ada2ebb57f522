//! One trial end to end: the scene with its stitch moved, a skill synthesized there from what was
//! learned (by the method asked for, its take of the thread aimed where the thread lies: [`take`]),
//! run by the controller on the simulated rig through the device traits, and the knot it leaves
//! evaluated.

pub mod obstacles;
pub mod report;
pub mod stitch;
pub mod take;

pub use stitch::StitchMove;

use knotlab_hw::controller::ArmSetup;
use knotlab_hw::kinematics::{ArmJoints, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::parse_rig_config;
use knotlab_hw::skill::Skill;
use knotlab_hw::skill::preview::{KinematicProblem, kinematic_preview, kinematic_trajectory};
use knotlab_learner::demonstration::Demonstration;
use knotlab_learner::fluid::{GridRegion, Instantiation, PlaneFrame};
use knotlab_learner::obstacles::{LinkCollision, first_link_collision};
use knotlab_learner::primitive::{KnowledgeBase, Primitive};
use knotlab_learner::synthesis::site::pose_isometry;
use knotlab_learner::synthesis::{
    ApproachSettings, Method, PrimitiveOffset, PrimitiveSettings, PrimitiveSpan, Reach, ReplaySettings, Site,
    StartPose, SynthesisError, Trocars, offset_primitives, prepend_approach, relocation, replay, synthesize,
};
use knotlab_sim::knot::{FailureMode, Verdict};
use knotlab_sim::scene::SceneConfig;
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use self::obstacles::{ObstacleLog, collision_world, virtual_obstacles};

use crate::expert::record::{
    CycleObserver, DemoRun, ExpertError, RecordOptions, SIM_RIG_TOML, expert_metadata, record_demonstration,
};

/// What was learned from the demonstration: the knowledge base, and the demonstration itself (the
/// replay baseline plays it back).
#[derive(Clone, Debug)]
pub struct Learned {
    /// The primitives.
    pub knowledge: KnowledgeBase,
    /// The demonstration they came from.
    pub demonstration: Demonstration,
}

/// One trial's set-up.
#[derive(Clone, Debug)]
pub struct TrialSetup {
    /// The scene (before the stitch is moved).
    pub scene: SceneConfig,
    /// Its name (the file), for the record.
    pub scene_name: String,
    /// Seeds the sensor noise.
    pub seed: u64,
    /// Where the stitch goes, relative to the scene's.
    pub stitch: StitchMove,
    /// How the skill is carried there.
    pub method: Method,
    /// Each primitive's own offset from where the method puts it (none: as the method puts it).
    pub offsets: Vec<PrimitiveOffset>,
}

/// Why a trial could not run (a knot not tied is a verdict, not an error).
#[derive(Debug, thiserror::Error)]
pub enum TrialError {
    /// The expert's machinery (the scene, the rig, the recording).
    #[error(transparent)]
    Expert(#[from] ExpertError),
    /// The skill could not be synthesized.
    #[error("synthesis ({method}): {reason}")]
    Synthesis {
        /// The method.
        method: Method,
        /// Why.
        reason: SynthesisError,
    },
    /// The primitives' offsets name no primitive of the skill, or are not finite.
    #[error("the primitives' offsets: {0}")]
    Offsets(SynthesisError),
    /// The scene cannot be built with its stitch moved there.
    #[error(
        "{scene} with the stitch moved by {offset_m:?} m, turned {rotate_deg} deg and tilted {tilt_deg} deg: {reason}"
    )]
    Site {
        /// The scene file.
        scene: String,
        /// The offset, m.
        offset_m: [f64; 3],
        /// The turn, degrees.
        rotate_deg: f64,
        /// The tilt, degrees.
        tilt_deg: f64,
        /// Why.
        reason: Box<knotlab_sim::world::WorldError>,
    },
}

/// A trial that ran.
pub struct TrialRun {
    /// What the devices read, the verdict, timings (the recording's own type).
    pub run: DemoRun,
    /// The skill that ran.
    pub skill: Skill,
    /// How long the instruments took to reach the skill's start, s (included in the skill).
    pub approach_s: f64,
    /// The virtual obstacles of its 2D primitives.
    pub obstacles: ObstacleLog,
    /// The fluid's regenerations of its 2D primitives, each with when it starts in the skill, s.
    pub fluid: Vec<(String, Instantiation, f64)>,
    /// The kinematic preview: every target reachable within the joints' limits, or the first that is not.
    pub kinematics: Result<(), KinematicProblem>,
    /// The collision preview: the first link collision along the skill, if any (not looked for when
    /// the kinematic preview failed).
    pub collision: Option<LinkCollision>,
}

impl TrialRun {
    /// The trial's verdict as the preview gate sees it: a skill whose kinematic preview found a
    /// target out of reach is `unreachable`, one whose collision preview found a link collision is
    /// `collision` (on real devices neither would be executed), whatever the simulated knot; else the
    /// knot's verdict.
    pub fn verdict(&self) -> Verdict {
        if self.kinematics.is_err() {
            Verdict::Failure(FailureMode::Unreachable)
        } else if self.collision.is_some() {
            Verdict::Failure(FailureMode::Collision)
        } else {
            self.run.evaluation.verdict
        }
    }
}

/// The kinematic preview of `skill` on `world`'s instruments as they stand.
pub fn kinematic_check(world: &SimWorld, skill: &Skill) -> Result<(), KinematicProblem> {
    let (setups, current) = preview_arms(world);
    kinematic_preview(skill, &setups, &current, 0.01)
}

/// The instruments' setups and joints as they stand, for the previews.
fn preview_arms(world: &SimWorld) -> (Vec<ArmSetup>, Vec<(ArmName, ArmJoints)>) {
    let arms = [ArmName::Left, ArmName::Right, ArmName::Assist];
    let current = arms.iter().map(|&a| (a, world.arm(a).command)).collect();
    let setups = arms
        .iter()
        .map(|&a| ArmSetup {
            arm: a,
            model: world.rig().arm(a).model,
            world_trocar_m: trocar_of(world.config(), a),
        })
        .collect();
    (setups, current)
}

/// Step of the collision preview, s.
const COLLISION_STEP_S: f64 = 0.02;

/// The collision preview of `skill` on `world` as it stands: every arm's link boxes along the joints the
/// kinematic preview finds, every 20 ms, against the other arms, the gantry, the table, the patient and
/// the scene's obstacles. `Ok(None)` when nothing collides (or a target is out of reach: the kinematic
/// preview reports that).
pub fn collision_check(world: &SimWorld, skill: &Skill) -> Result<Option<LinkCollision>, SynthesisError> {
    let (setups, current) = preview_arms(world);
    let Ok(trajectory) = kinematic_trajectory(skill, &setups, &current, COLLISION_STEP_S) else {
        return Ok(None);
    };
    Ok(first_link_collision(&collision_world(world)?, &trajectory, COLLISION_STEP_S))
}

fn isometry(world_from_tip: &nalgebra::IsometryMatrix3<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::from(world_from_tip.translation.vector),
        UnitQuaternion::from_rotation_matrix(&world_from_tip.rotation),
    )
}

/// A skill made for a trial.
#[derive(Clone, Debug)]
pub struct Synthesized {
    /// The skill.
    pub skill: Skill,
    /// How long the way in from where the instruments were lasts, s.
    pub approach_s: f64,
    /// The virtual obstacles the fluid flowed around.
    pub obstacles: ObstacleLog,
    /// The fluid's regenerations of the 2D primitives, each with when it starts in the skill, s.
    pub fluid: Vec<(String, Instantiation, f64)>,
    /// Where each primitive runs in the skill.
    pub spans: Vec<PrimitiveSpan>,
}

/// Synthesizes the skill for `world` (whose tissue frame is the new stitch frame) by `method`.
pub fn synthesize_for(
    world: &SimWorld,
    learned: &Learned,
    method: Method,
) -> Result<Synthesized, SynthesisError> {
    let new_world_from_stitch = world.tissue().world_from_tissue;
    let demo_world_from_stitch = learned.demonstration.metadata.stitch.world_from_stitch();
    let moved = relocation(&demo_world_from_stitch, &new_world_from_stitch);
    let trocars = Trocars(
        [ArmName::Left, ArmName::Right, ArmName::Assist]
            .into_iter()
            .map(|a| (a, trocar_of(world.config(), a)))
            .collect(),
    );
    let starts: Vec<StartPose> = [ArmName::Left, ArmName::Right, ArmName::Assist]
        .into_iter()
        .map(|arm| StartPose { arm, world_from_tip: isometry(&world.world_from_tip(arm)) })
        .collect();
    let mut log = ObstacleLog::default();
    let mut fluid = Vec::new();
    let mut spans = Vec::new();
    let mut skill = match method {
        Method::Replay => {
            // The demonstration on its own clock: each primitive where it was demonstrated.
            for instrument in &learned.knowledge.instruments {
                let Ok(arm) = instrument.instrument.parse::<ArmName>() else { continue };
                for p in &instrument.primitives {
                    spans.push(PrimitiveSpan { name: p.name().to_owned(), arm, skill_s: p.span_s() });
                }
            }
            replay(&learned.demonstration, &moved, &trocars, &ReplaySettings::default())?
        }
        Method::Fluid | Method::Dmp => {
            let collision = collision_world(world)?;
            let mut source = |name: &str, arm: ArmName, plane: &PlaneFrame, region: &GridRegion| {
                let kb_pose = match learned.knowledge.primitive(name) {
                    Some(Primitive::TwoD(p)) => p.start_pose,
                    _ => return Ok(knotlab_learner::fluid::ObstacleMask::free(region.n)),
                };
                let direction = (new_world_from_stitch * pose_isometry(&kb_pose)).rotation * Vector3::z();
                let mask = virtual_obstacles(&collision, arm, plane, region, direction)?;
                log.grids.push((name.to_owned(), mask.count_blocked(), region.n * region.n));
                Ok(mask)
            };
            // The pull of a force-controlled primitive stops where the arm's reach ends.
            let reaches = |arm: ArmName, target: &TipTarget| {
                world
                    .rig()
                    .arm(arm)
                    .model
                    .solve_tip(target, &trocar_of(world.config(), arm), &arm.ready_joints())
                    .is_ok()
            };
            let site = Site {
                new_world_from_stitch,
                trocars: &trocars,
                starts: &starts,
                reach: Some(Reach(&reaches)),
            };
            let made =
                synthesize(&learned.knowledge, method, &site, &PrimitiveSettings::default(), &mut source)?;
            for slot in &made.schedule.slots {
                spans.push(PrimitiveSpan {
                    name: slot.name.clone(),
                    arm: slot.instrument,
                    skill_s: slot.new_s,
                });
            }
            for (name, inst) in made.fluid {
                let start_s = made.schedule.slot(&name).map_or(0.0, |s| s.new_s.0);
                fluid.push((name, inst, start_s));
            }
            made.skill
        }
    };
    // Each take aimed at the thread where it lies in this scene (every method: the take's aim is what
    // the instruments see, not how the method carries the skill).
    let aimed = take::take_offsets(world, learned, &new_world_from_stitch)?;
    if !aimed.is_empty() {
        offset_primitives(&mut skill, &spans, &aimed, &new_world_from_stitch.rotation)?;
    }
    let approach_s = prepend_approach(&mut skill, &starts, &ApproachSettings::default());
    for entry in &mut fluid {
        entry.2 += approach_s;
    }
    for span in &mut spans {
        span.skill_s = (span.skill_s.0 + approach_s, span.skill_s.1 + approach_s);
    }
    Ok(Synthesized { skill, approach_s, obstacles: log, fluid, spans })
}

/// Runs one trial; `observer`, if any, sees every control cycle.
pub fn run_trial(
    learned: &Learned,
    setup: &TrialSetup,
    options: &RecordOptions,
    observer: Option<&mut CycleObserver<'_>>,
) -> Result<TrialRun, TrialError> {
    let rig = Rig::shipped().map_err(|e| ExpertError::Rig(e.to_string()))?;
    let config = parse_rig_config(SIM_RIG_TOML, "scenarios/rigs/sim.toml")
        .map_err(|e| ExpertError::Rig(e.to_string()))?;
    let mut scene = setup.scene.clone();
    setup.stitch.apply(&mut scene);
    let mut world = SimWorld::new(scene, rig.clone()).map_err(|reason| TrialError::Site {
        scene: setup.scene_name.clone(),
        offset_m: setup.stitch.offset_m.into(),
        rotate_deg: setup.stitch.rotate_rad.to_degrees(),
        tilt_deg: setup.stitch.tilt_rad.to_degrees(),
        reason: Box::new(reason),
    })?;
    world.reseed(setup.seed);
    let Synthesized { mut skill, approach_s, obstacles, fluid, spans } =
        synthesize_for(&world, learned, setup.method)
            .map_err(|reason| TrialError::Synthesis { method: setup.method, reason })?;
    if !setup.offsets.is_empty() {
        let world_from_stitch = world.tissue().world_from_tissue.rotation;
        offset_primitives(&mut skill, &spans, &setup.offsets, &world_from_stitch)
            .map_err(TrialError::Offsets)?;
    }
    let kinematics = kinematic_check(&world, &skill);
    let collision = match kinematics {
        Ok(()) => collision_check(&world, &skill)
            .map_err(|reason| TrialError::Synthesis { method: setup.method, reason })?,
        Err(_) => None,
    };
    let rate_hz = 1.0 / (world.config().solver.dt_s * options.cycles_per_sample.max(1) as f64);
    let mut metadata = expert_metadata(&world, &setup.scene_name, Some(setup.seed), rate_hz);
    metadata.source = format!("knotlab run ({})", setup.method);
    metadata.description = format!("{} at a moved stitch", learned.knowledge.task);
    let run = record_demonstration(world, &rig, &config, skill.clone(), metadata, options, observer, None)
        .map_err(ExpertError::from)?;
    Ok(TrialRun { run, skill, approach_s, obstacles, fluid, kinematics, collision })
}
