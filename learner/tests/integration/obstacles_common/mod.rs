//! Scenes for the virtual-obstacle tests: the shipped rig with the nominal scene's trocars and parked
//! poses (as sim parks them), and seeded random variations.
#![allow(dead_code)]

use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::obstacles::{
    ArmState, CollisionWorld, GridPlane, GridRequest, PreparedGrid, SubcellOrientation,
};
use nalgebra::{Rotation3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The tissue centre of scenarios/default.toml.
pub const TISSUE_M: [f64; 3] = [0.0, 0.0, 0.95];

/// The trocars of scenarios/default.toml.
pub fn trocar(name: ArmName) -> Vector3<f64> {
    match name {
        ArmName::Left => Vector3::new(-0.08, 0.12, 1.02),
        ArmName::Right => Vector3::new(-0.08, -0.12, 1.02),
        ArmName::Assist => Vector3::new(0.12, 0.10, 1.02),
        ArmName::Camera => Vector3::new(-0.14, 0.0, 1.02),
    }
}

/// The parked pose sim gives an arm: tip 4 cm past its trocar towards `tissue`, along the shaft.
pub fn parked(rig: &Rig, name: ArmName, trocar_m: &Vector3<f64>, tissue: &Vector3<f64>) -> ArmJoints {
    let towards = (tissue - trocar_m).normalize();
    let target =
        TipTarget { world_position_m: trocar_m + towards * 0.04, orientation: TipOrientation::AlongShaft };
    let mut joints =
        rig.arm(name).model.solve_tip(&target, trocar_m, &name.ready_joints()).expect("parked pose");
    if name.carries_instrument() {
        joints.tool.jaw_rad = 0.6;
    }
    joints
}

/// Every arm parked at the nominal trocars.
pub fn nominal_states(rig: &Rig) -> Vec<ArmState> {
    let tissue = Vector3::from(TISSUE_M);
    ArmName::ALL
        .iter()
        .map(|&name| ArmState {
            name,
            trocar_m: trocar(name),
            joints: parked(rig, name, &trocar(name), &tissue),
        })
        .collect()
}

/// The nominal world.
pub fn nominal_world(rig: &Rig) -> CollisionWorld {
    CollisionWorld::from_rig(rig, &nominal_states(rig)).expect("nominal world")
}

/// A horizontal square of `size_m` centred on `centre`.
pub fn square(centre: Vector3<f64>, size_m: f64, cells: usize, subcells: usize) -> GridPlane {
    let origin = centre - Vector3::new(0.5 * size_m, 0.5 * size_m, 0.0);
    GridPlane::new(origin, Vector3::x(), Vector3::y(), size_m, cells, subcells).expect("plane")
}

/// A seeded random scene: the arm that moves, trocars and other arms' joints jittered, obstacle boxes
/// near the moving instrument's path, a tilted plane of random size near the tissue, and a random tip
/// orientation.
pub fn random_scene(rig: &Rig, seed: u64, cells: usize, subcells: usize) -> (CollisionWorld, GridRequest) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let tissue = Vector3::from(TISSUE_M)
        + Vector3::new(rng.random_range(-0.02..0.02), rng.random_range(-0.02..0.02), 0.0);
    let moving = ArmName::ALL[rng.random_range(0..4)];
    let states: Vec<ArmState> = ArmName::ALL
        .iter()
        .map(|&name| {
            let t = trocar(name)
                + Vector3::new(rng.random_range(-0.02..0.02), rng.random_range(-0.02..0.02), 0.0);
            let mut joints = parked(rig, name, &t, &tissue);
            if name != moving {
                for q in &mut joints.arm_rad {
                    *q += rng.random_range(-0.15..0.15);
                }
            }
            ArmState { name, trocar_m: t, joints }
        })
        .collect();
    let mut world = CollisionWorld::from_rig(rig, &states).expect("world");
    let height = rng.random_range(0.0..0.06);
    let centre = tissue + Vector3::new(rng.random_range(-0.03..0.03), rng.random_range(-0.03..0.03), height);
    let size = rng.random_range(0.04..0.25);
    let tilt = Rotation3::from_euler_angles(
        rng.random_range(-0.4..0.4),
        rng.random_range(-0.4..0.4),
        rng.random_range(-3.2..3.2),
    );
    let (u, v) = (tilt * Vector3::x(), tilt * Vector3::y());
    let plane = GridPlane::new(centre - (u + v) * (0.5 * size), u, v, size, cells, subcells).expect("plane");
    // Obstacles on the way from the moving arm's trocar to the plane, and near the plane.
    let from = states.iter().find(|s| s.name == moving).map(|s| s.trocar_m).expect("moving arm");
    for k in 0..rng.random_range(0..4) {
        let along = rng.random_range(0.3..1.1);
        let at = from
            + (centre - from) * along
            + Vector3::new(
                rng.random_range(-0.03..0.03),
                rng.random_range(-0.03..0.03),
                rng.random_range(-0.02..0.02),
            );
        let half = Vector3::new(
            rng.random_range(0.002..0.02),
            rng.random_range(0.002..0.02),
            rng.random_range(0.002..0.02),
        );
        world.add_obstacle(&format!("obstacle {k}"), at, half).expect("obstacle");
    }
    let orientation = if moving.carries_instrument() && rng.random_bool(0.4) {
        let dir = Vector3::new(rng.random_range(-0.5..0.5), rng.random_range(-0.5..0.5), -1.0);
        SubcellOrientation::JawDirection(dir)
    } else {
        SubcellOrientation::AlongShaft
    };
    (world, GridRequest { arm: moving, plane, orientation })
}

/// A prepared random scene.
pub fn random_prepared(rig: &Rig, seed: u64, cells: usize, subcells: usize) -> PreparedGrid {
    let (world, request) = random_scene(rig, seed, cells, subcells);
    PreparedGrid::new(&world, &request).expect("prepared")
}
