//! The collision groups of the scene's bodies: which kinds of body may touch which.

use rapier3d::prelude::Group;

/// Collision group of thread segments.
pub const THREAD_GROUP: Group = Group::GROUP_1;
/// Collision group of robot links (instruments and arms).
pub const ROBOT_GROUP: Group = Group::GROUP_2;
/// Collision group of the environment (table, patient's torso, gantry): kept away from the thread,
/// which works inside the chest cavity the torso box stands for.
pub const ENVIRONMENT_GROUP: Group = Group::GROUP_3;
/// Collision group of the two flaps.
pub const FLAP_GROUP: Group = Group::GROUP_4;
/// Collision group of the pad under the flaps (the body wall the thread rests on).
pub const PAD_GROUP: Group = Group::GROUP_5;
