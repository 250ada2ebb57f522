//! knotlab's scenarios: scene files and their randomization, the scripted expert who demonstrates, and
//! the task patterns (the files live in `scenarios/`, the code here).
//!
//! - [`episode`]: a trial driven step by step from outside (a policy, a Gymnasium environment).
//! - [`expert`]: the scripted surgeon who ties the knot in the simulator and leaves a demonstration.
//! - [`shipped`]: the shipped scene, demonstration, pattern, expert's plan and rigs, built in.
//! - [`session`]: the lab's workflow: teleoperation, the skill pedal, preview, execution, manual again.
//! - [`stress`]: the scripted stress sequence behind `knotlab sim`, on either suture model.
//! - [`trial`]: one trial end to end: a learned skill synthesized at a moved stitch, run, evaluated.

pub mod episode;
pub mod expert;
pub mod session;
pub mod shipped;
pub mod stress;
pub mod trial;
