//! The expert's wind that keeps the long end's tension (`winding_give_force_n`): the right's track
//! gives along the thread while its gauge reads more than the set force
//! ([`knotlab_hw::skill::ForceAction::Give`]) from the winding's start to the plan's end, and the plan
//! ends there: the fetch is planned from the world the wind leaves ([`plan_after_wind`]), the right
//! starting where its tip gave to rather than on its circle (a track that went back to the circle
//! would jerk the taut thread and tear the tail from the assist's jaws).

use super::common::expert;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::skill::ForceAction;
use knotlab_scenarios::expert::{
    TieGeometry, Variation, plan_after_wind, plan_instrument_tie, plan_tail_take,
};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;

fn rope_world() -> SimWorld {
    let scene = parse_scene(include_str!("../../default.toml"), "default.toml").expect("the shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("the rig")).expect("the rope scene builds")
}

/// With the tension kept, the first plan is the approach and the wind, its right track's one event a
/// give at the set force over the winding and on to the plan's end; the fetch to the look follows,
/// keeping no tension. Without it, no plan comes after the wind and the first plan reaches the look.
#[test]
fn keeping_the_tension_ends_the_first_plan_at_the_wound_coils() {
    let world = rope_world();
    let variation = Variation::none();
    let shipped = expert("instrument-tie.toml");
    assert_eq!(shipped.winding_give_force_n, None, "the shipped plan winds by position");
    let keeping = TieGeometry { winding_give_force_n: Some(0.5), ..shipped.clone() };
    let wound = plan_instrument_tie(&world, &keeping, &variation);
    let to_the_tail = plan_instrument_tie(&world, &shipped, &variation);
    let (wound_s, look_s) = (wound.duration_s(), to_the_tail.duration_s());
    assert!(wound_s + 2.0 < look_s, "the wind ends at {wound_s} s, the look at {look_s} s");
    let right = wound.tracks.iter().find(|t| t.arm == ArmName::Right).expect("the right's track");
    let [event] = right.events.as_slice() else { panic!("{:?}", right.events) };
    let rate_m_per_n_s = keeping.winding_give_rate_m_per_n_s;
    assert_eq!(event.action, ForceAction::Give { set_force_n: 0.5, rate_m_per_n_s });
    assert_eq!(event.threshold_n, 0.5);
    // From the winding's start (after the approach) to the plan's end.
    assert!(event.from_s > 1.0 && event.from_s + keeping.winding_s < wound_s, "{event:?}");
    assert!((event.until_s - wound_s).abs() < 1e-9, "{event:?} against {wound_s} s");
    // The fetch follows, from the world as it stands, holding no tension.
    let fetch = plan_after_wind(&world, &keeping, &variation).expect("the fetch after the wind");
    assert!(fetch.tracks.iter().all(|t| t.events.is_empty()), "{:?}", fetch.tracks);
    assert!(plan_tail_take(&world, &keeping, &variation).is_some(), "and the take after the look");
    assert!(plan_after_wind(&world, &shipped, &variation).is_none());
    let events =
        |skill: &knotlab_hw::skill::Skill| skill.tracks.iter().map(|t| t.events.len()).sum::<usize>();
    assert_eq!(events(&to_the_tail), 0, "the shipped plan keeps no tension before the look");
}
