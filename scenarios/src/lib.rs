//! knotlab's scenarios: scene files and their randomization, the scripted expert who demonstrates, and
//! the task patterns (the files live in `scenarios/`, the code here).
//!
//! - [`expert`]: the scripted surgeon who ties the knot in the simulator and leaves a demonstration.

pub mod expert;
