//! knotlab's simulated operating scene: the Rapier world (gantry, arms, instruments, suture, needle,
//! tissue) that implements the `knotlab-hw` device traits, and knot evaluation.
//!
//! - [`world`]: the simulated scene: rig bodies driven through servos, thread, grasps, forces.
//! - [`backend`]: the scene as `knotlab-hw` devices (arm servos, instrument drives, force sensors, clock).
//! - [`grasp`]: grasping as a constraint that slips above the grip force.
//! - [`knot`]: which knot a thread's centreline holds, whether it is down, the verdict.
//! - [`physics`]: the Rapier sets of a scene, its step and health check.
//! - [`scene`]: the scene file (TOML) and its checks.
//! - [`servo`]: how a joint follows its command (lag, limits, play, calibration).
//! - [`thread`]: the suture as a chain of capsules.
//! - [`tunnelling`]: detecting one capsule passing through another.

pub mod backend;
pub mod grasp;
pub mod knot;
pub mod physics;
pub mod scene;
pub mod servo;
pub mod thread;
pub mod tunnelling;
pub mod world;
