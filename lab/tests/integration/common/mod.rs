//! What the lab's tests share: the scenes and ropes they start from.

use knotlab_sim::scene::{SceneConfig, parse_scene};

/// `scenarios/short-suture-friction-0.5.toml`, the scene the rope's knot trials use.
pub fn short_suture_friction_0_5() -> SceneConfig {
    parse_scene(
        include_str!("../../../../scenarios/short-suture-friction-0.5.toml"),
        "short-suture-friction-0.5.toml",
    )
    .expect("shipped scene")
}

/// A tight surgeon's knot for the rope's wound trials: helices of 0.22 mm radius, 1.6 mm either
/// side of the wound, 1 mm over the tissue, snugged at 2 N for 6 s. Snugged for less, the knot may
/// still be settling when it is let go: snugged 2, 3, 4, 6 s, the rope at friction 0.5 let the
/// hand-integrated wound open 0.56, 0.00, 0.00, 0.00 mm and the Rapier flaps 0.01, 0.94, 0.01, 0.01.
pub fn tight_surgeons_knot() -> knotlab_lab::laid_knot::LaidKnotParams {
    knotlab_lab::laid_knot::LaidKnotParams {
        kind: knotlab_lab::laid_knot::LaidKnotKind::SurgeonsKnot,
        spread_m: 0.0016,
        lift_m: 0.00022,
        height_m: 0.001,
        snug_n: 2.0,
        snug_s: 6.0,
        ..Default::default()
    }
}

/// The rope at friction 0.5 on itself (kinetic 0.4), damped lightly (10/s).
pub fn rope_at_friction_0_5() -> knotlab_sim::rope::RopeParams {
    knotlab_sim::rope::RopeParams {
        static_friction: 0.5,
        kinetic_friction: 0.4,
        damping_per_s: 10.0,
        ..Default::default()
    }
}

/// The scene's suture as the capsule chain, for the tests of that model.
pub fn chain(suture: &knotlab_sim::suture::Suture) -> &knotlab_sim::suture::ChainSuture {
    suture.as_chain().expect("the scene's suture is the chain")
}
