//! Virtual obstacles (the paper's section II.D): the cells of a 2D primitive's grid where putting the
//! instrument tip would make its arm collide with the other arms, the endoscope, the gantry, the table,
//! the patient or a scene obstacle, or where the arm cannot put it at all. Each cell is split into
//! subcells; at each, trocar-constrained IK places the arm, forward kinematics poses its link boxes,
//! and oriented-box tests check them. A cell with any colliding or unreachable subcell is blocked, and
//! the mask is grown to the fluid solver's rules.
//!
//! Two backends give the same grids: [`cpu`] (rayon, `hw`'s f64 kinematics) and, with the `gpu`
//! feature, `gpu` (a wgpu compute shader in WGSL porting the same closed-form IK and box tests to
//! f32). Results differ only at subcells within about 1e-5 m of a collision or reachability boundary.
//!
//! Collision geometry: the rig's URDF boxes; capsules and spheres become their bounding boxes.

pub mod check;
pub mod cpu;
pub mod error;
pub mod frames;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod grid;
pub mod mask;
pub mod obb;
pub mod plane;
pub mod postprocess;
pub mod prepare;
pub mod request;
pub mod sweep;
pub mod world;

pub use check::SubcellVerdict;
pub use cpu::compute_cpu;
pub use error::ObstacleError;
pub use grid::{CellVerdict, GridResult};
pub use mask::ObstacleMask;
pub use plane::GridPlane;
pub use prepare::PreparedGrid;
pub use request::{GridRequest, SubcellOrientation};
pub use sweep::{LinkCollision, first_link_collision};
pub use world::{ArmBoxes, ArmState, CollisionWorld, FixedBox, FixedKind, LinkBox};
