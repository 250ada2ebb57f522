//! The expert's second throw round empty jaws, the tail taken by its end (`[second_throw]
//! tail_hold_from_end_m`, `scenarios/tests/experts/two-throws-tail-end.toml`): after the
//! first throw the assist takes the tail near its free end, the left lets go of it, and the long end
//! is wound once round the left's open jaws. With the stitch's points kept on their segments
//! (`lab/tests/integration/stitch_point_slid_past_its_segment_into_empty_space.rs`) the left then
//! closes on nothing on seeds 0-4 (with the points sliding off them, it took the presented tail on
//! seed 1 and drew the turn onto the tail's standing part, not a knot: in the pulls the turn came off
//! over the tail's free end); this branch of the expert is left as it is (see
//! docs/notebook/knot-tying-notes.md).

use super::common;

use common::{event_segment, event_time_s, expert, two_throw_run};
use knotlab_scenarios::expert::TieGeometry;

/// `two-throws-tail-end.toml` is `coils-on-the-left.toml` with a second throw whose assist holds the tail
/// 6 mm from its end and presents it.
#[test]
fn the_tail_end_file_ties_its_first_throw_as_coils_on_the_left() {
    let file = expert("two-throws-tail-end.toml");
    let second = file.second_throw.clone().expect("a second throw");
    assert_eq!(second.tail_hold_from_end_m, Some(0.006));
    assert!(!second.left_keeps_tail && second.assist_presents);
    assert_eq!(TieGeometry { second_throw: None, ..file }, expert("coils-on-the-left.toml"));
}

/// For the second throw the assist takes the tail within two segments of its end, the left lets go after,
/// and the turn lies wound on the left's empty jaws.
#[test]
fn the_assist_takes_the_tail_by_its_end_and_the_turn_is_wound_round_the_empty_jaws() {
    // Seed 1: the first throw ends at 27 s; the assist takes the tail's end, the left lets go, the
    // turn is wound by 40 s.
    let run = two_throw_run("two-throws-tail-end.toml", 1, vec![40.0], 40.5);
    let segments = run.final_scene.thread_m.len().saturating_sub(1);
    let time_of = |e: &String| event_time_s(e);
    // The assist's second take is within two segments of the tail's free end, after the first throw.
    let takes: Vec<&String> = run.events.iter().filter(|e| e.starts_with("Grasped { arm: Assist")).collect();
    assert_eq!(takes.len(), 2, "at the start and for the second throw: {:?}", run.events);
    let segment = event_segment(takes[1]);
    assert!(segment.is_some_and(|s| s + 2 >= segments - 1), "{segments} segments: {}", takes[1]);
    assert!(time_of(takes[1]) > Some(20.0), "{}", takes[1]);
    // ... and then the left lets go of the tail.
    let left_release = run.events.iter().find(|e| e.starts_with("Released { arm: Left")).expect("lets go");
    assert!(time_of(left_release) > time_of(takes[1]), "{left_release} after {}", takes[1]);
    // The turn lies on the left's jaws: the long end (the needle's side) touches both.
    let snapshot = run.snapshots.first().expect("the snapshot at 40 s");
    let on = |link: &str| {
        snapshot.contacts.iter().filter(|(segment, l)| l == link && *segment < segments / 2).count()
    };
    assert!(on("left_jaw_1") >= 3 && on("left_jaw_2") >= 3, "{:?}", snapshot.contacts);
}
