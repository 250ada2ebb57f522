//! Guards against friction between strands holding almost nothing. With the twist between segments
//! free, a strand wound twice round another, pulled with 0.3 N at one end and 0.15 N at the other,
//! slides off it whatever the friction (even 1.0, where the capstan equation allows a ratio of
//! 290,000): a capsule 0.4 mm round spins at the slightest torque, and the strands roll over each
//! other instead of sliding.
//! The shipped thread locks the twist; with the ends held as jaws hold them the wrap then holds a
//! ratio of 1.5 at the scene's friction (0.15: the equation allows 6.6), where the twist-free strand
//! slides to its end. (Laid twisted between segments it holds 2; laid untwisted it slides 12 mm
//! at 2.) `cargo bench -p knotlab-lab --bench thread_capstan` prints the whole table.

use knotlab_lab::cinch::{CapstanParams, run_capstan};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadParams;

const PULL: CapstanParams =
    CapstanParams { snug_n: 1.0, snug_s: 0.5, high_n: 0.3, low_n: 0.15, hold_s: 1.0, held_as_jaws: true };

/// A ratio of 1.5.
const GENTLE: CapstanParams = CapstanParams { low_n: 0.2, ..PULL };

/// The shipped thread locks its twist and holds a double wrap at a tension ratio of 1.5, where the
/// twist-free thread slides off.
#[test]
fn the_shipped_thread_holds_a_double_wrap_at_a_tension_ratio_of_1_5() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    assert!(!scene.thread.twist_free, "the shipped thread locks its twist");
    let held = run_capstan(&scene.solver, &scene.thread, &GENTLE).expect("a healthy pull");
    assert!(held.slip_m.abs() < 0.005, "{held:?}");
    assert!(!held.slid_to_end && held.turns_end > 2.0, "{held:?}");
    // The same wrap with the twist free rolls to its end.
    let rolling = ThreadParams { twist_free: true, ..scene.thread };
    match run_capstan(&scene.solver, &rolling, &GENTLE) {
        Ok(slid) => assert!(slid.slid_to_end || slid.turns_end < 1.0 || slid.slip_m > 0.01, "{slid:?}"),
        Err(e) => assert!(e.to_string().contains("moves at"), "{e}"),
    }
}

/// A twist-free thread's double wrap slides off even at friction 1 (or trips the speed check).
#[test]
fn with_the_twist_free_it_slides_even_at_friction_1() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let rolling = ThreadParams { twist_free: true, friction: 1.0, friction_on_itself: None, ..scene.thread };
    // Slid until its held end jammed against the other strand, or off it (a strand that flies off trips
    // the speed check).
    match run_capstan(&scene.solver, &rolling, &PULL) {
        Ok(slid) => assert!(slid.slid_to_end || slid.turns_end < 1.0 || slid.slip_m > 0.01, "{slid:?}"),
        Err(e) => assert!(e.to_string().contains("moves at"), "{e}"),
    }
}
