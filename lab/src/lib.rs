//! knotlab's experiment rigs: small scenes built to measure one behaviour of a suture model, which
//! the tests and the benchmarks that print tables of experiments run. No trial uses them, and nothing
//! the product needs depends on this crate.
//!
//! - [`cinch`]: a strand wound twice round another and pulled: how much tension the contacts hold.
//! - [`reef`]: a square knot of two strands, loaded with its free ends let go: does it hold?
//! - [`laid_knot`]: a square or surgeon's knot laid over the stitch and snugged: does it pass the
//!   holding test?
//! - [`scenes`]: the scenes they start from (the chain's, the short suture's), the chain made finer.
//! - [`trials`]: the rope's knot trials (the capstan, the reef knot, the wound pair).
//! - [`wound`]: a surgeon's knot laid in the rope and tied over a wound whose flaps are integrated by
//!   hand, snugged, released and loaded.
//! - [`tissue_trial`]: the same trial with the scene's own tissue (the flaps as Rapier's bodies).

pub mod cinch;
pub mod laid_knot;
pub mod reef;
pub mod scenes;
pub mod tissue_trial;
pub mod trials;
pub mod wound;
