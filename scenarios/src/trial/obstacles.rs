//! The obstacles a 2D primitive's fluid flows around at the trial's site: virtual obstacles (the cells
//! where the instrument's tip would make its arm hit another arm, the endoscope, the gantry, the table,
//! the patient or a scene obstacle, or cannot be put at all), computed on the CPU for the primitive's
//! moved plane with the other arms where the scene starts them.

use knotlab_hw::rig::{ArmName, Rig};
use knotlab_learner::fluid::{GridRegion, ObstacleMask, PlaneFrame};
use knotlab_learner::obstacles::{
    ArmState, CollisionWorld, GridPlane, GridRequest, PreparedGrid, SubcellOrientation, compute_cpu,
};
use knotlab_learner::synthesis::SynthesisError;
use knotlab_sim::world::{SimWorld, trocar_of};
use nalgebra::Vector3;

/// Subcells per cell side (the paper's 5 x 5).
pub const SUBCELLS: usize = 5;

/// What virtual obstacles a trial found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObstacleLog {
    /// Per 2D primitive: its name, the cells blocked (after the fluid's rules), the cells in all.
    pub grids: Vec<(String, usize, usize)>,
}

/// The collision world of `world` as it starts: every arm at its joints, the scene's obstacles.
pub fn collision_world(world: &SimWorld) -> Result<CollisionWorld, SynthesisError> {
    let problem = |reason: String| SynthesisError::Invalid { field: "virtual obstacles".into(), reason };
    let states: Vec<ArmState> = ArmName::ALL
        .iter()
        .map(|&name| ArmState {
            name,
            trocar_m: trocar_of(world.config(), name),
            joints: world.arm(name).command,
        })
        .collect();
    let rig: &Rig = world.rig();
    let mut collision = CollisionWorld::from_rig(rig, &states).map_err(|e| problem(e.to_string()))?;
    for (k, o) in world.config().obstacles.iter().enumerate() {
        collision
            .add_obstacle(
                &format!("obstacles[{k}]"),
                Vector3::from(o.centre_m),
                Vector3::from(o.half_extents_m),
            )
            .map_err(|e| problem(e.to_string()))?;
    }
    Ok(collision)
}

/// The virtual obstacles of `arm`'s tip over `region` of `plane`, the jaws pointing along `jaw_direction`.
pub fn virtual_obstacles(
    collision: &CollisionWorld,
    arm: ArmName,
    plane: &PlaneFrame,
    region: &GridRegion,
    jaw_direction: Vector3<f64>,
) -> Result<ObstacleMask, SynthesisError> {
    let problem = |reason: String| SynthesisError::Invalid { field: "virtual obstacles".into(), reason };
    let grid = GridPlane::new(
        plane.to_world(&region.origin_m),
        plane.axis_x,
        plane.axis_y,
        region.size_m(),
        region.n,
        SUBCELLS,
    )
    .map_err(|e| problem(e.to_string()))?;
    let request =
        GridRequest { arm, plane: grid, orientation: SubcellOrientation::JawDirection(jaw_direction) };
    let prepared = PreparedGrid::new(collision, &request).map_err(|e| problem(e.to_string()))?;
    let result = compute_cpu(&prepared, false);
    ObstacleMask::new(region.n, result.mask.blocked).map_err(|e| problem(e.to_string()))
}
