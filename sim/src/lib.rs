//! knotlab's simulated operating scene: the Rapier world (gantry, arms, instruments, suture, needle,
//! tissue) that implements the `knotlab-hw` device traits, and knot evaluation.
//!
//! - [`knot`]: which knot a thread's centreline holds, whether it is down, the verdict.

pub mod knot;
