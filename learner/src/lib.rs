//! knotlab's learner: demonstrations, features, task patterns, segmentation into motion primitives, the
//! fluid solver, virtual obstacles and skill synthesis. It never depends on a physics engine. It grows
//! with the learner issues; today it only fixes the crate's place in the workspace (`hw` <- `learner`).

pub mod fluid;
pub mod obstacles;
