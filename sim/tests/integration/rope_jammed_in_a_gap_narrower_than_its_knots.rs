//! The nominal suture drawn between two parts closer together than its knots' section but wider than
//! the suture itself (the right's jaws shut on the 0.6 mm needle lie 0.78 mm apart, the knots'
//! section is 0.8 mm): it slides through at the pull that holds its other end, whatever the substep.
//! Pushed by metal at its knots' radius, it jammed there, held by a pull that grew as the square of
//! the substeps (7.9 N at 24 substeps, 0.52 N at 6, through plates 0.85 of 0.8 mm apart), and the
//! thread so jammed tore the tail out of the left's jaws at the finer steps.

use knotlab_sim::rope::RopeParams;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::validation::SutureUnderTest;
use knotlab_sim::validation::pinch::{HOLD_N, slides_at_n};

fn nominal_suture() -> SutureUnderTest {
    let scene = parse_scene(include_str!("../../../scenarios/default.toml"), "default.toml")
        .expect("the shipped scene parses");
    SutureUnderTest::from_scene(&scene).expect("the shipped scene's suture is the rope")
}

/// Plates 0.85 of the knots' diameter apart (0.68 mm) let the suture through at the pull that holds
/// its other end, at 6 and at 24 substeps; pushed at its knots' radius, the same rope needs more
/// than 1 N at 24 substeps (the check can fire).
#[test]
fn the_suture_slides_through_a_gap_its_knots_would_not_fit_at_every_substep() {
    let suture = nominal_suture();
    assert!(
        suture.diameter_at_metal_m() < 0.85 * suture.diameter_m(),
        "the nominal suture is pushed by metal at {} m across, its knots {} m",
        suture.diameter_at_metal_m(),
        suture.diameter_m()
    );
    let gap_m = 0.85 * suture.diameter_m();
    for substeps in [6, 24] {
        let pull_n = slides_at_n(&suture, RopeParams { substeps, ..suture.params }, gap_m, 2.0);
        assert!(
            pull_n.is_some_and(|n| n < 1.5 * HOLD_N),
            "at {substeps} substeps the suture slid through a {:.2} mm gap at {pull_n:?} N",
            gap_m * 1e3
        );
    }
    let fat = RopeParams { substeps: 24, metal_radius_m: None, ..suture.params };
    let pull_n = slides_at_n(&suture, fat, gap_m, 2.0);
    assert!(
        pull_n.is_none_or(|n| n > 1.0),
        "pushed at its knots' radius the rope slid through at {pull_n:?} N"
    );
}
