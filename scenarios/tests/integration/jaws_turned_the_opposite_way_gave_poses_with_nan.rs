//! Regression: the left's jaws wound round pointing straight up (`left_jaw_direction = [0, 0, 1]`)
//! and then turned to fetch the tail pointing straight down (the shipped `[left_fetches]`) planned
//! poses that were not numbers: the turn blended the two directions, and half way opposite
//! directions blend to zero. The controller then refused the skill
//! (`tracks[0].poses[1391].world_position_m: not finite`). Such a turn now goes about a side at
//! right angles; the plan stays finite and well formed.

use knotlab_hw::rig::Rig;
use knotlab_scenarios::expert::{TieGeometry, Variation, plan_instrument_tie};
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;

/// Jaws wound pointing straight up and then turned straight down to fetch the tail plan only finite,
/// well-formed poses.
#[test]
fn jaws_wound_pointing_up_then_turned_down_to_the_tail() {
    let scene = parse_scene(include_str!("../../chain.toml"), "chain.toml").expect("the chain scene");
    let world = SimWorld::new(scene, Rig::shipped().expect("the shipped rig")).expect("the scene builds");
    let geometry = TieGeometry { left_jaw_direction: Some([0.0, 0.0, 1.0]), ..TieGeometry::default() };
    let down = geometry.left_fetches.as_ref().map(|f| f.jaw_direction);
    assert_eq!(down, Some([0.0, 0.0, -1.0]), "the shipped fetch turns the jaws straight down");
    let skill = plan_instrument_tie(&world, &geometry, &Variation::none());
    skill.check().expect("every pose finite");
}
