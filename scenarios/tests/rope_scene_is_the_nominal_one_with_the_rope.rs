//! `scenarios/rope.toml` is the nominal scene with the suture as the XPBD rope, its friction on
//! itself at 0.5, cut to 0.2 m and held in the tissue by 0.6 N a flap (session 48: the chain's 0.05 N,
//! which the rope ignored until then, let the first throw's draw drag the long end through the
//! stitch), nothing else changed, so that runs on it compare with the nominal scene's on the suture
//! alone.

use knotlab_sim::scene::parse_scene;
use knotlab_sim::thread::ThreadModel;

#[test]
fn the_rope_scene_differs_from_the_nominal_one_only_in_the_suture() {
    let nominal = parse_scene(include_str!("../default.toml"), "default.toml").expect("the shipped scene");
    let mut rope = parse_scene(include_str!("../rope.toml"), "rope.toml").expect("the rope scene");
    assert_eq!(nominal.thread.model, ThreadModel::Chain);
    assert_eq!(rope.thread.model, ThreadModel::Rope);
    assert_eq!(rope.thread.friction_on_itself, Some(0.5));
    assert_eq!((rope.thread.length_m, rope.stitch.slide_friction_n), (0.2, 0.6));
    rope.thread.model = ThreadModel::Chain;
    rope.thread.friction_on_itself = nominal.thread.friction_on_itself;
    rope.thread.length_m = nominal.thread.length_m;
    rope.stitch.slide_friction_n = nominal.stitch.slide_friction_n;
    assert_eq!(rope, nominal, "every other setting as in default.toml");
}
