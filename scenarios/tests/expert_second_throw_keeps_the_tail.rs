//! The expert's second throw with the left keeping the tail (`[second_throw] left_keeps_tail`,
//! `scenarios/experts/two-throws.toml`; issue 6, session 32): the long end is wound once round the
//! left's closed jaws while they hold the tail, the right draws the turn off their tips, and the ends
//! are pulled across. Seed 7 on the scene where two throws can hold leaves the surgeon's knot (the
//! double throw and an opposite single one), the first time the expert tied the knot the task asks
//! for; it still slips under the holding load (the first throw's loop is slack), so the verdict is not
//! asserted here.

use knotlab_scenarios::expert::{RecordOptions, TieGeometry, demonstrate_with, load_tie_geometry};
use knotlab_sim::knot::KnotType;
use knotlab_sim::scene::parse_scene;

fn expert(name: &str) -> TieGeometry {
    let file = format!("{}/experts/{name}", env!("CARGO_MANIFEST_DIR"));
    load_tie_geometry(std::path::Path::new(&file)).expect("the expert file")
}

#[test]
fn the_two_throw_file_ties_its_first_throw_as_coils_on_the_left() {
    let two = expert("two-throws.toml");
    let second = two.second_throw.clone().expect("a second throw");
    assert!(second.left_keeps_tail);
    assert_eq!(TieGeometry { second_throw: None, ..two }, expert("coils-on-the-left.toml"));
}

#[test]
fn wound_round_the_jaws_that_hold_the_tail_the_second_throw_makes_the_surgeons_knot() {
    let scene =
        parse_scene(include_str!("../short-suture-friction-0.5.toml"), "short-suture-friction-0.5.toml")
            .expect("the two-throw scene");
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = demonstrate_with(
        scene,
        "scenarios/short-suture-friction-0.5.toml",
        7,
        true,
        &expert("two-throws.toml"),
        &options,
        None,
    )
    .expect("records");
    assert_eq!(run.fault, None);
    // The left takes the tail once, in the first throw, and lets it go only at the end: no hand-over.
    let left_events: Vec<&String> =
        run.events.iter().filter(|e| e.contains("arm: Left") && !e.contains("time_s: 0.0 ")).collect();
    assert_eq!(left_events.len(), 2, "one take and one release: {:?}", run.events);
    assert!(left_events[0].starts_with("Grasped"), "{left_events:?}");
    assert!(left_events[1].starts_with("Released"), "{left_events:?}");
    let assist_takes = run.events.iter().filter(|e| e.starts_with("Grasped { arm: Assist")).count();
    assert_eq!(assist_takes, 1, "the assist holds the tail at the start only: {:?}", run.events);
    assert!(run.simulated_s > 44.0, "both throws ran: {} s", run.simulated_s);
    assert_eq!(run.evaluation.knot_before, Some(KnotType::SurgeonsKnot), "{:?}", run.evaluation);
}
