//! What two throws hold in the simulated thread: a square knot, snugged by its four ends at
//! 1 N and then loaded by its standing parts with both free ends let go (as the holding test loads a
//! tied stitch), holds 0.3 N once the thread's friction on itself is 0.5, and comes apart at the
//! 3-0 monofilament's 0.15 even under 0.05 N (`cargo bench -p knotlab-lab --bench thread_reef`
//! prints the table). A first throw alone holds at no friction
//! (`throw_holds_the_loop_only_while_its_ends_are_held.rs`), so the expert must tie two, and the
//! thread's friction on itself decides whether they hold.

use knotlab_lab::reef::{ReefOutcome, ReefParams, run_reef};
use knotlab_sim::knot::KnotType;
use knotlab_sim::physics::HealthError;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadParams;

fn loaded(friction_on_itself: f64, load_n: f64, release_free: bool) -> Result<ReefOutcome, HealthError> {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let thread = ThreadParams { friction_on_itself: Some(friction_on_itself), ..scene.thread };
    let params = ReefParams::snug_then_load(0.006, load_n, release_free);
    run_reef(&scene.solver, &thread, &params)
}

/// At friction 0.5 on itself a square knot laid with its strands apart stays square and holds 0.3 N with
/// its free ends let go, settling a few millimetres at most.
#[test]
fn at_friction_0_5_the_square_knot_holds_with_its_free_ends_let_go() {
    let o = loaded(0.5, 0.3, true).expect("a healthy pull");
    assert_eq!(
        (o.knot_laid, o.knot_snug, o.knot_end),
        (KnotType::Square, KnotType::Square, KnotType::Square)
    );
    assert!(o.clearance_m > 0.0, "laid with the strands apart: {o:?}");
    // It settles by a few millimetres as the free ends let go, then stays.
    assert!(o.slip_m < 0.02 && o.late_slip_m.abs() < 0.0005, "{o:?}");
}

/// At friction 0.15 a square knot holds 0.05 N while its free ends are held and comes apart once they are
/// let go.
#[test]
fn at_friction_0_15_it_comes_apart_unless_its_free_ends_are_held() {
    let held = loaded(0.15, 0.05, false).expect("a healthy pull");
    assert_eq!(held.knot_end, KnotType::Square, "{held:?}");
    assert!(held.late_slip_m.abs() < 0.0005, "{held:?}");
    // Let go, the strands slide out of each other (a strand that flies off trips the speed check).
    match loaded(0.15, 0.05, true) {
        Ok(o) => assert_ne!(o.knot_end, KnotType::Square, "the knot held: {o:?}"),
        Err(e) => assert!(matches!(e, HealthError::Exploding { .. }), "{e}"),
    }
}
