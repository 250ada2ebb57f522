//! The knot's verdict in the simulator: the topology and tightness judged on the thread's centreline
//! ([`crate::knot::judge`]), then the holding test no public surgical simulator runs: every
//! instrument lets go, the wound's elastic load acts for a settle time, and the knot holds if the
//! wound gap stays below a threshold and the knot type persists.

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

use crate::knot::{
    Classification, DownLimits, FailureMode, KnotPlacement, KnotType, StitchSite, TissueSurface, Verdict,
    classify, judge,
};
use crate::world::SimWorld;

/// How a knot is judged (the scene file's `[evaluation]`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EvaluationParams {
    /// Knots the task accepts.
    pub accepted: Vec<KnotType>,
    /// Largest height of the knot's lowest crossing above the tissue, m.
    pub max_knot_height_m: f64,
    /// Largest distance from the stitch to the knot's nearest crossing, m.
    pub max_stitch_distance_m: f64,
    /// How long the released knot must hold against the elastic load, s.
    pub settle_s: f64,
    /// The wound gap a holding knot keeps below, m.
    pub max_wound_gap_m: f64,
}

impl Default for EvaluationParams {
    /// A surgeon's knot (or the square knot the surgeon's knot is often taken for), down within
    /// [`DownLimits::default`], holding the wound below 1.5 mm for one second.
    fn default() -> Self {
        let down = DownLimits::default();
        Self {
            accepted: vec![KnotType::SurgeonsKnot, KnotType::Surgeons],
            max_knot_height_m: down.max_height_m,
            max_stitch_distance_m: down.max_stitch_distance_m,
            settle_s: 1.0,
            max_wound_gap_m: 0.0015,
        }
    }
}

/// What the evaluation found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KnotEvaluation {
    /// The outcome.
    pub verdict: Verdict,
    /// The knot in the thread before the instruments let go (None: the centreline was degenerate).
    pub knot_before: Option<KnotType>,
    /// The knot after the settle time, if the holding test ran.
    pub knot_after: Option<KnotType>,
    /// Where the knot sat before release, if it had a span.
    pub height_m: Option<f64>,
    /// Distance from the stitch to the knot's nearest crossing before release, m.
    pub stitch_distance_m: Option<f64>,
    /// Wound gap before release, m.
    pub gap_before_m: f64,
    /// Wound gap after the settle time, if the holding test ran, m.
    pub gap_after_m: Option<f64>,
    /// How often the thread passed through itself during the run (a solver failure; the knot of a
    /// run with any is not a real thread's).
    pub thread_self_crossings: usize,
}

/// The tissue surface and stitch point of a scene.
pub fn stitch_site(world: &SimWorld) -> Option<StitchSite> {
    let frame = world.tissue.world_from_tissue;
    let surface = TissueSurface::new(frame.translation.vector, world.tissue.normal()).ok()?;
    let stitch_m = (frame * Point3::new(world.config.stitch.along_m, 0.0, 0.0)).coords;
    Some(StitchSite { surface, stitch_m })
}

fn classify_thread(world: &SimWorld) -> Option<Classification> {
    let line: Vec<Vector3<f64>> = world.thread.centreline(&world.physics);
    classify(&line).ok()
}

/// Judges the thread as it lies, then (if the knot is right and down) lets go of everything and runs
/// the holding test. Advances the world by the settle time when the holding test runs.
pub fn evaluate_knot(world: &mut SimWorld, params: &EvaluationParams) -> KnotEvaluation {
    let gap_before_m = world.wound_gap_m();
    let mut result = KnotEvaluation {
        verdict: Verdict::Failure(FailureMode::NoKnot),
        knot_before: None,
        knot_after: None,
        height_m: None,
        stitch_distance_m: None,
        gap_before_m,
        gap_after_m: None,
        thread_self_crossings: world.thread_watch.crossings.len(),
    };
    let Some(site) = stitch_site(world) else {
        result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
        return result;
    };
    let Some(before) = classify_thread(world) else {
        result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
        return result;
    };
    result.knot_before = Some(before.knot);
    if let Some(span) = &before.span {
        let placement = KnotPlacement::measure(span, &site.surface, &site.stitch_m);
        result.height_m = Some(placement.height_m);
        result.stitch_distance_m = Some(placement.stitch_distance_m);
    }
    let limits = DownLimits {
        max_height_m: params.max_knot_height_m,
        max_stitch_distance_m: params.max_stitch_distance_m,
    };
    result.verdict = judge(&before, &params.accepted, &site, &limits);
    if result.verdict != Verdict::Success {
        return result;
    }
    // The holding test: every jaw opens, the load pulls the wound open for the settle time.
    world.release_all();
    let steps = (params.settle_s / world.config.solver.dt_s).round() as usize;
    for _ in 0..steps {
        if world.step().is_err() {
            result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
            return result;
        }
    }
    result.thread_self_crossings = world.thread_watch.crossings.len();
    let gap_after = world.wound_gap_m();
    result.gap_after_m = Some(gap_after);
    let after = classify_thread(world);
    result.knot_after = after.as_ref().map(|c| c.knot);
    let persists = after.is_some_and(|c| c.knot == before.knot);
    if !persists || gap_after > params.max_wound_gap_m {
        result.verdict = Verdict::Failure(FailureMode::KnotSlipped);
    }
    result
}
