//! The expert's second throw round empty jaws, the tail taken by its end (`[second_throw]
//! tail_hold_from_end_m`, `scenarios/experts/two-throws-tail-end.toml`; issue 6, session 33): after the
//! first throw the assist takes the tail near its free end, the left lets go of it, and the long end
//! is wound once round the left's open jaws, the left takes the presented tail and draws it back, and
//! the turn lies round the tail's standing part. (Not yet a knot: in the pulls the turn comes off over
//! the tail's free end; see docs/knot-tying-notes.md.)

mod common;

use common::{event_segment, event_time_s, expert, two_throw_run};
use knotlab_scenarios::expert::TieGeometry;
use knotlab_scenarios::expert::diagnose::turns_about;

#[test]
fn the_tail_end_file_ties_its_first_throw_as_coils_on_the_left() {
    let file = expert("two-throws-tail-end.toml");
    let second = file.second_throw.clone().expect("a second throw");
    assert_eq!(second.tail_hold_from_end_m, Some(0.006));
    assert!(!second.left_keeps_tail && second.assist_presents);
    assert_eq!(TieGeometry { second_throw: None, ..file }, expert("coils-on-the-left.toml"));
}

#[test]
fn the_assist_takes_the_tail_by_its_end_and_the_turn_goes_from_the_empty_jaws_onto_the_tail() {
    // Seed 1: the first throw ends at 27 s; the assist takes the tail's end, the left lets go, the
    // turn is wound by 40 s, the left takes the presented tail at 42.8 s and draws it back by 46 s.
    let run = two_throw_run("two-throws-tail-end.toml", 1, vec![40.0, 47.0], 47.5);
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
    // The left takes the presented tail, after letting go of it.
    let left_takes: Vec<&String> =
        run.events.iter().filter(|e| e.starts_with("Grasped { arm: Left")).collect();
    assert_eq!(left_takes.len(), 2, "the first throw's take and the second's: {:?}", run.events);
    assert!(time_of(left_takes[1]) > time_of(left_release), "{}", left_takes[1]);
    // Drawn back, the turn lies round the tail's standing part: the long end (the 22 segments next to
    // the needle) winds about the line from the tail near the knot to where the left holds it.
    let drawn = run.snapshots.get(1).expect("the snapshot at 47 s");
    let held = event_segment(left_takes[1]).expect("a segment");
    let line = &drawn.centreline_m;
    let standing_from = held - 9;
    let turns = turns_about(&line[..=22], &line[standing_from], &(line[held] - line[standing_from]));
    assert!(turns.abs() > 0.8, "{turns} turns round the tail's standing part at 47 s");
}
