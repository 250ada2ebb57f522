//! The laid-knot trial's layout (`knotlab_lab::laid_knot`, the `laid_knot` benchmark): the scene's
//! thread laid as a loose square knot or surgeon's knot over the wound, through both stitch points,
//! and a clear error where the thread is too short for it.

use crate::common::chain;
use knotlab_hw::rig::Rig;
use knotlab_lab::laid_knot::{LaidKnotError, LaidKnotKind, LaidKnotParams, laid_knot_layout, lay_and_snug};
use knotlab_sim::evaluate::knot_now;
use knotlab_sim::knot::KnotType;
use knotlab_sim::scene::{SceneConfig, parse_scene};
use knotlab_sim::world::SimWorld;

fn scene() -> SceneConfig {
    parse_scene(
        include_str!("../../../scenarios/short-suture-friction-0.5.toml"),
        "short-suture-friction-0.5.toml",
    )
    .expect("shipped scene")
}

/// The laid thread spans its full length as a square knot through every stitch point, with no instrument
/// holding it.
#[test]
fn the_thread_is_laid_as_a_square_knot_through_both_stitch_points() {
    let params = LaidKnotParams::default();
    let mut length_m = None;
    let world = SimWorld::with_thread_laid(scene(), Rig::shipped().expect("shipped rig"), |c, t, p| {
        let path = laid_knot_layout(c, t, p, &params).expect("the thread is long enough");
        length_m = Some(path.windows(2).map(|w| (w[1] - w[0]).norm()).sum::<f64>());
        path
    })
    .expect("the scene builds");
    // The path is as long as the thread, the knot a square knot, the stitch's points on the thread.
    let length_m = length_m.expect("laid");
    assert!((length_m - world.config().thread.length_m).abs() < 1e-9, "{length_m} m");
    assert_eq!(knot_now(&world).map(|k| k.knot), Some(KnotType::Square));
    assert!(
        chain(world.suture())
            .stitch()
            .holes
            .iter()
            .chain(&chain(world.suture()).stitch().guides)
            .all(|h| h.segment.is_some())
    );
    // No instrument holds it.
    assert!(world.arms().iter().all(|a| a.hold().is_none()));
}

/// A surgeon's knot laid as two helices is named a surgeon's knot by the evaluator.
#[test]
fn the_surgeons_knot_is_laid_as_two_helices_the_evaluator_names_a_surgeons_knot() {
    let params = LaidKnotParams {
        kind: LaidKnotKind::SurgeonsKnot,
        spread_m: 0.008,
        lift_m: 0.0012,
        height_m: 0.004,
        ..LaidKnotParams::default()
    };
    let world = SimWorld::with_thread_laid(scene(), Rig::shipped().expect("shipped rig"), |c, t, p| {
        laid_knot_layout(c, t, p, &params).expect("the thread is long enough")
    })
    .expect("the scene builds");
    assert_eq!(knot_now(&world).map(|k| k.knot), Some(KnotType::SurgeonsKnot));
}

/// A thread too short for the laid knot is refused with `ThreadTooShort` instead of being laid.
#[test]
fn a_thread_too_short_for_the_knot_is_refused() {
    let mut short = scene();
    short.thread.length_m = 0.08;
    let result = lay_and_snug(short, Rig::shipped().expect("shipped rig"), &LaidKnotParams::default());
    assert!(matches!(result, Err(LaidKnotError::ThreadTooShort)), "{:?}", result.err());
}
