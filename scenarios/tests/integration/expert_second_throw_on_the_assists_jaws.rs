//! The expert's second throw wound on the assist's jaws (`[second_throw] left_retakes_from_end_m`,
//! `scenarios/tests/experts/two-throws-on-the-assist.toml`): after the first throw the
//! assist takes the tail by its end and draws it up, the left takes it back nearer the knot and the
//! assist lets go; the long end is wound once round the assist's jaws (level along -x, where the
//! left's cannot point), the left presents the tail and the assist takes it. (Not yet a second throw:
//! drawn through, this turn leaves the first throw's knot; see docs/notebook/knot-tying-notes.md.)

use super::common;

use common::{event_segment, event_time_s, two_throw_run};
use knotlab_hw::rig::ArmName;
use knotlab_scenarios::expert::diagnose::turns_about;
use nalgebra::Vector3;

/// The assist takes the tail's end, the left lets go and retakes it nearer the knot, the assist lets go,
/// the long end is wound about once round the assist's jaws, and the presented tail is taken near its end.
#[test]
fn the_left_takes_the_tail_back_and_the_long_end_is_wound_round_the_assists_jaws() {
    // Seed 0: the first throw ends near 28 s; the assist takes the tail's end at 29.4 s, the left
    // lets go at 30.3 s and takes it back at 36.5 s, the turn is wound by 52 s, the assist takes the
    // presented tail at 54.1 s.
    let run = two_throw_run("two-throws-on-the-assist.toml", 0, vec![52.0], 54.5);
    let segments = run.final_scene.thread_m.len().saturating_sub(1);
    let events_of = |prefix: &str| run.events.iter().filter(|e| e.starts_with(prefix)).collect::<Vec<_>>();
    let (assist_takes, left_takes) = (events_of("Grasped { arm: Assist"), events_of("Grasped { arm: Left"));
    let (left_lets_go, assist_lets_go) =
        (events_of("Released { arm: Left"), events_of("Released { arm: Assist"));
    // No grip slips until the assist takes the presented tail (the left's grip then slips, 5.1 N at
    // 54.07 s, as the assist closes on it at 54.05 s).
    let slips = events_of("Slipped");
    let presented_s = assist_takes.last().and_then(|e| event_time_s(e));
    assert!(slips.iter().all(|e| event_time_s(e) > presented_s), "no grip slips: {:?}", run.events);
    // The start's take, the tail's end after the first throw, the presented tail.
    assert_eq!(assist_takes.len(), 3, "{:?}", run.events);
    let end_take = event_segment(assist_takes[1]).expect("a segment");
    assert!(end_take + 2 >= segments - 1, "{segments} segments: {}", assist_takes[1]);
    // The left lets go after the assist holds the tail's end, then takes it back nearer the knot
    // (17 mm from the end: 5 or 6 segments) ...
    assert_eq!(left_takes.len(), 2, "the first throw's take and the retake: {:?}", run.events);
    let retake = event_segment(left_takes[1]).expect("a segment");
    assert!((segments - 7..=segments - 4).contains(&retake), "{segments} segments: {}", left_takes[1]);
    assert!(event_time_s(left_lets_go[0]) > event_time_s(assist_takes[1]), "{:?}", run.events);
    assert!(event_time_s(left_takes[1]) > event_time_s(left_lets_go[0]), "{:?}", run.events);
    // ... and the assist lets go of it (its second release: the first was in the first throw), before
    // the winding.
    assert!(event_time_s(assist_lets_go[1]) > event_time_s(left_takes[1]), "{:?}", run.events);
    // Wound: the long end next to the needle lies about once round the assist's jaw axis.
    let snapshot = run.snapshots.first().expect("the snapshot at 52 s");
    let on = |link: &str| {
        snapshot.contacts.iter().filter(|(segment, l)| l == link && *segment < segments / 2).count()
    };
    assert!(on("assist_jaw_1") + on("assist_jaw_2") >= 4, "{:?}", snapshot.contacts);
    let line = &snapshot.centreline_m;
    let assist = run.demonstration.instrument(ArmName::Assist).expect("the assist's record");
    let sample = assist.sample_nearest(52.0).expect("a sample at 52 s");
    let axis = sample.world_from_tip() * Vector3::z();
    let turns = turns_about(&line[2..=16], &sample.position_m, &axis);
    assert!((0.8..1.4).contains(&turns.abs()), "{turns} turns round the assist's jaws at 52 s");
    // The assist takes the presented tail near its end, after the winding.
    let presented = event_segment(assist_takes[2]).expect("a segment");
    assert!(presented + 4 >= segments - 1, "{segments} segments: {}", assist_takes[2]);
    assert!(event_time_s(assist_takes[2]) > Some(52.0), "{}", assist_takes[2]);
}
