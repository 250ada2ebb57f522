//! knotlab's learner: demonstrations, features, task patterns, segmentation into motion primitives, the
//! fluid solver, virtual obstacles and skill synthesis. It never depends on a physics engine. It grows
//! with the learner issues; today it only fixes the crate's place in the workspace (`hw` <- `learner`).

pub mod demonstration;
pub mod features;
pub mod fluid;
pub mod obstacles;
pub mod pattern;
pub mod primitive;
pub mod segment;
pub mod synthetic;
