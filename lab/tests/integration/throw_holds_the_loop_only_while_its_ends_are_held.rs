//! What a surgeon's throw alone holds in the simulated thread: a strand wound twice round
//! another and snugged at 1 N holds the loop's 0.3 N while its free ends are held, as the instruments
//! hold them before they let go; with both free ends let go (the knot as the holding test loads it)
//! the turns slide off under a sixth of that, at the scene's friction as at 1.0 (`cargo bench -p knotlab-lab --bench
//! thread_holding` prints the table). A frictional string obeys the capstan equation: a wrap whose one
//! end is slack cannot hold the other, so a first throw let go has nothing to hold the wound with; a
//! surgeon lays the second throw before letting go. If a change to the thread model makes a lone
//! throw hold, the second assertion tells: the expert's plan rests on it.

use knotlab_lab::cinch::{HoldingParams, run_holding};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadParams;

fn loaded(release: bool, friction: f64, loop_n: f64) -> knotlab_lab::cinch::HoldingOutcome {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    let thread = ThreadParams { friction, friction_on_itself: None, ..scene.thread };
    let params = HoldingParams {
        snug_n: 1.0,
        snug_s: 0.5,
        loop_n,
        hold_s: 1.0,
        release_a: release,
        release_b: release,
    };
    run_holding(&scene.solver, &thread, &params).expect("a healthy pull")
}

/// A surgeon's throw snugged at 1 N keeps its turns and holds the loop's 0.3 N while its free ends are held.
#[test]
fn held_by_its_free_ends_the_throw_holds_the_loop() {
    let held = loaded(false, 0.15, 0.3);
    assert!(held.turns_end > 2.0, "{held:?}");
    assert!(held.slip_m.abs() < 0.005 && held.late_slip_m.abs() < 0.001, "{held:?}");
}

/// A lone throw with its free ends let go loses its turns under 0.05 N, at friction 1 as at 0.15.
#[test]
fn let_go_the_throw_slides_off_even_at_friction_1() {
    for friction in [0.15, 1.0] {
        let o = loaded(true, friction, 0.05);
        assert!(o.turns_snug > 2.0, "friction {friction}: snugged {o:?}");
        assert!(o.turns_end < 1.0, "friction {friction}: the turns held: {o:?}");
    }
}
