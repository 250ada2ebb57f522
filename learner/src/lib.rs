//! knotlab's learner: demonstrations, features, task patterns, segmentation into motion primitives, the
//! fluid solver, virtual obstacles and skill synthesis. It never depends on a physics engine.
//!
//! - [`demonstration`]: the demonstration files (`demo.toml` + a CSV per instrument), read and written.
//! - [`features`]: what a demonstration shows: motion starts and stops, accelerations, inflections and
//!   loops, force episodes, jaw events.
//! - [`pattern`]: hand-written task patterns (TOML).
//! - [`segment`]: matching a pattern against the features; decomposition or rejection; boundary metrics.
//! - [`primitive`]: primitives extracted into a versioned JSON knowledge base, in the stitch frame.
//! - [`synthetic`]: seeded synthetic demonstrations with known boundaries, for tests and benchmarks.
//! - [`fluid`]: the 2D Navier-Stokes solver that regenerates 2D primitives.
//! - [`obstacles`]: virtual obstacles, on the CPU and the GPU.
//! - [`synthesis`]: skills made from what was learned, at a new stitch site, by one of several methods.

pub mod demonstration;
pub mod features;
pub mod fluid;
pub mod obstacles;
pub mod pattern;
pub mod primitive;
pub mod segment;
pub mod synthesis;
pub mod synthetic;
