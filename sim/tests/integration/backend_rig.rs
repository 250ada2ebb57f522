//! The shipped simulated rig config (`scenarios/rigs/sim.toml`) built on the scene: the controller's
//! cycle is the scene's step, every arm reads and writes the scene, forces come back into the world
//! frame unchanged, and the emergency stop freezes the set-points in the cycle after the press while
//! the simulated joints come to rest on them.

use knotlab_hw::controller::{ControllerParams, Status};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_hw::rig_config::{build_rig, parse_rig_config};
use knotlab_hw::skill::{Orientation, PoseKey, Skill, Track};
use knotlab_sim::backend::SimBackend;
use knotlab_sim::scene::parse_scene;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

fn backend() -> (SimBackend, Rig) {
    let scene =
        parse_scene(include_str!("../../../scenarios/chain.toml"), "chain.toml").expect("the shipped scene");
    let rig = Rig::shipped().expect("the shipped rig");
    (SimBackend::new(SimWorld::new(scene, rig.clone()).expect("the scene builds")), rig)
}

/// The shipped sim rig config drives the scene one step per cycle, reads the scene's joints, and brings the
/// instruments' forces back to the world frame unchanged.
#[test]
fn the_shipped_sim_rig_drives_the_scene() {
    let (mut backend, rig) = backend();
    let config =
        parse_rig_config(include_str!("../../../scenarios/rigs/sim.toml"), "sim.toml").expect("parses");
    let built = build_rig(&config, &rig, Some(&mut backend)).expect("builds on the scene");
    assert_eq!(built.params, ControllerParams::default());
    assert_eq!(built.setups.len(), 4);
    let trocar = Vector3::from(backend.world().config().trocars.right);
    assert_eq!(built.setups[1].world_trocar_m, trocar, "trocars come from the scene");
    let (mut controller, _) = built.into_controller().expect("starts");
    assert_eq!(controller.period_s(), backend.world().config().solver.dt_s);
    let time_before = backend.world().time_s();
    for _ in 0..19 {
        controller.step().expect("a healthy cycle");
    }
    // A cycle reads the devices, then steps the scene: its record shows the scene as it was before.
    let (joints_before, forces_before): (Vec<_>, Vec<_>) = {
        let world = backend.world();
        ArmName::ALL.iter().map(|&a| (world.arm(a).actual(), world.arm(a).force_n)).unzip()
    };
    let record = controller.step().expect("a healthy cycle").clone();
    let world = backend.world();
    assert!(
        (world.time_s() - time_before - 20.0 * world.config().solver.dt_s).abs() < 1e-12,
        "one step per cycle"
    );
    for (i, arm) in ArmName::ALL.into_iter().enumerate() {
        let a = record.arm(arm).expect("every arm takes part");
        assert_eq!(a.measured, joints_before[i], "{arm}: the readings are the scene's joints");
        // Force: scene (world frame) -> sensor (shaft frame) -> record (world frame) is the identity.
        if arm.carries_instrument() {
            let f = forces_before[i];
            assert!(
                (a.world_force_n - f).norm() <= 1e-9 * (1.0 + f.norm()),
                "{arm}: {:?} vs {f:?}",
                a.world_force_n
            );
        }
    }
    let pulled = forces_before.iter().map(|f| f.norm()).fold(0.0, f64::max);
    println!("largest instrument force in the scene's start condition: {pulled:.3} N");
    assert!(pulled > 0.01, "some instrument feels a force, so the frame round trip is tested");
}

/// After an emergency stop the set-points freeze in the next cycle, the scene holds the last one, and the
/// simulated links come to rest on it within 150 ms.
#[test]
fn the_emergency_stop_freezes_the_set_points_and_the_scene_comes_to_rest() {
    let (mut backend, rig) = backend();
    let config = parse_rig_config(
        "description = \"left arm\"\n[arms.left]\nservo = { backend = \"sim\" }\ninstrument = { backend = \"sim\" }\n",
        "left.toml",
    )
    .expect("parses");
    let (mut controller, handles) =
        build_rig(&config, &rig, Some(&mut backend)).expect("builds").into_controller().expect("starts");
    let pedals = handles.pedals.expect("dummy pedals");
    let start = controller.record().arm(ArmName::Left).expect("left").world_from_tip.translation.vector;
    let key = |time_s: f64, p: Vector3<f64>| PoseKey {
        time_s,
        world_position_m: p.into(),
        orientation: Orientation::AlongShaft,
    };
    let skill = Skill {
        name: "down".into(),
        tracks: vec![Track {
            arm: ArmName::Left,
            poses: vec![key(0.0, start), key(2.0, start + Vector3::new(0.0, 0.0, -0.02))],
            jaw: vec![],
            events: vec![],
        }],
    };
    controller.load_skill(skill).expect("loads");
    for _ in 0..500 {
        controller.step().expect("runs");
    }
    let held = controller.record().arm(ArmName::Left).expect("left").commanded;
    pedals.set_emergency_stop(true);
    let record = controller.step().expect("runs");
    assert_eq!(record.status, Status::EmergencyStopped);
    assert_eq!(record.arm(ArmName::Left).expect("left").commanded, held, "no new set-point after the press");
    assert_eq!(backend.world().arm(ArmName::Left).command, held, "the scene holds the last set-point");
    // The servos (10 ms lag) bring the links onto the held set-point and they stay there.
    let mut last = record.arm(ArmName::Left).expect("left").measured;
    let mut moving_cycles = 0;
    for cycle in 1..=300 {
        let now = controller.step().expect("runs").arm(ArmName::Left).expect("left").measured;
        let moved = now.arm_rad.iter().zip(last.arm_rad).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        if moved > 1e-7 {
            moving_cycles = cycle;
        }
        last = now;
    }
    let off = last.arm_rad.iter().zip(held.arm_rad).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    println!(
        "after the press the links moved for {moving_cycles} ms, ending {off:.2e} rad from the held set-point"
    );
    assert!(moving_cycles < 150, "still moving after {moving_cycles} cycles");
    assert!(off < 1e-6, "the links rest {off} rad from the held set-point");
}
