//! Why the expert's knots slip: a square knot capsized, one strand drawn
//! straight with the other's collar wound round it, slides further under the load that the same knot
//! laid flat holds (`square_knot_holds_its_free_ends_let_go.rs`: friction 0.5 on itself, 0.3 N, free
//! ends let go), and its knot type never tells. Here, features 6 mm apart: 19.3 mm against 4.1 mm,
//! both then still. Over the nine layouts and frictions of `thread_reef`'s second table, capsized
//! slides further in six (by 3-15 mm or off), about as far in one, less in two: capsizing costs grip,
//! and the layout matters as much. The expert's knots are all capsized (`knot_at_release.bending`).

use knotlab_lab::reef::{ReefParams, run_reef};
use knotlab_sim::knot::KnotType;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadParams;

/// A capsized square knot, one strand drawn straight, slides further under the load the flat one holds,
/// while its knot type still reads square.
#[test]
fn a_square_knot_drawn_straight_through_one_strand_slides_under_the_load_the_flat_one_holds() {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let thread = ThreadParams { friction_on_itself: Some(0.5), ..scene.thread };
    let flat = ReefParams::snug_then_load(0.006, 0.3, true);
    let capsized = ReefParams { capsize_s: 1.0, ..flat };
    let flat = run_reef(&scene.solver, &thread, &flat).expect("a healthy pull");
    let capsized = run_reef(&scene.solver, &thread, &capsized).expect("a healthy pull");
    println!("flat: {flat:?}\ncapsized: {capsized:?}");
    // Capsizing draws red straight, and the type still reads square.
    assert!(flat.red_straightness < 0.8, "{flat:?}");
    assert!(capsized.red_straightness > 0.9, "{capsized:?}");
    assert_eq!(capsized.knot_snug, KnotType::Square, "{capsized:?}");
    // Flat, it holds; capsized, blue slides along red.
    assert!(flat.slip_m < 0.02 && flat.late_slip_m.abs() < 0.0005, "{flat:?}");
    // Measured: 4.1 mm flat, 19.3 mm capsized, both then still.
    assert!(capsized.slip_m > flat.slip_m + 0.01, "flat: {flat:?}\ncapsized: {capsized:?}");
}
