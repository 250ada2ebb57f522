//! The simulated operating scene: the rig's links as bodies driven through joint servos, the suture,
//! grasps, and the instruments' force readings. The controller drives it through joint commands, as
//! it would drive the real robots.

//!
//! - `arm`: one arm: servos, command, jaw state, gauge reading.
//! - `build`: the scene built from its file.
//! - `jaws`: the jaws taking, letting go of and slipping off the suture.
//! - `gauges`: the instruments' force readings.

mod arm;
mod build;
mod gauges;
mod jaws;

use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::{IsometryMatrix3, Point3, Vector3};
use rand_chacha::ChaCha8Rng;
use rapier3d::prelude::*;

use crate::convert::matrix_to_pose;
use crate::grasp::GraspEvent;
pub use crate::grasp::{GRASP_REACH_M, JAW_CENTRE_OFFSET_M};
use crate::physics::{HealthError, Physics};
use crate::scene::SceneConfig;
use crate::suture::Suture;
use crate::suture::layout::start_layout;
pub use crate::suture::{HELD_CLEARANCE_M, JAW_CLEAR_M, SLIP_OUT_FACTOR};
use crate::tissue::Tissue;
pub use arm::{JawState, SimArm};

/// Why a scene cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WorldError {
    /// An instrument cannot be placed through its trocar.
    #[error("trocars.{arm}: the {arm} arm cannot put its tool through this trocar: {reason}")]
    TrocarUnreachable {
        /// The arm.
        arm: ArmName,
        /// What the kinematics said.
        reason: knotlab_hw::kinematics::IkError,
    },
    /// An instrument cannot reach the point where the start condition wants it to hold the thread.
    #[error("start.{key}: the {arm} instrument cannot reach it: {reason}")]
    StartUnreachable {
        /// The scene key.
        key: &'static str,
        /// The arm.
        arm: ArmName,
        /// What the kinematics said.
        reason: knotlab_hw::kinematics::IkError,
    },
    /// The instrument at a start point did not close on the thread.
    #[error("start.{key}: the {arm} jaws found no thread to hold there")]
    StartNotHeld {
        /// The scene key.
        key: &'static str,
        /// The arm.
        arm: ArmName,
    },
}

/// The simulated scene.
pub struct SimWorld {
    /// The Rapier sets.
    pub(crate) physics: Physics,
    /// The robots.
    pub(crate) rig: Rig,
    /// The four arms, in [`ArmName::ALL`] order.
    pub(crate) arms: Vec<SimArm>,
    /// The suture (the rope or the chain), its needle and its self-crossing watch.
    pub(crate) suture: Suture,
    /// The pad and the two flaps of the wound.
    pub(crate) tissue: Tissue,
    /// Body of each URDF link with collision geometry (indexed like the rig's tree links).
    pub(crate) link_bodies: Vec<Option<RigidBodyHandle>>,
    /// The moving links that are fixed bodies, posed after each step (with the rope: the arms'
    /// links before the flange), with their indices in the rig's tree.
    posed_links: Vec<(usize, RigidBodyHandle)>,
    /// Simulated time, s.
    pub(crate) time_s: f64,
    /// Grasp events so far.
    pub(crate) events: Vec<GraspEvent>,
    /// The scene it was built from.
    pub(crate) config: SceneConfig,
    /// Jaw openings below this count as closed, rad.
    pub(crate) jaw_closed_rad: f64,
    /// Pull at which a grasp slips, N.
    pub(crate) grip_force_n: f64,
    /// The strain gauges' noise source.
    noise: ChaCha8Rng,
}

/// `next` with its quaternion in the same hemisphere as `current`'s: the same pose, but Rapier derives
/// a kinematic body's velocity from the quaternion of `next * current^-1` without taking its shorter
/// arc, so a sign flip between two steps (which `from_rotation_matrix` makes wherever its branch
/// changes) became a one-step spin of hundreds of rad/s that flung the thread off a shaft
/// (`sim/tests/integration/kinematic_link_spun_when_its_quaternion_flipped_sign.rs`).
fn continuous_pose(next: Pose, current: &Pose) -> Pose {
    if next.rotation.dot(current.rotation) < 0.0 {
        Pose::from_parts(next.translation, -next.rotation)
    } else {
        next
    }
}

impl SimWorld {
    /// The jaw opening the scene starts with, rad.
    pub const JAW_OPEN_RAD: f64 = 0.6;

