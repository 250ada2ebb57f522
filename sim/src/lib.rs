//! knotlab's simulated operating scene: the Rapier world (gantry, arms, instruments, suture, needle,
//! tissue) that implements the `knotlab-hw` device traits, and knot evaluation.
//!
//! - [`world`]: the simulated scene: rig bodies driven through servos, thread, grasps, forces.
//! - [`backend`]: the scene as `knotlab-hw` devices (arm servos, instrument drives, force sensors, clock).
//! - [`tissue`]: the pad and the two flaps of the wound, pulled open by an elastic load.
//! - [`stitch`]: the thread passing through the flaps, sliding with friction.
//! - [`needle`]: the half-circle needle on the thread's first segment.
//! - [`evaluate`]: the knot's verdict in the scene, with the holding test.
//! - [`grasp`]: grasping as a constraint that slips above the grip force.
//! - [`groups`]: the collision groups: which kinds of body may touch which.
//! - [`hooks`]: the contact filter (thread through the flaps and through the jaws holding it) and
//!   the thread's friction on itself.
//! - [`knot`]: which knot a thread's centreline holds, whether it is down, the verdict.
//! - [`physics`]: the Rapier sets of a scene, its step and health check.
//! - [`scene`]: the scene file (TOML) and its checks.
//! - [`snapshot`]: the scene drawn in top, front and side views (PNG).
//! - [`servo`]: how a joint follows its command (lag, limits, play, calibration).
//! - [`suture`]: the suture, one interface over its two models (the rope and the chain): stepping,
//!   its centreline, the jaws' holds on it, its pull on the instruments, its self-crossing watch.
//! - [`rope`]: the suture as an XPBD rope (the nominal model).
//! - [`thread`]: the suture as a chain of capsules.
//! - [`convert`]: between nalgebra's types and Rapier's, written once.
//! - [`chords`]: points a fixed chord apart along a polyline, where a thread is laid.
//! - [`tunnelling`]: detecting one capsule passing through another.
//! - [`crossing`]: detecting a strand of the thread passing through another, for either model.
//! - [`validation`]: the suture checked against mechanics (`knotlab validate`).

pub mod backend;
pub mod chords;
pub mod convert;
pub mod crossing;
pub mod evaluate;
pub mod gauge;
pub mod grasp;
pub mod groups;
pub mod hooks;
pub mod knot;
pub mod needle;
pub mod physics;
pub mod rope;
pub mod scene;
pub mod servo;
pub mod shapes;
pub mod snapshot;
pub mod stitch;
pub mod suture;
pub mod thread;
pub mod thread_watch;
pub mod tissue;
pub mod tunnelling;
pub mod validation;
pub mod world;
