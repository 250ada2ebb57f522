//! Experiment rigs: small scenes built to measure one behaviour of the rope in a wound, which the tests
//! and the benchmarks run; no trial uses them.
//!
//! - [`wound`]: a surgeon's knot laid in the rope and tied over a wound whose flaps are integrated by
//!   hand, snugged, released and loaded.
//! - [`tissue_trial`]: the same trial with the scene's own tissue (the flaps as Rapier's bodies).

pub mod tissue_trial;
pub mod wound;
