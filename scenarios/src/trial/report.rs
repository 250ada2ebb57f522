//! What a trial tells its caller: the verdict, the knot and the wound, the thread's health, what ran
//! and for how long, the preview's outcome and where the skill was executed. `knotlab run --json`
//! prints it; the Python package returns it as a dict.

use serde::{Deserialize, Serialize};

use knotlab_sim::evaluate::Slid;
use knotlab_sim::knot::Verdict;
use knotlab_sim::thread_watch::{SelfCrossing, Stretch};

use super::{TrialRun, TrialSetup};

/// One trial's report (field names as serialized; lengths in m, times in s, angles in degrees where
/// the name says so).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TrialReport {
    /// Whether the knot was accepted (and the preview gate let it run).
    pub success: bool,
    /// `success` or the failure mode.
    pub verdict: String,
    /// The failure mode (none on success).
    pub failure_mode: Option<String>,
    /// The knot before release, if any.
    pub knot: Option<String>,
    /// The knot after release, if any.
    pub knot_after_release: Option<String>,
    /// The wound's gap at the end, m.
    pub wound_gap_m: f64,
    /// The wound's gap after release, m.
    pub wound_gap_after_release_m: Option<f64>,
    /// The knot's height over the wound, m.
    pub knot_height_m: Option<f64>,
    /// The knot's distance from the stitch, m.
    pub knot_stitch_distance_m: Option<f64>,
    /// The thread outside the tissue between the stitch and the knot, both sides (about the two bites
    /// for a knot cinched down on the wound); not part of the verdict.
    pub knot_loop_outside_m: Option<f64>,
    /// How much of each free end the knot drew in during the holding test (a knot that slips lets
    /// one through).
    pub knot_slid: Option<Slid>,
    /// How often the thread passed through itself during the trial (a trial with any is judged
    /// `thread_unstable`).
    pub thread_self_crossings: usize,
    /// The first ten of them: when (s of the scene's simulated time) and which two segments.
    pub first_self_crossings: Vec<SelfCrossing>,
    /// The suture at its most stretched (its most stretched segment beyond its rest length, a
    /// fraction of it, and when; and how long it was beyond 5 %); not part of the verdict.
    pub thread_most_stretched: Option<Stretch>,
    /// The method (`fluid`, `dmp`, `replay`).
    pub method: String,
    /// The trial's seed.
    pub seed: u64,
    /// The scene file.
    pub scene: String,
    /// The stitch's shift, world frame, m.
    pub stitch_offset_m: [f64; 3],
    /// Its turn about the tissue's normal, degrees.
    pub stitch_rotate_deg: f64,
    /// Its tilt about the wound, degrees.
    pub stitch_tilt_deg: f64,
    /// How long the way in to the skill's start took, s.
    pub approach_s: f64,
    /// The skill's length, s (the approach included).
    pub skill_duration_s: f64,
    /// Why the controller stopped early, if it did.
    pub fault: Option<String>,
    /// Simulated time, s.
    pub sim_seconds: f64,
    /// Wall-clock time, s.
    pub wall_seconds: f64,
    /// The scene's grasp events, in order.
    pub events: Vec<String>,
    /// How the long end lay round the instruments' jaws when the left first closed on the thread (its
    /// take of the tail), if it did: the turns the draw is to pull the tail through.
    pub coils_at_take: Option<crate::expert::diagnose::CoilsAtTake>,
    /// The preview gate's outcome.
    pub preview: Preview,
    /// Where the skill ran.
    pub execution: Execution,
}

/// The preview: the simulated trial, with the kinematic and collision checks in front of it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Preview {
    /// Whether a rig's real devices may run the skill.
    pub passed: bool,
    /// Why not (empty when it passed).
    pub reason: String,
}

/// Where the skill was executed after its preview.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Execution {
    /// `simulated` (the trial was the run), `refused` (a failed preview on real devices), `completed`
    /// or `emergency_stopped` (on the rig's devices).
    pub status: String,
    /// The rig config, if one was given.
    pub rig: Option<String>,
    /// Why it was refused, or what else there is to say.
    pub message: String,
}

impl Execution {
    /// The trial was the run.
    pub fn simulated() -> Self {
        Self { status: "simulated".to_owned(), rig: None, message: String::new() }
    }
}

impl TrialReport {
    /// The report of `trial`, set up by `setup` (the stitch's move as asked), executed as `execution`
    /// says.
    pub fn new(setup: &TrialSetup, trial: &TrialRun, execution: Execution) -> Self {
        let e = &trial.run.evaluation;
        let preview = match (&trial.run.fault, e.verdict) {
            _ if trial.kinematics.is_err() => Preview {
                passed: false,
                reason: trial.kinematics.as_ref().err().map(ToString::to_string).unwrap_or_default(),
            },
            _ if trial.collision.is_some() => Preview {
                passed: false,
                reason: trial.collision.as_ref().map(|c| format!("link collision: {c}")).unwrap_or_default(),
            },
            (Some(fault), _) => Preview { passed: false, reason: format!("fault: {fault}") },
            (None, Verdict::Success) => Preview { passed: true, reason: String::new() },
            (None, verdict) => Preview { passed: false, reason: format!("knot: {}", verdict.label()) },
        };
        let verdict = trial.verdict();
        Self {
            success: verdict == Verdict::Success,
            verdict: verdict.label().to_owned(),
            failure_mode: match verdict {
                Verdict::Success => None,
                Verdict::Failure(mode) => Some(mode.name().to_owned()),
            },
            knot: e.knot_before.map(|k| k.name().to_owned()),
            knot_after_release: e.knot_after.map(|k| k.name().to_owned()),
            wound_gap_m: e.gap_after_m.unwrap_or(e.gap_before_m),
            wound_gap_after_release_m: e.gap_after_m,
            knot_height_m: e.height_m,
            knot_stitch_distance_m: e.stitch_distance_m,
            knot_loop_outside_m: e.loop_outside_m,
            knot_slid: e.slid,
            thread_self_crossings: e.thread_self_crossings,
            first_self_crossings: trial.run.first_self_crossings().to_vec(),
            thread_most_stretched: e.thread_most_stretched,
            method: setup.method.as_str().to_owned(),
            seed: setup.seed,
            scene: setup.scene_name.clone(),
            stitch_offset_m: setup.stitch.offset_m.into(),
            stitch_rotate_deg: setup.stitch.rotate_rad.to_degrees(),
            stitch_tilt_deg: setup.stitch.tilt_rad.to_degrees(),
            approach_s: trial.approach_s,
            skill_duration_s: trial.skill.duration_s(),
            fault: trial.run.fault.clone(),
            sim_seconds: trial.run.simulated_s,
            wall_seconds: trial.run.wall_s,
            events: trial.run.events.clone(),
            coils_at_take: trial.run.coils_at_take.clone(),
            preview,
            execution,
        }
    }
}
