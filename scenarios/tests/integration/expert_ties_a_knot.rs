//! The scripted expert ties the knot in the simulated thread.
//!
//! On the nominal scene (the rope), seed 0 of the shipped plan (`scenarios/experts/instrument-tie.toml`,
//! the canonical demonstration's run, which records the shipped files sample for sample) leaves a
//! surgeon's double throw that the evaluator accepts: down at the stitch, holding the wound closed
//! against the holding load once both have let go.
//!
//! On the capsule chain (`scenarios/chain.toml`), seed 0 of the base plan (`TieGeometry::default()`)
//! leaves a surgeon's knot down on the tissue at the stitch that
//! does not hold: the expert runs it down onto the wound and cinches it there (as the left lets go: at
//! the tissue, the wound closed to 1.17 mm), but the long end's leg from the exit to the knot is slack,
//! and once both let go the holding load opens the wound. A change to the scene, the grasp model or
//! the plan that stops the expert from tying either fails here.

use knotlab_learner::demonstration::load_demonstration;
use knotlab_scenarios::expert::{RecordOptions, demonstrate, demonstrate_with, load_tie_geometry};
use knotlab_sim::knot::KnotType;
use knotlab_sim::knot::Verdict;
use knotlab_sim::scene::parse_scene;

/// On the chain, seed 0 of the base plan ties a surgeon's double throw down at the stitch, the wound nearly
/// closed at release, the right's pull stopped at its set force and the long end wound round both jaws.
#[test]
fn on_the_chain_seed_0_ties_a_surgeons_knot_down_at_the_stitch() {
    let scene = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = demonstrate(scene, "scenarios/chain.toml", 0, true, &options, None).expect("records");
    let e = &run.evaluation;
    println!(
        "seed 0: {} (knot {:?}, height {:?} m, stitch distance {:?} m, loop outside {:?} m, gap after {:?} m), \
         {:.1} s simulated in {:.1} s",
        e.verdict.label(),
        e.knot_before,
        e.height_m,
        e.stitch_distance_m,
        e.loop_outside_m,
        e.gap_after_m,
        run.simulated_s,
        run.wall_s
    );
    assert_eq!(run.fault, None, "the controller ran the skill to its end");
    assert_eq!(e.knot_before, Some(KnotType::Surgeons), "the knot: {:?}", run.events);
    let limits = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the scene").evaluation;
    let height = e.height_m.expect("a knot has a height");
    let distance = e.stitch_distance_m.expect("and a distance from the stitch");
    assert!(height <= limits.max_knot_height_m, "{height} m above the tissue");
    assert!(distance <= limits.max_stitch_distance_m, "{distance} m from the stitch");
    assert!(e.loop_outside_m.is_some(), "the knot's crossings enclose the stitch");
    // The pulls, level with the tissue, draw the loop tight: the wound nearly closed as they let go
    // (pulled up and out at 1.5 N instead, they leave it 2.9 mm open). With the thread laid
    // untwisted at the start and the jaws clamping it as their faces squeeze it, seeds 0-7 let go
    // with it 0.95-3.13 mm open (seed 0: 2.63 mm, seed 7 the 3.13), all eight surgeon's knots within
    // 1 mm of the tissue.
    assert!(e.gap_before_m < 0.003, "the wound {} m open as the instruments let go", e.gap_before_m);
    assert!(e.gap_after_m.is_some(), "the holding test ran: {:?}", e.verdict);
    // The right's pull stopped at the set force (seed 0: 0.30 N at 23.74 s, 16 mm out: a spike as the
    // coils caught, the slack left in the exit leg); the run lists where.
    let stop = run
        .force_events
        .iter()
        .find(|f| f.arm == "right" && f.name == "set force")
        .unwrap_or_else(|| panic!("the right's pull stopped at its set force: {:?}", run.force_events));
    assert!(stop.force_n >= 0.3 && stop.time_s < run.simulated_s, "{stop:?}");
    // As the left takes the tail, the long end lies wound twice round its jaws (seed 0: -1.80 turns
    // about their direction). The same loops go round the right's jaws too (+1.90 about theirs, which
    // point back at the left's): each turn is a 40 mm loop round both instruments, not a coil on the
    // left's jaws (docs/notebook/knot-tying-notes.md). A winding round the left's jaws only will move that figure
    // towards 0: assert it here then.
    let coils = run.coils_at_take.expect("the left took the tail, the long end through the stitch");
    assert!((1.5..2.5).contains(&coils.left_turns.abs()), "{coils:?}");
    assert!(coils.right_turns.abs() > 1.0, "{coils:?}");
    // Which is also where the long end touches the right's instrument: besides the few segments next
    // to the needle in its jaws, two stretches far along it (seed 0: 11-15 and 24-28), where each
    // loop passes round the right's jaws and clevis. `coils-on-the-left.toml` brings the
    // turns about the right's jaw axis to -0.2 yet keeps such a bight (16-20 and 34-39, every seed
    // of 0-15 that took the tail with the turns on): a loop round the right's wrist.
    let far: Vec<usize> = coils.long_end_on_right.iter().copied().filter(|s| *s > 8).collect();
    assert!(far.len() >= 4 && far[far.len() - 1] > far[0] + 8, "{coils:?}");
}

