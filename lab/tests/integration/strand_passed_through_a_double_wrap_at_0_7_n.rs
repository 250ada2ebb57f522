//! Regression: a throw came undone when pulled tight. A strand wound twice round another passed
//! through it once its ends were pulled apart with 0.7 N (the scripted expert cinches with 1.9 N): the
//! chain's joints drag its segments into the strand they press on a little every step, and the solver
//! pushed them apart at no more than 0.1 m/s. The shipped scene corrects at 1 m/s.

use knotlab_lab::cinch::{CinchParams, run_cinch};
use knotlab_sim::physics::SolverParams;
use knotlab_sim::scene::parse_scene;

const PULL: CinchParams = CinchParams { top_tension_n: 3.0, ramp_s: 1.5, ccd: false };

/// The shipped thread holds a double wrap pulled to 3 N: no strand passes through the other and no turn
/// comes off.
#[test]
fn the_shipped_thread_holds_a_double_wrap_pulled_to_3_n() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let held = run_cinch(&scene.solver, &scene.thread, &PULL).expect("a healthy pull");
    assert_eq!(held.first_pass_tension_n, None, "{held:?}");
    assert_eq!(held.passes, 0, "{held:?}");
    assert_eq!(held.turn_lost_tension_n, None, "{held:?}");
    assert!((held.turns_end - held.turns_start).abs() < 0.2, "the wraps stay on: {held:?}");
    assert!(held.deepest_overlap < 0.9, "{held:?}");
}

/// With overlaps corrected at only 0.1 m/s the strand passes through below 1.5 N and a turn comes off, so
/// the cinch trial detects a pass-through when one happens.
#[test]
fn corrected_at_0_1_m_s_the_strand_passes_through_below_3_n() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let slow = SolverParams { max_corrective_speed_m_s: 0.1, ..scene.solver };
    let through = run_cinch(&slow, &scene.thread, &PULL).expect("a healthy pull");
    let tension_n = through.first_pass_tension_n.expect("a pass below 3 N");
    assert!(tension_n < 1.5, "{through:?}");
    assert!(through.turn_lost_tension_n.is_some_and(|t| t < 3.0), "{through:?}");
    assert!(through.turns_end < through.turns_start - 0.8, "a turn came off: {through:?}");
}