    /// Builds the scene in the knot-tying task's start condition: the thread runs through the stitch,
    /// its needle held by the right instrument and its tail by the assist (where `config.start` says);
    /// the left instrument and the endoscope are parked 4 cm inside their trocars.
    pub fn new(config: SceneConfig, rig: Rig) -> Result<Self, WorldError> {
        let mut world = Self::with_thread_laid(config, rig, |config, tissue, physics| {
            start_layout(config, tissue, physics)
        })?;
        // The start condition: the right jaws on the needle, the assist's on the tail.
        for (arm, key) in [(ArmName::Right, "needle_m"), (ArmName::Assist, "tail_m")] {
            let poses = world.link_poses();
            if !world.try_grasp(arm, &poses) {
                return Err(WorldError::StartNotHeld { key, arm });
            }
        }
        Ok(world)
    }

    /// Joints that put `arm`'s jaw centre at `jaw_centre_m` (world), nearest its last command, the jaw
    /// opening unchanged.
    pub fn joints_for_jaw_centre(
        &self,
        arm: ArmName,
        jaw_centre_m: &Vector3<f64>,
    ) -> Result<ArmJoints, knotlab_hw::kinematics::IkError> {
        let trocar = trocar_of(&self.config, arm);
        let current = self.arm(arm).command;
        let mut joints = self.rig.arm(arm).model.solve_tip(
            &tip_for_jaw_centre(&trocar, jaw_centre_m),
            &trocar,
            &current,
        )?;
        joints.tool.jaw_rad = current.tool.jaw_rad;
        Ok(joints)
    }

    /// Seeds the strain gauges' noise (the same seed gives the same readings).
    pub fn reseed(&mut self, seed: u64) {
        self.noise = rand::SeedableRng::seed_from_u64(seed);
    }

    /// Opens every instrument's jaws: grasps are released at the next step.
    pub fn release_all(&mut self) {
        for arm in &mut self.arms {
            if arm.name.carries_instrument() {
                // Past the angle the jaws took what they hold at: jaws opened less still squeeze it.
                let past_grasp_rad = match &arm.jaws {
                    JawState::Holding { at_jaw_rad, .. } => at_jaw_rad + 0.05,
                    _ => 0.0,
                };
                arm.command.tool.jaw_rad = Self::JAW_OPEN_RAD.max(past_grasp_rad);
            }
        }
    }

    /// Lets go of everything and takes the thread out of the tissue: a free thread for experiments.
    pub fn free_thread(&mut self) {
        for a in 0..self.arms.len() {
            if self.arms[a].holds()
                && let JawState::Holding { hold, .. } =
                    std::mem::replace(&mut self.arms[a].jaws, JawState::Free)
            {
                self.suture.release(a, hold, &mut self.physics, false);
            }
            if self.arms[a].name.carries_instrument() {
                self.arms[a].command.tool.jaw_rad = Self::JAW_OPEN_RAD;
            }
        }
        self.suture.unstitch(&mut self.physics);
    }

    /// Pulls each flap away from the wound with `outward_n` more (negative: less), N: a force on
    /// the chain's dynamic flaps, a load on the rope's slides.
    pub fn pull_flaps_open(&mut self, outward_n: f64) {
        self.suture.pull_flaps_open(&mut self.physics, &self.tissue, outward_n);
    }

    /// The suture (the rope or the chain), its needle and its self-crossing watch.
    pub fn suture(&self) -> &Suture {
        &self.suture
    }

    /// The Rapier sets.
    pub fn physics(&self) -> &Physics {
        &self.physics
    }

    /// The Rapier sets, to change by hand (experiments that move bodies or turn gravity off).
    pub fn physics_mut(&mut self) -> &mut Physics {
        &mut self.physics
    }

    /// The suture and the Rapier sets to change, together (experiments that lay the chain by hand).
    pub fn suture_and_physics_mut(&mut self) -> (&Suture, &mut Physics) {
        (&self.suture, &mut self.physics)
    }

    /// The robots.
    pub fn rig(&self) -> &Rig {
        &self.rig
    }

    /// The four arms, in [`ArmName::ALL`] order.
    pub fn arms(&self) -> &[SimArm] {
        &self.arms
    }