/// Seed 0 of the shipped plan on the nominal scene ties a surgeon's double throw the evaluator accepts,
/// holding the wound closed under load, each pull stopped at its own set force; its recording is the
/// shipped demonstration, sample for sample.
#[test]
fn seed_0_of_the_shipped_plan_ties_a_surgeons_knot_that_holds() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    let limits = scene.evaluation.clone();
    let geometry = load_tie_geometry(&root.join("experts/instrument-tie.toml")).expect("the shipped plan");
    let options = RecordOptions { cycles_per_sample: 10, ..RecordOptions::default() };
    let run = demonstrate_with(scene, "scenarios/default.toml", 0, true, &geometry, &options, None)
        .expect("records");
    let e = &run.evaluation;
    println!(
        "seed 0: {} (knot {:?}, height {:?} m, gap before {} m, after {:?} m), {:.1} s simulated in {:.1} s",
        e.verdict.label(),
        e.knot_before,
        e.height_m,
        e.gap_before_m,
        e.gap_after_m,
        run.simulated_s,
        run.wall_s
    );
    assert_eq!(run.fault, None, "the controller ran the skill to its end");
    assert_eq!(e.verdict, Verdict::Success, "{:?}; events {:?}", e, run.events);
    assert_eq!(e.knot_before, Some(KnotType::Surgeons), "the knot: {:?}", run.events);
    let gap_after_m = e.gap_after_m.expect("the holding test ran");
    assert!(gap_after_m <= limits.max_wound_gap_m, "the wound {gap_after_m} m open under the load");
    // Each pull stopped at its own set force, a surgeon's snug (3 N): the left's on the tail, the
    // right's on the long end, the right's gauge reading the rope's pull on the needle.
    for (arm, set_n) in [("left", 3.0), ("right", 3.0)] {
        let stop =
            run.force_events.iter().find(|f| f.arm == arm && f.name == "set force").unwrap_or_else(|| {
                panic!("the {arm}'s pull stopped at its set force: {:?}", run.force_events)
            });
        assert!(stop.force_n >= set_n, "{stop:?}");
    }
    // This run is the canonical demonstration (`scenarios/demos/instrument-tie`, what `knotlab demo
    // --seed 0` records): every figure learned from the shipped files is one this build reproduces.
    let shipped = load_demonstration(&root.join("demos/instrument-tie")).expect("the shipped demonstration");
    assert_eq!(shipped.metadata, run.demonstration.metadata, "the shipped demonstration's metadata");
    for recorded in &run.demonstration.instruments {
        let name = recorded.instrument;
        let on_file = shipped.instrument(name).unwrap_or_else(|| panic!("{name:?} in the shipped files"));
        let differs = recorded.samples.iter().zip(&on_file.samples).find(|(a, b)| a != b);
        assert!(
            differs.is_none() && recorded.samples.len() == on_file.samples.len(),
            "{name:?}: the shipped demonstration is not what this build records (first difference {differs:?}; \
             {} samples against {} on file): regenerate it as scenarios/demos/README.md says, and the \
             figures learned from it",
            recorded.samples.len(),
            on_file.samples.len()
        );
    }
    assert_eq!(shipped.instruments.len(), run.demonstration.instruments.len(), "the same instruments");
}
