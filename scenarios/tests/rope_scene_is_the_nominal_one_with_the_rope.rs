//! `scenarios/rope.toml` is the nominal scene with the suture as the XPBD rope and its friction on
//! itself at 0.5, nothing else changed, so that runs on it compare with the nominal scene's on the
//! suture's model alone.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadModel;

#[test]
fn the_rope_scene_differs_from_the_nominal_one_only_in_the_sutures_model_and_friction_on_itself() {
    let nominal = parse_scene(include_str!("../default.toml"), "default.toml").expect("the shipped scene");
    let mut rope = parse_scene(include_str!("../rope.toml"), "rope.toml").expect("the rope scene");
    assert_eq!(nominal.thread.model, ThreadModel::Chain);
    assert_eq!(rope.thread.model, ThreadModel::Rope);
    assert_eq!(rope.thread.friction_on_itself, Some(0.5));
    rope.thread.model = ThreadModel::Chain;
    rope.thread.friction_on_itself = nominal.thread.friction_on_itself;
    assert_eq!(rope, nominal, "every other setting as in default.toml");
}