    /// One arm, to change by hand (an experiment setting its jaws' state).
    pub fn arm_mut(&mut self, name: ArmName) -> &mut SimArm {
        let i = ArmName::ALL.iter().position(|a| *a == name).unwrap_or(0);
        &mut self.arms[i]
    }

    /// The pad and the two flaps of the wound.
    pub fn tissue(&self) -> &Tissue {
        &self.tissue
    }

    /// Where `flap`'s stitch point is now, world frame, m.
    pub fn hole_m(&self, flap: crate::tissue::Flap) -> Vector3<f64> {
        self.tissue.hole_m(&self.physics, flap)
    }

    /// The body of the rig's link `link` (an index into its tree's links), if it has collision
    /// geometry.
    pub fn link_body(&self, link: usize) -> Option<RigidBodyHandle> {
        self.link_bodies.get(link).copied().flatten()
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// What the jaws did so far, in order.
    pub fn events(&self) -> &[GraspEvent] {
        &self.events
    }

    /// The scene it was built from.
    pub fn config(&self) -> &SceneConfig {
        &self.config
    }

    /// Jaw openings below this count as closed, rad.
    pub fn jaw_closed_rad(&self) -> f64 {
        self.jaw_closed_rad
    }

    /// The pull at which the jaws' grip on the thread slips, N.
    pub fn grip_force_n(&self) -> f64 {
        self.grip_force_n
    }

    /// The suture's centreline, needle end first, m: the chain's segment ends or the rope's
    /// particles.
    pub fn thread_centreline(&self) -> Vec<Vector3<f64>> {
        self.suture.centreline(&self.physics)
    }

    /// Where `flap`'s stitch point sits on the suture: the arc length from the needle end, m
    /// (`None` while the thread is not through it).
    pub fn stitch_arc_at_m(&self, flap: crate::tissue::Flap) -> Option<f64> {
        self.suture.arc_at_m(&self.physics, &self.tissue, flap)
    }

    /// The points of the centreline ([`Self::thread_centreline`]) in the tissue, from the exit's to
    /// the entry's, with one either side for the chain.
    pub fn thread_inside(&self) -> Option<std::ops::RangeInclusive<usize>> {
        self.suture.inside()
    }

    /// Which points of the thread touch which robot links now: `(point, link name)`, points from
    /// the needle end, sorted ([`Suture::touching`]). Shows where the thread lies on the
    /// instruments, e.g. turns wound round an instrument that should not hold them.
    pub fn thread_contacts(&self) -> Vec<(usize, String)> {
        let links: Vec<(String, RigidBodyHandle)> = self
            .link_bodies
            .iter()
            .enumerate()
            .filter_map(|(k, body)| Some((self.rig.tree.links[k].name.clone(), (*body)?)))
            .collect();
        self.suture.touching(&self.physics, &links)
    }

    /// The wound gap between the flaps' inner faces, m.
    pub fn wound_gap_m(&self) -> f64 {
        self.tissue.gap_m(&self.physics)
    }

    /// Rigid bodies in the scene.
    pub fn body_count(&self) -> usize {
        self.physics.bodies.len()
    }

    fn link_poses(&self) -> Vec<IsometryMatrix3<f64>> {
        let mut positions = vec![0.0; self.rig.tree.joints.len()];
        for arm in &self.arms {
            self.rig.arm(arm.name).write_tree_positions(&arm.actual(), &mut positions);
        }
        self.rig.tree.root_from_links(&positions)
    }

    /// Commands one arm's joints (the jaw opening included).
    pub fn command(&mut self, arm: ArmName, joints: ArmJoints) {
        if let Some(a) = self.arms.iter_mut().find(|a| a.name == arm) {
            a.command = joints;
        }
    }

    /// One arm.
    pub fn arm(&self, name: ArmName) -> &SimArm {
        let i = ArmName::ALL.iter().position(|a| *a == name).unwrap_or(0);
        &self.arms[i]
    }

    /// The tip pose of an arm as its links stand now.
    pub fn world_from_tip(&self, name: ArmName) -> IsometryMatrix3<f64> {
        self.rig.arm(name).model.world_from_tip(&self.arm(name).actual())
    }

    /// Advances one step: servos, link poses, grasps, physics, slip and force readings.
    pub fn step(&mut self) -> Result<(), HealthError> {
        let dt = self.config.solver.dt_s;
        let mut positions = vec![0.0; self.rig.tree.joints.len()];
        for arm in &mut self.arms {
            let command = arm.command.to_array();
            for ((servo, state), q) in arm.servos.iter().zip(arm.states.iter_mut()).zip(command) {
                servo.step(state, q, dt);
            }
            self.rig.arm(arm.name).write_tree_positions(&arm.actual(), &mut positions);
        }
        let poses = self.rig.tree.root_from_links(&positions);
        for (i, body) in self.link_bodies.iter().enumerate() {
            if let Some(h) = body
                && self.physics.bodies[*h].is_kinematic()
            {
                let link = &mut self.physics.bodies[*h];
                let next = continuous_pose(matrix_to_pose(&poses[i]), link.position());
                link.set_next_kinematic_position(next);
            }
        }
        self.update_grasps(&poses);
        self.hand_over_needle();
        let jaws = jaws::jaws_now(&self.arms, &self.rig, self.jaw_closed_rad, &poses);
        let hooks = self.suture.before_step(&mut self.physics, &self.tissue, &jaws, dt);
        let flaps = self.tissue.flaps;
        let suture = &self.suture;
        self.physics.step_with_hooks(&hooks, &|h| match suture.body_name(h) {
            Some(name) => name,
            None if flaps.contains(&h) => "tissue flap".to_owned(),
            None => "rig link".to_owned(),
        })?;
        for (i, h) in &self.posed_links {
            let link = &mut self.physics.bodies[*h];
            let next = continuous_pose(matrix_to_pose(&poses[*i]), link.position());
            link.set_position(next, false);
        }
        self.time_s += dt;
        self.suture.after_step(&mut self.physics, &self.tissue, self.time_s);
        self.check_slip();
        self.hand_over_needle();
        self.read_forces();
        Ok(())
    }
}

/// The scene's trocar point of an arm, world frame, m.
pub fn trocar_of(config: &SceneConfig, arm: ArmName) -> Vector3<f64> {
    Vector3::from(match arm {
        ArmName::Left => config.trocars.left,
        ArmName::Right => config.trocars.right,
        ArmName::Assist => config.trocars.assist,
        ArmName::Camera => config.trocars.camera,
    })
}

/// The tip target that puts the jaws' centre at `jaw_centre_m` (world), the tip along the shaft.
pub fn tip_for_jaw_centre(trocar_m: &Vector3<f64>, jaw_centre_m: &Vector3<f64>) -> TipTarget {
    let shaft = (jaw_centre_m - trocar_m).normalize();
    TipTarget {
        world_position_m: jaw_centre_m + shaft * JAW_CENTRE_OFFSET_M,
        orientation: TipOrientation::AlongShaft,
    }
}

/// The joints an arm starts with: the right instrument holding the needle and the assist holding the
/// tail where the scene's start condition says; the others parked, their tip 4 cm past the trocar
/// towards the tissue, jaws open.
fn start_joints(
    config: &SceneConfig,
    rig: &Rig,
    name: ArmName,
    trocar: &Vector3<f64>,
) -> Result<ArmJoints, WorldError> {
    let arm = rig.arm(name);
    let world_from_tissue = Tissue::frame(&config.tissue);
    let held = match name {
        ArmName::Right => Some(("needle_m", config.start.needle_m)),
        ArmName::Assist => Some(("tail_m", config.start.tail_m)),
        _ => None,
    };
    if let Some((key, point)) = held {
        let jaw_centre = world_from_tissue * Point3::from(Vector3::from(point));
        let target = tip_for_jaw_centre(trocar, &jaw_centre.coords);
        let mut joints = arm
            .model
            .solve_tip(&target, trocar, &name.ready_joints())
            .map_err(|reason| WorldError::StartUnreachable { key, arm: name, reason })?;
        joints.tool.jaw_rad = 0.0;
        return Ok(joints);
    }
    let towards = (Vector3::from(config.tissue.centre_m) - trocar).normalize();
    let target =
        TipTarget { world_position_m: trocar + towards * 0.04, orientation: TipOrientation::AlongShaft };
    let mut ready = arm
        .model
        .solve_tip(&target, trocar, &name.ready_joints())
        .map_err(|reason| WorldError::TrocarUnreachable { arm: name, reason })?;
    if name.carries_instrument() {
        ready.tool.jaw_rad = SimWorld::JAW_OPEN_RAD;
    }
    Ok(ready)
}
