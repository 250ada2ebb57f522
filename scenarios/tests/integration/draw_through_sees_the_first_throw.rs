//! `knot::drawn_through` checked against the physics it stands in for: just after
//! the left takes the tail in the first throw the thread reads `unknot`; with the tail drawn straight
//! back along the left's jaws from where they hold it, through the coils, it reads `surgeons`, the knot
//! the run's own draw and pulls make. Drawn the other way (out past the tips, missing the coils) it
//! does not.

use super::common;

use common::{event_segment, two_throw_run};
use knotlab_hw::rig::ArmName;
use knotlab_sim::knot::{KnotType, classify, drawn_through};
use nalgebra::Vector3;

/// Just after the left takes the tail the thread reads unknotted; drawn back through the coils it reads a
/// surgeon's throw, and drawn out past the jaws' tips it does not.
#[test]
fn drawn_through_the_coils_at_the_first_take_the_thread_makes_the_first_throw() {
    // Seed 0 of the two-throw scene: the left takes the tail at 16.23 s.
    let at_s = 16.3;
    let run = two_throw_run("two-throws-drawn-ahead.toml", 0, vec![at_s], 16.4);
    let take =
        run.events.iter().find(|e| e.starts_with("Grasped { arm: Left")).expect("the left takes the tail");
    let grip = event_segment(take).expect("a segment");
    let snapshot = run.snapshots.first().expect("the snapshot");
    let line = &snapshot.centreline_m;
    assert_eq!(classify(line).expect("classifies").knot, KnotType::Unknot, "nothing tied yet");

    let left = run.demonstration.instrument(ArmName::Left).expect("the left's record");
    let sample = left.sample_nearest(at_s).expect("samples");
    let jaws = sample.world_from_tip() * Vector3::z_axis();
    let through = drawn_through(line, grip, &sample.position_m, &jaws, 0.045, 0.003).expect("draws");
    assert_eq!(classify(&through).expect("classifies").knot, KnotType::Surgeons, "grip {grip}");
    let past_the_tips = drawn_through(line, grip, &sample.position_m, &-jaws, 0.045, 0.003).expect("draws");
    assert_ne!(classify(&past_the_tips).expect("classifies").knot, KnotType::Surgeons, "grip {grip}");
}
