//! A second throw of the other hand (`scenarios/tests/experts/two-throws-leg-behind.toml`): the
//! left's jaws ahead of the knot along the wound, the long end wound once round them as a helix
//! advancing towards their tips, so that its knot leg joins the turn from behind, and the tail taken
//! where it is presented within the jaws. As the instruments let go the thread holds
//! the surgeon's knot (a double throw, then a single of the opposite hand), run down onto the first
//! throw. It does not hold: the knot is capsized, and the tail lies over the right's instrument
//! from the second draw on. With the stitch's points kept on their segments
//! (`lab/tests/integration/stitch_point_slid_past_its_segment_into_empty_space.rs`) the wound opens
//! 18 mm under the holding load (about 30 with the points sliding off them, the throws then 3.4 mm
//! apart), the throws end 11 mm apart and the exit's leg is nearly taut (see
//! docs/notebook/knot-tying-notes.md).

use super::common;

use common::two_throw_run;
use knotlab_sim::knot::KnotType;
use knotlab_sim::knot::verdict::{FailureMode, Verdict};

/// The leg-behind second throw makes a surgeon's knot by release without grip slips, and the run shows why
/// it slips: throws apart, exit leg nearly taut, a capsized knot with the tail across the right.
#[test]
fn the_second_throw_is_of_the_other_hand_and_makes_a_surgeons_knot() {
    // Seed 0: the left takes the presented tail at 47.3 s; the instruments let go at 75.3 s.
    let run = two_throw_run("two-throws-leg-behind.toml", 0, Vec::new(), 80.0);
    let at_release = run.knot_at_release.as_ref().expect("the left let go of the tail");
    assert_eq!(at_release.knot, KnotType::SurgeonsKnot, "{:?}", run.evaluation);
    assert_eq!(run.evaluation.knot_before, Some(KnotType::SurgeonsKnot), "{:?}", run.evaluation);
    // Not yet holding (and on the chain the thread passes through itself once on the way: the
    // self-crossing watch makes that thread_unstable).
    assert!(
        matches!(
            run.evaluation.verdict,
            Verdict::Failure(
                FailureMode::KnotNotDown | FailureMode::KnotSlipped | FailureMode::ThreadUnstable
            )
        ),
        "{:?}",
        run.evaluation
    );
    assert!(run.events.iter().all(|e| !e.starts_with("Slipped")), "no grip slips: {:?}", run.events);
    // The second throw is not down on the first: at release the knot's crossings lie up to 11 mm from
    // their centre (3.4 mm with the stitch's points sliding off their segments).
    let radius_m = at_release.radius_m.expect("a knot has crossings");
    assert!(radius_m > 0.005, "the throws together ({radius_m} m): assert that instead");
    // The exit's leg is nearly taut: 9.4 mm of thread for 7.2 mm of span (about 40 mm for 6 mm with
    // the stitch's points sliding off their segments).
    let exit_leg = at_release.exit_leg.expect("the long end touches the tail");
    assert!(exit_leg.slack_m() < 0.005, "the exit's leg slack: {exit_leg:?}");
    // And why it gathers: from the right's draw of the turn onto the tail to the
    // release, the tail's standing part lies over the right's jaws, wrist and shaft (10-12 segments
    // from 62 s, as the left carries it over the top), so that the right's instrument, not the left,
    // sets its line from the knot.
    // (`ends_on_instruments[arm][end]`: arms left, right, assist; ends long end, tail.)
    let on = |t: f64| {
        run.knot_trace
            .iter()
            .find(|p| p.time_s >= t - 1e-6)
            .expect("the trace reaches the pulls")
            .ends_on_instruments
    };
    let (before, pulls) = (on(30.0)[1][1], on(70.0)[1][1]);
    assert!(before == 0 && pulls >= 8, "the tail on the right: {before} segments at 30 s, {pulls} at 70 s");
    // Which end is which: at 42 s the second turn (the long end) is wound round the left's empty jaws
    // (7 segments), none of the tail on them.
    let [long_end_on_left, tail_on_left] = on(42.0)[0];
    assert!(long_end_on_left >= 3 && tail_on_left == 0, "on the left at 42 s: {:?}", on(42.0)[0]);
    // And the knot is capsized: at release the tail runs straight through it while the long end
    // winds round it (a slip knot, whatever its type), so under load the tail slides through.
    let bending = at_release.bending.expect("the ends touch");
    assert!(
        bending.tail_rad < 1.0 && bending.long_end_rad > std::f64::consts::TAU,
        "the tail bends inside the knot ({bending:?}): assert that it holds instead"
    );
}
