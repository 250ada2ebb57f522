//! The scripted expert's second throw (opt-in, `[second_throw]` in an expert file): the
//! first throw's pulls hold the ends, then the second throw is planned from the world they left and
//! recorded on in the same demonstration. The assist takes the tail between the knot and the left's
//! jaws, then the left lets go of it to be wound round. (Not yet a knot: the first throw leaves the
//! long end too short to wind, and the right loses the needle; see docs/notebook/knot-tying-notes.md.)

use knotlab_hw::rig::ArmName;
use knotlab_learner::demonstration::GraspState;
use knotlab_scenarios::expert::{RecordOptions, SecondThrow, TieGeometry, demonstrate_with};
use knotlab_sim::scene::parse_scene;

/// `(arm, segment, time_s)` of a "Grasped" event.
type Grasped = (String, usize, f64);
/// `(arm, time_s)` of a "Released" event.
type Released = (String, f64);

/// The "Grasped" and "Released" events of a run.
fn parse(events: &[String]) -> (Vec<Grasped>, Vec<Released>) {
    let field = |e: &str, key: &str| -> String {
        e.split(&format!("{key}: ")).nth(1).and_then(|s| s.split([',', ' ']).next()).unwrap_or("").to_owned()
    };
    let mut grasped = Vec::new();
    let mut released = Vec::new();
    for e in events {
        let time_s: f64 = field(e, "time_s").parse().unwrap_or(f64::NAN);
        if e.starts_with("Grasped") {
            grasped.push((field(e, "arm"), field(e, "segment").parse().unwrap_or(usize::MAX), time_s));
        } else if e.starts_with("Released") {
            released.push((field(e, "arm"), time_s));
        }
    }
    (grasped, released)
}

/// After the first throw the assist takes the tail again between the knot and the left's jaws, the left
/// lets go after that, and one valid demonstration records on through both.
#[test]
fn the_assist_takes_the_tail_and_the_left_lets_it_go() {
    let scene = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    let geometry = TieGeometry { second_throw: Some(SecondThrow::default()), ..TieGeometry::default() };
    // Seed 0's first throw ends at 26.6 s; the assist has the tail at 29.7 s, the left lets go at
    // 30.2 s.
    let options =
        RecordOptions { cycles_per_sample: 10, stop_after_s: Some(31.0), ..RecordOptions::default() };
    let run =
        demonstrate_with(scene, "scenarios/chain.toml", 0, true, &geometry, &options, None).expect("records");
    assert_eq!(run.fault, None);
    assert!(run.simulated_s > 30.9, "recorded on past the first throw: {} s", run.simulated_s);
    let (grasped, released) = parse(&run.events);
    let left = grasped.iter().find(|g| g.0 == "Left").expect("the left took the tail in the first throw");
    let assist_again = grasped
        .iter()
        .find(|g| g.0 == "Assist" && g.2 > left.2)
        .unwrap_or_else(|| panic!("the assist took the tail again: {:?}", run.events));
    assert!(assist_again.1 < left.1, "between the knot and the left's jaws: {assist_again:?}, {left:?}");
    let left_let_go = released
        .iter()
        .find(|r| r.0 == "Left")
        .unwrap_or_else(|| panic!("the left let go: {:?}", run.events));
    assert!(left_let_go.1 > assist_again.2, "after the assist had the tail: {:?}", run.events);
    // One demonstration, its time running on through both throws.
    let demo = &run.demonstration;
    demo.validate().expect("what the loader accepts");
    let assist = demo.instrument(ArmName::Assist).expect("the assist");
    let holding_late =
        assist.samples.iter().any(|s| s.time_s > assist_again.2 && s.grasp == GraspState::Holding);
    assert!(holding_late, "the recording shows the assist holding the tail again");
}
