//! The first second throw of the other hand (`scenarios/experts/two-throws-leg-behind.toml`; issue
//! 6, session 37): the left's jaws ahead of the knot along the wound, the long end wound once round
//! them as a helix advancing towards their tips, so that its knot leg joins the turn from behind, and
//! the tail taken where it is presented within the jaws. As the instruments let go the thread holds
//! the surgeon's knot (a double throw, then a single of the opposite hand). It is not yet run down
//! onto the first throw: the verdict is a failure still (see the README).

mod common;

use common::two_throw_run;
use knotlab_sim::knot::KnotType;
use knotlab_sim::knot::verdict::{FailureMode, Verdict};

#[test]
fn the_second_throw_is_of_the_other_hand_and_makes_a_surgeons_knot() {
    // Seed 0: the left takes the presented tail at 47.4 s; the instruments let go at 64.5 s.
    let run = two_throw_run("two-throws-leg-behind.toml", 0, Vec::new(), 80.0);
    let at_release = run.knot_at_release.as_ref().expect("the left let go of the tail");
    assert_eq!(at_release.knot, KnotType::SurgeonsKnot, "{:?}", run.evaluation);
    assert_eq!(run.evaluation.knot_before, Some(KnotType::SurgeonsKnot), "{:?}", run.evaluation);
    // Not yet down and holding.
    assert!(
        matches!(
            run.evaluation.verdict,
            Verdict::Failure(FailureMode::KnotNotDown | FailureMode::KnotSlipped)
        ),
        "{:?}",
        run.evaluation
    );
    assert!(run.events.iter().all(|e| !e.starts_with("Slipped")), "no grip slips: {:?}", run.events);
    // Why: the second throw stays apart from the first. At release the knot's crossings spread 17.5 mm
    // from their centre (session 38); the first throw alone, drawn tight, about 3 mm.
    let radius_m = at_release.radius_m.expect("a knot has crossings");
    assert!(radius_m > 0.01, "the throws drawn together ({radius_m} m): assert that it holds instead");
}
