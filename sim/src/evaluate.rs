//! The knot's verdict in the simulator: the topology and tightness judged on the thread's centreline
//! ([`crate::knot::judge`]), then the holding test no public surgical simulator runs: every
//! instrument lets go, the wound's elastic load and a holding load on each flap act for a settle time,
//! and the knot holds if the wound gap stays below a threshold and the knot type persists.

use nalgebra::{Point3, Vector3};
use serde::{Deserialize, Serialize};

use crate::knot::bending::{Bending, bending};
use crate::knot::legs::{Leg, free_ends, legs};
use crate::knot::{
    Classification, DownLimits, FailureMode, KnotPlacement, KnotSpan, KnotType, StitchSite, TissueSurface,
    Verdict, classify, judge,
};
pub use crate::scene::EvaluationParams;
use crate::thread_watch::Stretch;
use crate::tissue::Flap;
use crate::world::SimWorld;

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
    /// The thread outside the tissue between the stitch and the knot, both sides, m
    /// ([`crate::knot::KnotSpan::loop_outside_m`]): about the two bites for a knot cinched down on the
    /// wound, twice its height and more for one cinched in the air. Read it while the ends are held
    /// taut: a slack loop lying over itself adds crossings, which shorten it. Not part of the verdict.
    pub loop_outside_m: Option<f64>,
    /// Wound gap before release, m.
    pub gap_before_m: f64,
    /// Wound gap after the settle time, if the holding test ran, m.
    pub gap_after_m: Option<f64>,
    /// How often the thread passed through itself during the run (a solver failure; the knot of a
    /// run with any is not a real thread's).
    pub thread_self_crossings: usize,
    /// The suture at its most stretched over the run and its holding test (its most stretched
    /// segment beyond its rest length, a fraction of it, and when; and how long it was beyond 5 %):
    /// an inextensible suture's solver error under load. Not part of the verdict.
    pub thread_most_stretched: Option<Stretch>,
    /// How much of each free end the knot drew in during the holding test, if it ran and the two ends
    /// touched before and after: a knot that slips draws in the end it lets through.
    pub slid: Option<Slid>,
}

/// How much of each free end a knot drew in while it was loaded: the free end's length before less
/// its length after, by contact ([`crate::knot::legs::free_ends`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Slid {
    /// The long end (the needle's), m.
    pub long_end_m: f64,
    /// The tail, m.
    pub tail_m: f64,
}

/// The tissue surface and stitch point of a scene.
pub fn stitch_site(world: &SimWorld) -> Option<StitchSite> {
    let frame = world.tissue.world_from_tissue;
    let surface = TissueSurface::new(frame.translation.vector, world.tissue.normal()).ok()?;
    let stitch_m = (frame * Point3::new(world.config.stitch.along_m, 0.0, 0.0)).coords;
    Some(StitchSite { surface, stitch_m })
}

fn classify_thread(world: &SimWorld) -> Option<Classification> {
    let line: Vec<Vector3<f64>> = world.thread_centreline();
    classify(&line).ok()
}

/// Where the knot sits as the thread lies now, not judged: its type, the height of its lowest
/// crossing above the tissue and the thread between the stitch and it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct KnotNow {
    /// The knot in the thread.
    pub knot: KnotType,
    /// Height of its lowest crossing above the tissue, m (none for no knot).
    pub height_m: Option<f64>,
    /// The thread outside the tissue between the stitch and the knot, m
    /// ([`KnotEvaluation::loop_outside_m`]).
    pub loop_outside_m: Option<f64>,
    /// How far the knot's crossings lie from their centre at most, m (none for no knot): small for a
    /// knot drawn tight, large for throws apart or loose.
    pub radius_m: Option<f64>,
    /// The loop's leg from the exit point (the needle's side) to where the long end first touches
    /// the tail: its thread and the distance it spans ([`crate::knot::legs`]); none if they do not
    /// touch.
    pub exit_leg: Option<Leg>,
    /// ... and from the entry point (the tail's side) to where the tail first touches the long end.
    pub entry_leg: Option<Leg>,
    /// How much each end bends inside the knot ([`crate::knot::bending`]): a tail that runs straight
    /// through the long end's turns slides through them under load; none if the ends do not touch.
    pub bending: Option<Bending>,
}

/// Strands closer than this many thread radii, axis to axis, touch (two radii and a quarter more).
const TOUCH_RADII: f64 = 2.5;

/// The knot as the thread lies now (`None` when the centreline or the tissue is degenerate): cheap
/// enough to take at a moment of interest, such as the cycle the instruments let go.
pub fn knot_now(world: &SimWorld) -> Option<KnotNow> {
    let site = stitch_site(world)?;
    let c = classify_thread(world)?;
    let (height_m, loop_outside_m, radius_m) = match &c.span {
        Some(span) => {
            let placement = KnotPlacement::measure(span, &site.surface, &site.stitch_m);
            (Some(placement.height_m), loop_outside(world, span), Some(span.radius_m))
        }
        None => (None, None, None),
    };
    let arc_at = |flap| world.stitch_arc_at_m(flap);
    let ((exit_leg, entry_leg), bending) = match (arc_at(Flap::B), arc_at(Flap::A)) {
        (Some(exit_m), Some(entry_m)) => {
            let line = world.thread_centreline();
            let touch_m = TOUCH_RADII * world.config.thread.radius_m;
            (legs(&line, exit_m, entry_m, touch_m), bending(&line, exit_m, entry_m, touch_m))
        }
        _ => ((None, None), None),
    };
    Some(KnotNow { knot: c.knot, height_m, loop_outside_m, radius_m, exit_leg, entry_leg, bending })
}

