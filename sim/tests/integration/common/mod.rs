//! What the sim tests share: the default scene's world, the left's jaws opened, then closed on a
//! thread laid across them with gravity off, and the rope scene's tissue with a way through its
//! stitch.
#![allow(dead_code)]

use knotlab_hw::kinematics::ArmJoints;
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_sim::physics::Physics;
use knotlab_sim::scene::{SceneConfig, parse_scene};
use knotlab_sim::tissue::Tissue;
use knotlab_sim::world::SimWorld;
use rapier3d::prelude::*;

/// The world of `scenarios/chain.toml` (the nominal scene with the capsule chain) on the shipped rig.
pub fn chain_world() -> SimWorld {
    let scene =
        parse_scene(include_str!("../../../../scenarios/chain.toml"), "chain.toml").expect("shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the shipped scene builds")
}

/// The world of `scenarios/default.toml` (the nominal scene, its suture the rope) on the shipped rig.
pub fn rope_world() -> SimWorld {
    let scene = parse_scene(include_str!("../../../../scenarios/default.toml"), "default.toml")
        .expect("shipped scene");
    SimWorld::new(scene, Rig::shipped().expect("shipped rig")).expect("the rope scene builds")
}

/// Frees the thread, opens the left's jaws `jaw_rad` and lets them get there (0.2 s); returns the
/// command that holds them open.
pub fn open_left_jaws(w: &mut SimWorld, jaw_rad: f64) -> ArmJoints {
    w.free_thread();
    let mut open = w.arm(ArmName::Left).command;
    open.tool.jaw_rad = jaw_rad;
    w.command(ArmName::Left, open);
    for _ in 0..200 {
        w.step().expect("healthy step");
    }
    open
}

/// Closes the left's jaws from `open` over `steps` steps with gravity off, so the thread laid across
/// them floats while they close (about 75 ms; it would fall 3 cm meanwhile), then turns gravity back on.
pub fn close_left_weightless(w: &mut SimWorld, open: ArmJoints, steps: usize) {
    let gravity = w.physics_mut().gravity;
    w.physics_mut().gravity = Vector::ZERO;
    let mut closed = open;
    closed.tool.jaw_rad = 0.0;
    w.command(ArmName::Left, closed);
    for _ in 0..steps {
        w.step().expect("healthy step");
    }
    w.physics_mut().gravity = gravity;
}

/// The rope scene's tissue in a physics world of its own, and a way for a rope through its stitch.
pub struct StitchBench {
    pub scene: SceneConfig,
    pub physics: Physics,
    pub tissue: Tissue,
    /// Out of the tissue, world frame.
    pub up: nalgebra::Vector3<f64>,
    /// Across the wound, towards the entry's flap, world frame.
    pub across: nalgebra::Vector3<f64>,
    /// The rope's two ends, the exit's and the entry's, world frame, m.
    pub ends: [nalgebra::Vector3<f64>; 2],
    /// From the exit's end through the stitch's four points to the entry's end, world frame, m.
    pub path: Vec<nalgebra::Vector3<f64>>,
}

/// [`StitchBench`] with the exit's end `exit_end_m` (up, out) from its hole and the entry's end
/// `entry_end_m` from its own, m.
pub fn rope_stitch_bench(exit_end_m: [f64; 2], entry_end_m: [f64; 2]) -> StitchBench {
    let scene = parse_scene(include_str!("../../../../scenarios/default.toml"), "default.toml")
        .expect("the shipped scene");
    let mut physics = Physics::new(&scene.solver);
    let tissue = Tissue::build(&mut physics, &scene.tissue, &scene.stitch);
    let frame = tissue.world_from_tissue;
    let (up, across) = (frame.rotation * nalgebra::Vector3::z(), frame.rotation * nalgebra::Vector3::y());
    let stitch = tissue.stitch_points_m(&physics).map(|(_, p)| p);
    let ends = [
        stitch[0] + up * exit_end_m[0] - across * exit_end_m[1],
        stitch[3] + up * entry_end_m[0] + across * entry_end_m[1],
    ];
    let mut path = vec![ends[0]];
    path.extend(stitch);
    path.push(ends[1]);
    StitchBench { scene, physics, tissue, up, across, ends, path }
}

/// The scene's suture as the capsule chain, for the tests of that model.
pub fn chain(suture: &knotlab_sim::suture::Suture) -> &knotlab_sim::suture::ChainSuture {
    suture.as_chain().expect("the scene's suture is the chain")
}
