//! The learner crate's integration tests, one binary: one link, and the tests of every file run side by side. Each module
//! guards what its doc comment says.

mod obstacles_common;

mod approach_first_key_not_before_zero;
mod demonstration_malformed;
mod demonstration_roundtrip;
mod fluid_cavity_ghia;
mod fluid_particle;
mod fluid_path;
mod fluid_primitive;
mod fluid_solids;
mod fluid_solver;
mod obstacles_cpu;
mod obstacles_gpu;
mod obstacles_obb;
mod obstacles_postprocess;
mod obstacles_sweep;
mod obstacles_world;
mod segment_features;
mod segment_pattern;
mod segment_primitives;
mod segment_rejection;
mod segment_synthetic;
mod synthesis_rules;
