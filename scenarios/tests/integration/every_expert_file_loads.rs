//! Every expert file loads, the shipped ones under `scenarios/experts/` and the tests' recipes under
//! `scenarios/tests/experts/`: work-in-progress recipes that no run test pins (say `two-throws-drawn-ahead.toml`) are still read through the same checks (keys,
//! ranges, combinations) as the ones that are, so a renamed or re-ranged key cannot leave one behind.

use knotlab_scenarios::expert::load_tie_geometry;

use super::common::expert_path;

/// Every expert file loads through the geometry checks, none goes missing, and each derived recipe
/// stays the one it is built from with only its stated changes.
#[test]
fn every_expert_file_loads() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut names = Vec::new();
    for dir in [root.join("experts"), root.join("tests/experts")] {
        for entry in std::fs::read_dir(&dir).expect("an expert directory") {
            let path = entry.expect("a directory entry").path();
            if path.extension().is_some_and(|e| e == "toml") {
                if let Err(e) = load_tie_geometry(&path) {
                    panic!("{} does not load: {e}", path.display());
                }
                names.push(path.file_name().unwrap().to_string_lossy().into_owned());
            }
        }
    }
    names.sort();
    // The base plan's listing, the shipped plan and the second-throw recipes are all there.
    for expected in [
        "base.toml",
        "instrument-tie.toml",
        "keeps-the-tension.toml",
        "two-throws-tail-end.toml",
        "two-throws-drawn-ahead.toml",
        "two-throws-on-the-assist.toml",
        "two-throws-leg-behind.toml",
        "two-throws-looking.toml",
        "looks-and-cinches.toml",
        "two-throws-cinched.toml",
    ] {
        assert!(names.iter().any(|n| n == expected), "{expected} missing from {names:?}");
    }
    // The drawn-ahead recipe is the tail-end one with the right drawing the turn off ahead.
    let ahead = load_tie_geometry(&expert_path("two-throws-drawn-ahead.toml")).unwrap();
    let second = ahead.second_throw.expect("a second throw");
    assert_eq!(second.tail_hold_from_end_m, Some(0.004));
    assert_eq!(second.tail_end_offered_m, Some(0.005));
    assert_eq!(second.right_draws_to_m, Some([0.035, -0.015, 0.02]));
    // The looking recipe's first throw is looks-at-the-tail's; its second fetch looks, square to the
    // tail, the right staying where it wound.
    let looking = load_tie_geometry(&expert_path("two-throws-looking.toml")).unwrap();
    let first = load_tie_geometry(&expert_path("looks-at-the-tail.toml")).unwrap();
    let second = looking.second_throw.clone().expect("a second throw");
    assert_eq!(knotlab_scenarios::expert::TieGeometry { second_throw: None, ..looking }, first);
    let fetch = second.left_fetches.expect("the second throw's own fetch");
    assert!(fetch.looks && fetch.hinge_along_tail && fetch.right_follows == 0.0, "{fetch:?}");
    // The cinching recipe is looks-at-the-tail's with pulls that go on to their set force.
    let cinches = load_tie_geometry(&expert_path("looks-and-cinches.toml")).unwrap();
    let expected = knotlab_scenarios::expert::TieGeometry {
        pull_on_m: 0.2,
        pulls_stop_together: true,
        tail_pull_force_n: Some(1.0),
        hold_through_release: true,
        ..load_tie_geometry(&expert_path("looks-at-the-tail.toml")).unwrap()
    };
    assert_eq!(cinches, expected);
    // The shipped plan, cinched by both ends: looks-at-the-tail's with each pull going on to its own
    // set force (a surgeon's snug, 3 N), slower, aimed at the tissue's surface, and the right going
    // the left's way as it draws the tail back.
    let both = load_tie_geometry(&expert_path("instrument-tie.toml")).unwrap();
    let expected = knotlab_scenarios::expert::TieGeometry {
        pull_s: 5.0,
        left_pull_to_m: [0.0, 0.06, 0.0],
        right_pull_to_m: [0.0, -0.05, 0.0],
        pulls_stop_together: false,
        pull_force_n: 3.0,
        tail_pull_force_n: Some(3.0),
        right_follows_draw: 1.0,
        ..cinches.clone()
    };
    assert_eq!(both, expected);
    // The plan for the suture at its real weight: the shipped one winding slower and keeping the long
    // end's tension, its draw and run-down asking less thread of 12 cm.
    let keeps = load_tie_geometry(&expert_path("keeps-the-tension.toml")).unwrap();
    let expected = knotlab_scenarios::expert::TieGeometry {
        winding_give_force_n: Some(0.5),
        winding_give_rate_m_per_n_s: 0.03,
        winding_s: 24.0,
        draw_back_m: 0.02,
        left_run_down_to_m: [0.0, 0.03, 0.035],
        right_run_down_to_m: [0.0, -0.008, 0.008],
        ..both.clone()
    };
    assert_eq!(keeps, expected);
    // The cinched two-throw recipe: that first throw (its pulls on 0.12 m), the left letting go of it.
    let cinched = load_tie_geometry(&expert_path("two-throws-cinched.toml")).unwrap();
    let second = cinched.second_throw.clone().expect("a second throw");
    assert!(second.left_lets_go_first && second.tail_held_taut == Some(0.9), "{second:?}");
    let fetch = second.left_fetches.as_ref().expect("the second throw's own fetch");
    assert_eq!(fetch.right_beside_m, Some([-0.015, 0.0, 0.012]), "the right keeps beside the left's jaws");
    let first = knotlab_scenarios::expert::TieGeometry { pull_on_m: 0.12, ..cinches };
    assert_eq!(knotlab_scenarios::expert::TieGeometry { second_throw: None, ..cinched }, first);
}
