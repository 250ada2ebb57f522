//! Regression: `knotlab run --method replay --stitch-offset -0.02,-0.02,0 --stitch-rotate -30` was
//! refused by the controller because the way in of the slowest instrument started at -2.2e-16 s
//! (its last key's time `duration * k / (n - 1)` rounded above the duration the lead came from).

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{JawKey, Orientation, PoseKey, Skill, Track};
use knotlab_learner::synthesis::{ApproachSettings, StartPose, prepend_approach};
use nalgebra::Isometry3;

/// No key of a way in is timed before 0 s, for distances and key counts whose durations round either way,
/// and the keys stay in time order.
#[test]
fn no_key_of_a_way_in_comes_before_the_start() {
    // Distances whose durations round either way at many key counts.
    for (k, distance_m) in
        [0.0123456789, 0.0314159265, 0.0271828182, 0.1, 0.07, 0.0333333333].iter().enumerate()
    {
        for keys in [7, 10, 13, 31, 50] {
            let track = |arm, x: f64| Track {
                arm,
                poses: vec![PoseKey {
                    time_s: 0.0,
                    world_position_m: [x, 0.0, 0.9],
                    orientation: Orientation::AlongShaft,
                }],
                jaw: vec![JawKey { time_s: 0.0, jaw_rad: 0.0 }],
                events: Vec::new(),
            };
            let mut skill = Skill {
                name: "probe".into(),
                tracks: vec![track(ArmName::Left, *distance_m), track(ArmName::Right, 0.3 * distance_m)],
            };
            let starts = [
                StartPose { arm: ArmName::Left, world_from_tip: Isometry3::translation(0.0, 0.0, 0.9) },
                StartPose { arm: ArmName::Right, world_from_tip: Isometry3::translation(0.0, 0.0, 0.9) },
            ];
            let settings = ApproachSettings { keys, ..ApproachSettings::default() };
            let lead_s = prepend_approach(&mut skill, &starts, &settings);
            assert!(lead_s > 0.0, "case {k}");
            for t in &skill.tracks {
                assert!(t.poses.iter().all(|p| p.time_s >= 0.0), "case {k}, {keys} keys: {:?}", t.poses[0]);
                assert!(t.poses.windows(2).all(|w| w[1].time_s >= w[0].time_s));
            }
        }
    }
}
