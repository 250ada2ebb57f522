//! The expert's second throw with the left keeping the tail (`[second_throw] left_keeps_tail`,
//! `scenarios/tests/experts/two-throws.toml`): the long end is wound once round the
//! left's closed jaws while they hold the tail from the first throw, with no hand-over to the assist.
//! (Not yet a throw: drawn off the jaws' tips, the turn catches on the right's jaws instead of the
//! tail; see docs/notebook/knot-tying-notes.md.)

use super::common;

use common::{event_time_s, expert, two_throw_run};
use knotlab_scenarios::expert::TieGeometry;

/// `two-throws.toml` is `coils-on-the-left.toml` with a second throw that keeps the tail in the left's jaws.
#[test]
fn the_two_throw_file_ties_its_first_throw_as_coils_on_the_left() {
    let two = expert("two-throws.toml");
    let second = two.second_throw.clone().expect("a second throw");
    assert!(second.left_keeps_tail);
    assert_eq!(TieGeometry { second_throw: None, ..two }, expert("coils-on-the-left.toml"));
}

/// With the left keeping the tail there is no hand-over (one left take, no release, one assist take), and
/// the second turn lies on the left's closed jaws.
#[test]
fn the_second_turn_is_wound_round_the_jaws_that_hold_the_tail() {
    // Seed 0: the first throw ends at 28 s, the second turn is wound by 38 s and drawn at 41-45 s.
    let run = two_throw_run("two-throws.toml", 0, vec![40.0], 40.5);
    // The left took the tail once, in the first throw, and holds it on: no hand-over (the jaws all
    // open as the run stops).
    let before_stop = |e: &&String| event_time_s(e) < Some(40.4);
    let left_events: Vec<&String> =
        run.events.iter().filter(|e| e.contains("arm: Left")).filter(before_stop).collect();
    assert_eq!(left_events.len(), 1, "one take, no release: {:?}", run.events);
    assert!(left_events[0].starts_with("Grasped"), "{left_events:?}");
    let assist_takes = run.events.iter().filter(|e| e.starts_with("Grasped { arm: Assist")).count();
    assert_eq!(assist_takes, 1, "the assist held the tail at the start only: {:?}", run.events);
    // The turn lies on the left's closed jaws: the long end (the needle's side of the thread)
    // touches both of them.
    let snapshot = run.snapshots.first().expect("the snapshot at 40 s");
    let segments = run.final_scene.thread_m.len().saturating_sub(1);
    let on = |link: &str| {
        snapshot.contacts.iter().filter(|(segment, l)| l == link && *segment < segments / 2).count()
    };
    assert!(on("left_jaw_1") >= 3 && on("left_jaw_2") >= 3, "{:?}", snapshot.contacts);
}