fn loop_outside(world: &SimWorld, span: &KnotSpan) -> Option<f64> {
    let arc_at = |flap| world.stitch_arc_at_m(flap);
    span.loop_outside_m(arc_at(Flap::B)?, arc_at(Flap::A)?)
}

/// The free ends as the thread lies now: `(long end, tail)`, m ([`crate::knot::legs::free_ends`]).
pub fn free_ends_now(world: &SimWorld) -> Option<(f64, f64)> {
    let arc_at = |flap| world.stitch_arc_at_m(flap);
    let line = world.thread_centreline();
    free_ends(&line, arc_at(Flap::B)?, arc_at(Flap::A)?, TOUCH_RADII * world.config.thread.radius_m)
}

/// The holding test's load: every jaw opens and, for the settle time, the tissue's elastic load and
/// `holding_load_n` on each flap pull the wound open. Returns the wound gap at the end, m; `None` when
/// the thread went unstable.
pub fn hold(world: &mut SimWorld, params: &EvaluationParams) -> Option<f64> {
    hold_watched(world, params, &mut |_, _| {})
}

/// [`hold`], showing `observe` the world before each step with the time since the load came on, s.
pub fn hold_watched(
    world: &mut SimWorld,
    params: &EvaluationParams,
    observe: &mut dyn FnMut(&SimWorld, f64),
) -> Option<f64> {
    world.release_all();
    let load = |world: &mut SimWorld, scale: f64| world.pull_flaps_open(params.holding_load_n * scale);
    load(world, 1.0);
    let steps = (params.settle_s / world.config.solver.dt_s).round() as usize;
    let mut stable = true;
    for step in 0..steps {
        observe(world, step as f64 * world.config.solver.dt_s);
        if world.step().is_err() {
            stable = false;
            break;
        }
    }
    load(world, -1.0);
    stable.then(|| world.wound_gap_m())
}

/// The evaluation of a run the controller stopped on a device fault: no knot judged, the verdict
/// `device_fault`, the wound and the thread as they are.
pub fn fault_evaluation(world: &SimWorld) -> KnotEvaluation {
    KnotEvaluation {
        verdict: Verdict::Failure(FailureMode::DeviceFault),
        knot_before: None,
        knot_after: None,
        height_m: None,
        stitch_distance_m: None,
        loop_outside_m: None,
        gap_before_m: world.wound_gap_m(),
        gap_after_m: None,
        thread_self_crossings: world.suture().self_crossings().len(),
        thread_most_stretched: world.suture().most_stretched(),
        slid: None,
    }
}

/// Judges the thread as it lies, then (if the knot is right and down) lets go of everything and runs
/// the holding test. Advances the world by the settle time when the holding test runs.
pub fn evaluate_knot(world: &mut SimWorld, params: &EvaluationParams) -> KnotEvaluation {
    evaluate_knot_watched(world, params, &mut |_, _| {})
}

/// [`evaluate_knot`], showing `observe` the world through the holding test ([`hold_watched`]).
pub fn evaluate_knot_watched(
    world: &mut SimWorld,
    params: &EvaluationParams,
    observe: &mut dyn FnMut(&SimWorld, f64),
) -> KnotEvaluation {
    let gap_before_m = world.wound_gap_m();
    let mut result = KnotEvaluation {
        verdict: Verdict::Failure(FailureMode::NoKnot),
        knot_before: None,
        knot_after: None,
        height_m: None,
        stitch_distance_m: None,
        loop_outside_m: None,
        gap_before_m,
        gap_after_m: None,
        thread_self_crossings: world.suture().self_crossings().len(),
        thread_most_stretched: world.suture().most_stretched(),
        slid: None,
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
        result.loop_outside_m = loop_outside(world, span);
    }
    let limits = DownLimits {
        max_height_m: params.max_knot_height_m,
        max_stitch_distance_m: params.max_stitch_distance_m,
    };
    result.verdict = judge(&before, &params.accepted, &site, &limits);
    // A thread that passed through itself may hold a knot real thread could not have tied (or
    // lack one it would have): whatever it ends with, the trial measured the solver, not the skill.
    if result.thread_self_crossings > 0 {
        result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
    }
    if result.verdict != Verdict::Success {
        return result;
    }
    // The holding test: every jaw opens, the load pulls the wound open for the settle time.
    let free_before = free_ends_now(world);
    let held = hold_watched(world, params, observe);
    result.thread_most_stretched = world.suture().most_stretched();
    if held.is_none() {
        result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
        return result;
    }
    result.thread_self_crossings = world.suture().self_crossings().len();
    if result.thread_self_crossings > 0 {
        result.verdict = Verdict::Failure(FailureMode::ThreadUnstable);
        return result;
    }
    let gap_after = world.wound_gap_m();
    result.gap_after_m = Some(gap_after);
    if let (Some(before), Some(after)) = (free_before, free_ends_now(world)) {
        result.slid = Some(Slid { long_end_m: before.0 - after.0, tail_m: before.1 - after.1 });
    }
    let after = classify_thread(world);
    result.knot_after = after.as_ref().map(|c| c.knot);
    let persists = after.is_some_and(|c| c.knot == before.knot);
    if !persists || gap_after > params.max_wound_gap_m {
        result.verdict = Verdict::Failure(FailureMode::KnotSlipped);
    }
    result
}
