//! The simulated operating scene: the rig's links as bodies driven through joint servos, the suture,
//! grasps, and the instruments' force readings. The controller drives it through joint commands, as
//! it would drive the real robots.

use knotlab_hw::kinematics::{ArmJoints, JointLimit, TipOrientation, TipTarget, Tool};
use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::{IsometryMatrix3, Point3, Vector3};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rapier3d::prelude::*;

pub use crate::grasp::GRASP_REACH_M;
use crate::grasp::{Grasp, GraspEvent};
use crate::groups::{ENVIRONMENT_GROUP, ROBOT_GROUP, THREAD_GROUP};
use crate::hooks::{ContactFilter, ThreadOnItself};
use crate::layout::start_layout;
use crate::needle::Needle;
use crate::physics::{HealthError, Physics};
use crate::rope::grasp::RopeGrasp;
use crate::rope::suture::SceneRope;
use crate::scene::SceneConfig;
use crate::servo::{ServoModel, ServoState};
use crate::stitch::{Stitch, StitchEvent};
use crate::thread::{Thread, ThreadModel};
use crate::thread_watch::ThreadWatch;
use crate::tissue::Tissue;

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

/// One arm in the simulation: its servos and what it was told.
pub struct SimArm {
    /// Which arm.
    pub name: ArmName,
    /// Servos in [`ArmJoints::ORDER`] (the endoscope's tool servos are unused).
    pub servos: Vec<ServoModel>,
    /// Their states.
    pub states: Vec<ServoState>,
    /// The last joint command.
    pub command: ArmJoints,
    /// The grasp held by the jaws, if any: on the chain or the needle.
    pub grasp: Option<Grasp>,
    /// The grasp on the rope, if the suture is the rope and the jaws hold it.
    pub rope_grasp: Option<RopeGrasp>,
    /// The rope's particles the jaws last held (and what lay along them), still let through the
    /// jaws until they have opened: pushed out of jaws that were closed on them, they would be
    /// thrown out at speed.
    pub rope_let_go: Option<std::ops::Range<usize>>,
    /// A grasp that slipped stays lost until the jaws reopen.
    pub slipped: bool,
    /// The rope slid through the jaws in the last step (pulled along itself beyond the grip).
    pub sliding: bool,
    /// Jaws that closed on nothing stay empty until they reopen: what later touches closed jaws is
    /// not grasped (and collides with them).
    pub closed_empty: bool,
    /// The jaw command when the grasp took hold, rad: told to open past it, the jaws let go.
    pub grasped_at_jaw_rad: f64,
    /// Force on the instrument from contacts and grasps, as the strain gauges read it (filtered,
    /// with noise), world frame, N.
    pub force_n: Vector3<f64>,
    /// The physical force through the gauges' filter (before the noise), world frame, N.
    pub filtered_force_n: Vector3<f64>,
    /// The bodies of the instrument (the flange and every link below it): what the gauge feels.
    pub instrument_bodies: Vec<RigidBodyHandle>,
    /// The colliders of the jaws and the clevis carrying them.
    pub jaw_colliders: Vec<ColliderHandle>,
}

impl SimArm {
    /// Whether the jaws hold the thread or the needle.
    pub fn holds(&self) -> bool {
        self.grasp.is_some() || self.rope_grasp.is_some()
    }

    /// Where along the thread the jaws hold it: the chain's segment, or the rope's particle in the
    /// middle of the held run (an index into the thread's centreline either way, from the needle
    /// end).
    pub fn held_at(&self) -> Option<usize> {
        match (&self.grasp, &self.rope_grasp) {
            (Some(grasp), _) => Some(grasp.segment),
            (None, Some(rope)) => Some(rope.particles.start + rope.particles.len() / 2),
            (None, None) => None,
        }
    }

    /// The joints as the links stand now (after lag, play and calibration).
    pub fn actual(&self) -> ArmJoints {
        let v: [f64; 10] = std::array::from_fn(|i| self.states[i].link_rad);
        ArmJoints::from_array(v)
    }
}

/// The simulated scene.
pub struct SimWorld {
    /// The Rapier sets.
    pub physics: Physics,
    /// The robots.
    pub rig: Rig,
    /// The four arms, in [`ArmName::ALL`] order.
    pub arms: Vec<SimArm>,
    /// The suture as Rapier's capsule chain (no segments when it is the rope).
    pub thread: Thread,
    /// The suture as the rope, when the scene's `thread.model` is `rope`.
    pub rope: Option<SceneRope>,
    /// The needle on the thread's first segment.
    pub needle: Needle,
    /// The pad and the two flaps of the wound.
    pub tissue: Tissue,
    /// Where the thread passes through the flaps.
    pub stitch: Stitch,
    /// What the stitch noticed so far.
    pub stitch_events: Vec<StitchEvent>,
    /// The thread's passes through itself so far.
    pub thread_watch: ThreadWatch,
    /// Body of each URDF link with collision geometry (indexed like the rig's tree links).
    pub link_bodies: Vec<Option<RigidBodyHandle>>,
    /// The moving links that are fixed bodies, posed after each step (with the rope: the arms'
    /// links before the flange), with their indices in the rig's tree.
    posed_links: Vec<(usize, RigidBodyHandle)>,
    /// Simulated time, s.
    pub time_s: f64,
    /// Grasp events so far.
    pub events: Vec<GraspEvent>,
    /// The scene it was built from.
    pub config: SceneConfig,
    /// Jaw openings below this count as closed, rad.
    pub jaw_closed_rad: f64,
    /// Pull at which a grasp slips, N.
    pub grip_force_n: f64,
    /// The strain gauges' noise source.
    noise: ChaCha8Rng,
}

fn to_pose(iso: &IsometryMatrix3<f64>) -> Pose {
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&iso.rotation);
    let t = iso.translation.vector;
    Pose::from_parts(Vector::new(t.x, t.y, t.z), Rotation::from_xyzw(q.i, q.j, q.k, q.w))
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

/// Whether link `i` of `rig` is the flange `flange` or hangs from it (the instrument an arm carries).
fn on_flange(rig: &Rig, i: usize, flange: usize) -> bool {
    i == flange || rig.tree.path_to(i).iter().any(|&j| rig.tree.joints[j].child == flange)
}

fn shape_collider(shape: &knotlab_hw::rig::Shape) -> ColliderBuilder {
    match *shape {
        knotlab_hw::rig::Shape::Box { half_extents_m: h } => ColliderBuilder::cuboid(h.x, h.y, h.z),
        knotlab_hw::rig::Shape::Capsule { radius_m, length_m } => {
            ColliderBuilder::capsule_z(0.5 * length_m, radius_m)
        }
        knotlab_hw::rig::Shape::Sphere { radius_m } => ColliderBuilder::ball(radius_m),
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

    /// Builds the scene with the thread laid along the path `layout` gives (world frame, needle end
    /// first, from the scene, its tissue and its physics as built), through the stitch where the path
    /// passes its points, and held by no instrument; the instruments stand as in [`Self::new`]. For
    /// trials of a thread placed by hand, such as a knot laid over the stitch (`crate::lab::laid_knot`).
    pub fn with_thread_laid(
        config: SceneConfig,
        rig: Rig,
        layout: impl FnOnce(&SceneConfig, &Tissue, &Physics) -> Vec<Vector3<f64>>,
    ) -> Result<Self, WorldError> {
        let mut physics = Physics::new(&config.solver);
        let arms: Vec<SimArm> = ArmName::ALL
            .iter()
            .map(|&name| {
                let arm = rig.arm(name);
                let offsets = match name {
                    ArmName::Left => config.servo.calibration_offset_rad.left,
                    ArmName::Right => config.servo.calibration_offset_rad.right,
                    ArmName::Assist => config.servo.calibration_offset_rad.assist,
                    ArmName::Camera => config.servo.calibration_offset_rad.camera,
                };
                let free = JointLimit::new(-1e3, 1e3, 10.0);
                let tool_limits = match &arm.model.tool {
                    Tool::Instrument { limits, .. } => [limits.roll, limits.pitch, limits.yaw, limits.jaw],
                    Tool::Endoscope { .. } => [free; 4],
                };
                let servos = (0..10)
                    .map(|i| ServoModel {
                        limit: if i < 6 { arm.model.limits[i] } else { tool_limits[i - 6] },
                        time_constant_s: if i < 6 {
                            config.servo.time_constant_s
                        } else {
                            config.servo.instrument_time_constant_s
                        },
                        max_acceleration_rad_s2: if i < 6 {
                            config.servo.max_acceleration_rad_s2
                        } else {
                            config.servo.instrument_max_acceleration_rad_s2
                        },
                        play_rad: if i < 6 { config.servo.play_rad } else { 0.0 },
                        calibration_offset_rad: if i < 6 { offsets[i] } else { 0.0 },
                    })
                    .collect();
                let trocar = trocar_of(&config, name);
                let ready = start_joints(&config, &rig, name, &trocar)?;
                let states = ready.to_array().iter().map(|q| ServoState::at(*q)).collect();
                Ok(SimArm {
                    name,
                    servos,
                    states,
                    command: ready,
                    grasp: None,
                    rope_grasp: None,
                    rope_let_go: None,
                    slipped: false,
                    sliding: false,
                    closed_empty: false,
                    grasped_at_jaw_rad: 0.0,
                    force_n: Vector3::zeros(),
                    filtered_force_n: Vector3::zeros(),
                    instrument_bodies: Vec::new(),
                    jaw_colliders: Vec::new(),
                })
            })
            .collect::<Result<_, WorldError>>()?;

        // Links: kinematic when an arm moves them, fixed otherwise.
        let mut positions = vec![0.0; rig.tree.joints.len()];
        for arm in &arms {
            rig.arm(arm.name).write_tree_positions(&arm.actual(), &mut positions);
        }
        let poses = rig.tree.root_from_links(&positions);
        let mut link_bodies = vec![None; rig.tree.links.len()];
        let mut posed_links = Vec::new();
        let mut jaw_colliders: Vec<(String, ColliderHandle)> = Vec::new();
        // What the rope touches of the robots: the instruments (the arms' own links stay outside the
        // body, above the trocars).
        let mut instrument_colliders: Vec<ColliderHandle> = Vec::new();
        let rope = config.thread.model == ThreadModel::Rope;
        let flanges: Vec<usize> = arms.iter().map(|a| rig.arm(a.name).flange_link).collect();
        let on_instrument = |i: usize| flanges.iter().any(|&flange| on_flange(&rig, i, flange));
        for (i, link) in rig.tree.links.iter().enumerate() {
            if link.collisions.is_empty() {
                continue;
            }
            let moving = rig.tree.path_to(i).iter().any(|&j| rig.tree.joints[j].limit.is_some());
            // The jaws collide with the thread (it can be wound around them), except with what they
            // hold or close on: the contact filter leaves that to the grasp constraint.
            let jaw = ["_jaw_1", "_jaw_2", "_clevis", "_wrist"].iter().any(|s| link.name.ends_with(s));
            // With the rope, whose contacts with the links are its own (`crate::rope::rigid`), Rapier
            // has nothing to do with a moving link but carry the needle in jaws: the links' colliders
            // stay out of its broad phase, and the arms' own links (before the flange, which hold
            // nothing) are fixed bodies posed after each step, out of its solver.
            let posed = rope && moving && !on_instrument(i);
            let (builder, group, filter) = if moving && !posed {
                (RigidBodyBuilder::kinematic_position_based(), ROBOT_GROUP, THREAD_GROUP)
            } else if moving {
                (RigidBodyBuilder::fixed(), ROBOT_GROUP, THREAD_GROUP)
            } else {
                (RigidBodyBuilder::fixed(), ENVIRONMENT_GROUP, Group::NONE)
            };
            let body = physics.bodies.insert(builder.pose(to_pose(&poses[i])).build());
            if posed {
                posed_links.push((i, body));
            }
            for c in &link.collisions {
                let collider = shape_collider(&c.shape)
                    .enabled(!(rope && moving))
                    .position(to_pose(&c.link_from_shape))
                    .friction(0.8)
                    .active_hooks(if jaw { ActiveHooks::FILTER_CONTACT_PAIRS } else { ActiveHooks::empty() })
                    .collision_groups(InteractionGroups::new(group, filter, InteractionTestMode::And))
                    .build();
                let handle = physics.colliders.insert_with_parent(collider, body, &mut physics.bodies);
                if jaw && moving {
                    jaw_colliders.push((link.name.clone(), handle));
                }
                if moving && on_instrument(i) {
                    instrument_colliders.push(handle);
                }
            }
            link_bodies[i] = Some(body);
        }

        let mut arms = arms;
        for arm in &mut arms {
            let flange = rig.arm(arm.name).flange_link;
            arm.instrument_bodies = (0..rig.tree.links.len())
                .filter(|&i| on_flange(&rig, i, flange))
                .filter_map(|i| link_bodies[i])
                .collect();
            let prefix = format!("{}_", arm.name);
            arm.jaw_colliders =
                jaw_colliders.iter().filter(|(name, _)| name.starts_with(&prefix)).map(|(_, h)| *h).collect();
        }
        let tissue = Tissue::build(&mut physics, &config.tissue, &config.stitch);
        let layout = layout(&config, &tissue, &physics);
        let (thread, needle, rope) = match config.thread.model {
            ThreadModel::Chain => {
                let thread =
                    Thread::build(&mut physics, &config.thread, &layout[0], &(layout[1] - layout[0]));
                thread.lay_along(&mut physics, &layout);
                let needle = Needle::attach(&config.needle, &mut physics, &thread);
                (thread, needle, None)
            }
            ThreadModel::Rope => {
                let (mut rope, needle) = SceneRope::build(
                    &config.thread,
                    &config.needle,
                    &layout,
                    &mut physics,
                    &tissue,
                    &config.tissue,
                    &instrument_colliders,
                );
                if let Some(stitch) = &mut rope.stitch {
                    stitch.slide_friction_n = config.stitch.slide_friction_n;
                }
                (Thread::empty(rope.spacing_m), needle, Some(rope))
            }
        };
        let mut tissue = tissue;
        let stitch = Stitch::anchor(&mut physics, &thread, &mut tissue, config.stitch.slide_friction_n);
        let grip_force_n = config.sensor.grip_force_n;
        let thread_watch = ThreadWatch::new(&thread);
        Ok(Self {
            physics,
            rig,
            arms,
            thread,
            rope,
            needle,
            tissue,
            stitch,
            stitch_events: Vec::new(),
            thread_watch,
            link_bodies,
            posed_links,
            time_s: 0.0,
            events: Vec::new(),
            config,
            jaw_closed_rad: 0.05,
            grip_force_n,
            noise: ChaCha8Rng::seed_from_u64(0),
        })
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
        self.noise = ChaCha8Rng::seed_from_u64(seed);
    }

    /// Opens every instrument's jaws: grasps are released at the next step.
    pub fn release_all(&mut self) {
        for arm in &mut self.arms {
            if arm.name.carries_instrument() {
                // Past the angle the jaws took what they hold at: jaws opened less still squeeze it.
                let past_grasp_rad = if arm.holds() { arm.grasped_at_jaw_rad + 0.05 } else { 0.0 };
                arm.command.tool.jaw_rad = Self::JAW_OPEN_RAD.max(past_grasp_rad);
            }
        }
    }

    /// Lets go of everything and takes the thread out of the tissue: a free thread for experiments.
    pub fn free_thread(&mut self) {
        for a in 0..self.arms.len() {
            if let Some(grasp) = self.arms[a].grasp.take() {
                grasp.release(&mut self.physics);
            }
            self.release_rope(a);
            if self.arms[a].name.carries_instrument() {
                self.arms[a].command.tool.jaw_rad = Self::JAW_OPEN_RAD;
            }
        }
        for hole in self.stitch.holes.iter_mut().chain(self.stitch.guides.iter_mut()) {
            if let Some(j) = hole.joint.take() {
                self.physics.impulse_joints.remove(j, true);
            }
            hole.segment = None;
        }
        if let Some(rope) = &mut self.rope {
            rope.unstitch(&mut self.physics);
        }
    }

    /// Lets each instrument's jaws pass what they hold of the rope and what lies along them: the
    /// run they grasp, or the swaged end of the needle they hold, and [`JAW_CLEAR_M`] of rope
    /// either side (pushed out of the jaws while its neighbours are held in, it would be torn
    /// between the two).
    /// Closing jaws (told to close, or closing now) that hold nothing let what lies between them
    /// pass, as the chain's contact filter does: the grasp takes it once they are closed.
    fn clear_jaws_of_held_rope(&mut self, poses: &[IsometryMatrix3<f64>]) {
        let Some(rope) = &mut self.rope else { return };
        let clear = (JAW_CLEAR_M / rope.spacing_m).ceil() as usize;
        let count = rope.ropes.x.len();
        for arm in &mut self.arms {
            let Some(run) = arm.rope_let_go.clone() else { continue };
            if arm.slipped || arm.actual().tool.jaw_rad < 0.5 * Self::JAW_OPEN_RAD {
                continue;
            }
            // Opened: the run goes back to touching the jaws once it is clear of them.
            let touches = run.clone().any(|p| {
                arm.jaw_colliders
                    .iter()
                    .filter_map(|c| self.physics.colliders.get(*c))
                    .any(|c| rope.touches(c, p))
            });
            if !touches {
                arm.rope_let_go = None;
            }
        }
        for arm in &self.arms {
            if arm.jaw_colliders.is_empty() {
                continue;
            }
            let closing = arm.command.tool.jaw_rad < self.jaw_closed_rad
                || arm.command.tool.jaw_rad < arm.actual().tool.jaw_rad - 1e-3;
            // The run through the jaws: around the particle nearest their line, while within reach.
            let between = || {
                let tip = poses[self.rig.arm(arm.name).tip_link];
                let line = crate::grasp::jaw_line_m(&tip, JAW_CENTRE_OFFSET_M);
                let thread_radius_m = self.config.thread.radius_m;
                let faces = Self::jaw_radius_m(&self.rig, arm.name)
                    .map(|r| crate::grasp::JawFaces::of(&tip, r, thread_radius_m));
                RopeGrasp::run_between(&rope.ropes, line, GRASP_REACH_M, faces.as_ref())
                    .map_or(0..0, |run| run.start.saturating_sub(clear)..(run.end + clear).min(count))
            };
            let held = match (&arm.grasp, &arm.rope_grasp) {
                (Some(grasp), _) if grasp.on_needle => 0..clear.min(count),
                (_, Some(grasp)) => grasp.widened(clear, count),
                (None, None) if arm.rope_let_go.is_some() => arm.rope_let_go.clone().unwrap_or(0..0),
                (None, None) if closing && !arm.closed_empty => between(),
                _ => 0..0,
            };
            for (collider, exempt) in &mut rope.contacts.colliders {
                if arm.jaw_colliders.contains(collider) {
                    *exempt = held.clone();
                }
            }
        }
    }

    /// Jaws that let go of the needle let the rope's swaged end out as they do a held run
    /// ([`SimArm::rope_let_go`]).
    fn let_rope_out_of_jaws(&mut self, a: usize, on_needle: bool) {
        if let (true, Some(rope)) = (on_needle, &self.rope) {
            let clear = (JAW_CLEAR_M / rope.spacing_m).ceil() as usize;
            self.arms[a].rope_let_go = Some(0..clear.min(rope.ropes.x.len()));
        }
    }

    /// Pulls each flap away from the wound with `outward_n` more (negative: less), N: a force on
    /// the chain's dynamic flaps, a load on the rope's slides.
    pub fn pull_flaps_open(&mut self, outward_n: f64) {
        if let Some(stitch) = self.rope.as_mut().and_then(|rope| rope.stitch.as_mut()) {
            for load in &mut stitch.load_n {
                *load += outward_n;
            }
            return;
        }
        for flap in crate::tissue::Flap::ALONG_THREAD {
            let outward = self.tissue.world_from_tissue.rotation * Vector3::new(0.0, flap.side(), 0.0);
            let f = outward * outward_n;
            let body = &mut self.physics.bodies[self.tissue.flaps[flap.index()]];
            body.add_force(Vector::new(f.x, f.y, f.z), true);
        }
    }

    /// Gives the rope's needle to the jaws that hold it, or to the rope when none do.
    fn hand_over_needle(&mut self) {
        let held = self.arms.iter().any(|a| a.grasp.as_ref().is_some_and(|g| g.on_needle));
        if let Some(rope) = &mut self.rope {
            rope.set_needle_held(&mut self.physics, held);
        }
    }

    /// Lets go of arm `a`'s grasp on the rope, if any.
    fn release_rope(&mut self, a: usize) {
        self.arms[a].sliding = false;
        if let (Some(grasp), Some(rope)) = (self.arms[a].rope_grasp.take(), &mut self.rope) {
            let clear = (JAW_CLEAR_M / rope.spacing_m).ceil() as usize;
            self.arms[a].rope_let_go = Some(grasp.widened(clear, rope.ropes.x.len()));
            grasp.release(&mut rope.contacts);
        }
    }

    /// The suture's centreline, needle end first, m: the chain's segment ends or the rope's
    /// particles.
    pub fn thread_centreline(&self) -> Vec<Vector3<f64>> {
        match &self.rope {
            Some(rope) => rope.centreline(),
            None => self.thread.centreline(&self.physics),
        }
    }

    /// Where `flap`'s stitch point sits on the suture: the arc length from the needle end, m
    /// (`None` while the thread is not through it).
    pub fn stitch_arc_at_m(&self, flap: crate::tissue::Flap) -> Option<f64> {
        match &self.rope {
            Some(rope) => rope.arc_at_m(flap),
            None => self.stitch.arc_at_m(&self.physics, &self.thread, &self.tissue, flap),
        }
    }

    /// The points of the centreline ([`Self::thread_centreline`]) in the tissue, from the exit's to
    /// the entry's, with one either side for the chain.
    pub fn thread_inside(&self) -> Option<std::ops::RangeInclusive<usize>> {
        match &self.rope {
            Some(rope) => rope.inside(),
            None => self.stitch.segments_inside(),
        }
    }

    /// Which thread segments touch which robot links now (an active contact between their
    /// colliders): `(segment, link name)`, segments from the needle end, sorted. Shows where the
    /// thread lies on the instruments, e.g. turns wound round an instrument that should not hold them.
    /// For the rope: its particles (from the needle end) within its radius of a link's colliders.
    pub fn thread_contacts(&self) -> Vec<(usize, String)> {
        if let Some(rope) = &self.rope {
            let mut found: Vec<(usize, String)> = self
                .link_bodies
                .iter()
                .enumerate()
                .filter_map(|(k, body)| Some((self.rig.tree.links[k].name.clone(), (*body)?)))
                .flat_map(|(name, body)| {
                    rope.particles_touching(&self.physics, body).into_iter().map(move |p| (p, name.clone()))
                })
                .collect();
            found.sort();
            return found;
        }
        let link_of = |body: RigidBodyHandle| {
            self.link_bodies
                .iter()
                .position(|h| *h == Some(body))
                .map(|k| self.rig.tree.links[k].name.clone())
        };
        let segment_of = |body: RigidBodyHandle| self.thread.segment_index(body);
        let mut found: Vec<(usize, String)> = self
            .physics
            .narrow_phase
            .contact_pairs()
            .filter(|pair| pair.has_any_active_contact())
            .filter_map(|pair| {
                let b1 = self.physics.colliders.get(pair.collider1)?.parent()?;
                let b2 = self.physics.colliders.get(pair.collider2)?.parent()?;
                match (segment_of(b1), segment_of(b2)) {
                    (Some(i), None) => Some((i, link_of(b2)?)),
                    (None, Some(i)) => Some((i, link_of(b1)?)),
                    _ => None,
                }
            })
            .collect();
        found.sort();
        found.dedup();
        found
    }

    /// The wound gap between the flaps' inner faces, m.
    pub fn wound_gap_m(&self) -> f64 {
        self.tissue.gap_m(&self.physics)
    }

    /// Rigid bodies in the scene.
    pub fn body_count(&self) -> usize {
        self.physics.bodies.len()
    }

    /// The pairs that must not touch this step: segments inside the tissue and the flaps; the jaws and
    /// what they hold (the held segment and its neighbours), are closing on (what lies between them)
    /// or just lost (what is near their centre). Jaws that closed on nothing touch everything.
    fn contact_filter(&self, poses: &[IsometryMatrix3<f64>]) -> ContactFilter {
        let mut filter = ContactFilter::default();
        filter.thread_on_itself = ThreadOnItself::of(&self.config.thread);
        let colliders_of = |i: usize| -> Vec<ColliderHandle> {
            self.thread
                .segments
                .get(i)
                .map_or_else(Vec::new, |h| self.physics.bodies[*h].colliders().to_vec())
        };
        if let Some(range) = self.stitch.segments_inside() {
            let inside: Vec<ColliderHandle> = range.flat_map(colliders_of).collect();
            filter.exclude_all(&self.tissue.flap_colliders, &inside);
        }
        let reach = GRASP_REACH_M;
        for arm in &self.arms {
            if arm.jaw_colliders.is_empty() {
                continue;
            }
            let mut near: Vec<usize> = Vec::new();
            if let Some(grasp) = &arm.grasp {
                near.extend(grasp.segment.saturating_sub(2)..=grasp.segment + 2);
            }
            if arm.slipped {
                // Slipped, until the jaws reopen: the thread found inside the jaws the moment it slipped
                // out would be thrown out at speed, so what is near their centre passes. (Holding jaws
                // do touch the rest of the thread: coils wound around them must slide off over their
                // tips.)
                let tip = poses[self.rig.arm(arm.name).tip_link];
                let centre = (tip * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords;
                let clearance = HELD_CLEARANCE_M + self.thread.segment_length_m;
                for (i, h) in self.thread.segments.iter().enumerate() {
                    let t = self.physics.bodies[*h].translation();
                    if (Vector3::new(t.x, t.y, t.z) - centre).norm() < clearance {
                        near.push(i);
                    }
                }
            }
            // Closing (told to close, or closing now): what lies between the jaws does not push them
            // apart; the grasp takes it once they are closed.
            let closing = arm.command.tool.jaw_rad < self.jaw_closed_rad
                || arm.command.tool.jaw_rad < arm.actual().tool.jaw_rad - 1e-3;
            if closing && arm.grasp.is_none() && !arm.closed_empty {
                // What passes between the closing jaws (near their line), as the grasp will judge it.
                let tip = poses[self.rig.arm(arm.name).tip_link];
                let (hinge, end) = crate::grasp::jaw_line_m(&tip, JAW_CENTRE_OFFSET_M);
                for (i, c) in self.thread.capsules(&self.physics, 0.0).iter().enumerate() {
                    if knotlab_hw::geometry::segment_distance(&c.a_m, &c.b_m, &hinge, &end) < reach {
                        near.push(i);
                    }
                }
            }
            let held: Vec<ColliderHandle> = near.into_iter().flat_map(colliders_of).collect();
            filter.exclude_all(&arm.jaw_colliders, &held);
        }
        filter
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
                let next = continuous_pose(to_pose(&poses[i]), link.position());
                link.set_next_kinematic_position(next);
            }
        }
        self.update_grasps(&poses);
        self.hand_over_needle();
        let hooks = if self.rope.is_some() { ContactFilter::default() } else { self.contact_filter(&poses) };
        if self.rope.is_some() {
            self.clear_jaws_of_held_rope(&poses);
        }
        if let Some(rope) = &mut self.rope {
            rope.step(&mut self.physics, dt);
        }
        let thread_segments = self.thread.segments.clone();
        let flaps = self.tissue.flaps;
        self.physics.step_with_hooks(&hooks, &|h| match thread_segments.iter().position(|s| *s == h) {
            Some(i) => format!("thread segment {i}"),
            None if flaps.contains(&h) => "tissue flap".to_owned(),
            None => "rig link".to_owned(),
        })?;
        for (i, h) in &self.posed_links {
            let link = &mut self.physics.bodies[*h];
            let next = continuous_pose(to_pose(&poses[*i]), link.position());
            link.set_position(next, false);
        }
        self.time_s += dt;
        self.thread_watch.update(&self.physics, &self.thread, self.config.thread.radius_m, self.time_s);
        if let Some(rope) = &self.rope {
            self.thread_watch.record(self.time_s, rope.ropes.crossed_last_step());
        }
        let events = self.stitch.follow(&mut self.physics, &self.thread, &self.tissue, self.time_s);
        self.stitch_events.extend(events);
        self.check_slip();
        self.hand_over_needle();
        self.read_forces();
        Ok(())
    }

    fn update_grasps(&mut self, poses: &[IsometryMatrix3<f64>]) {
        for a in 0..self.arms.len() {
            let name = self.arms[a].name;
            if !name.carries_instrument() {
                continue;
            }
            let actual_rad = self.arms[a].actual().tool.jaw_rad;
            let command_rad = self.arms[a].command.tool.jaw_rad;
            let closed = actual_rad < self.jaw_closed_rad;
            // Told to close, or closing now (the command ramps down ahead of the jaws).
            let closing = command_rad < actual_rad - 1e-3;
            // A grasp holds until the jaws are told to open past where they took it (at least to
            // the closed threshold).
            let let_go_rad = match self.arms[a].holds() {
                true => self.jaw_closed_rad.max(self.arms[a].grasped_at_jaw_rad + 1e-3),
                false => self.jaw_closed_rad,
            };
            if command_rad >= let_go_rad && !closing {
                if self.arms[a].holds() {
                    if let Some(grasp) = self.arms[a].grasp.take() {
                        self.let_rope_out_of_jaws(a, grasp.on_needle);
                        grasp.release(&mut self.physics);
                    }
                    self.release_rope(a);
                    self.events.push(GraspEvent::Released { arm: name, time_s: self.time_s });
                }
                self.arms[a].slipped = false;
                self.arms[a].closed_empty = false;
                continue;
            }
            if self.arms[a].holds() || self.arms[a].slipped || self.arms[a].closed_empty {
                continue;
            }
            if !closed {
                // Closing: the jaws clamp the thread once their faces squeeze it.
                if closing && self.jaws_squeeze_thread(a, poses) && self.try_grasp(name, poses) {
                    self.arms[a].grasped_at_jaw_rad = command_rad;
                }
                continue;
            }
            if self.try_grasp(name, poses) {
                self.arms[a].grasped_at_jaw_rad = command_rad;
            } else {
                self.arms[a].closed_empty = true;
            }
        }
    }

    /// Whether arm `a`'s closing jaws squeeze the thread between them ([`Grasp::squeezes`]).
    fn jaws_squeeze_thread(&self, a: usize, poses: &[IsometryMatrix3<f64>]) -> bool {
        let rig_arm = self.rig.arm(self.arms[a].name);
        let Some(jaw_radius_m) = Self::jaw_radius_m(&self.rig, self.arms[a].name) else { return false };
        let capsules = match &self.rope {
            Some(rope) => rope
                .centreline()
                .windows(2)
                .map(|w| crate::tunnelling::Capsule { a_m: w[0], b_m: w[1], radius_m: 0.0 })
                .collect(),
            None => self.thread.capsules(&self.physics, 0.0),
        };
        Grasp::squeeze(
            &capsules,
            &poses[rig_arm.tip_link],
            JAW_CENTRE_OFFSET_M,
            self.arms[a].actual().tool.jaw_rad,
            jaw_radius_m,
            self.config.thread.radius_m,
        )
    }

    /// The radius of `arm`'s jaws: their capsules', from the robot model (`None` without jaws).
    fn jaw_radius_m(rig: &Rig, arm: ArmName) -> Option<f64> {
        rig.link_radius_m(arm, "jaw_1")
    }

    /// Closes `arm`'s grasp on the thread or needle between its jaws, if any; true when it holds.
    fn try_grasp(&mut self, arm: ArmName, poses: &[IsometryMatrix3<f64>]) -> bool {
        let Some(a) = self.arms.iter().position(|x| x.name == arm) else { return false };
        let rig_arm = self.rig.arm(arm);
        // The jaws' carrier: the link the tip frame hangs from.
        let clevis = self.rig.tree.links[rig_arm.tip_link]
            .parent_joint
            .and_then(|j| self.link_bodies[self.rig.tree.joints[j].parent]);
        let Some(clevis) = clevis else { return false };
        let tip = poses[rig_arm.tip_link];
        let jaw_radius_m = Self::jaw_radius_m(&self.rig, arm);
        let needle = self.needle.world_points_m(&self.physics, &self.thread);
        let needle_body = self.needle.body;
        let physics = &mut self.physics;
        match Grasp::try_close(physics, &self.thread, &needle, needle_body, clevis, &tip, JAW_CENTRE_OFFSET_M)
        {
            Some(grasp) => {
                self.events.push(GraspEvent::Grasped { arm, segment: grasp.segment, time_s: self.time_s });
                self.arms[a].grasp = Some(grasp);
                true
            }
            None => {
                let Some(rope) = &mut self.rope else { return false };
                let clevis_pose = *self.physics.bodies[clevis].position();
                let line = crate::grasp::jaw_line_m(&tip, JAW_CENTRE_OFFSET_M);
                let thread_radius_m = self.config.thread.radius_m;
                let faces = jaw_radius_m.map(|r| crate::grasp::JawFaces::of(&tip, r, thread_radius_m));
                let (ropes, contacts) = (&rope.ropes, &mut rope.contacts);
                let closed = RopeGrasp::try_close_between(
                    ropes,
                    contacts,
                    clevis,
                    &clevis_pose,
                    line,
                    GRASP_REACH_M,
                    faces.as_ref(),
                );
                match closed {
                    Some(grasp) => {
                        grasp.grip(contacts, self.grip_force_n);
                        let segment = grasp.particles.start + grasp.particles.len() / 2;
                        self.events.push(GraspEvent::Grasped { arm, segment, time_s: self.time_s });
                        self.arms[a].rope_grasp = Some(grasp);
                        true
                    }
                    None => false,
                }
            }
        }
    }

    fn check_slip(&mut self) {
        let dt = self.config.solver.dt_s;
        for a in 0..self.arms.len() {
            let arm = &mut self.arms[a];
            let (Some(grasp), Some(rope)) = (&mut arm.rope_grasp, &mut self.rope) else { continue };
            let force = grasp.force_n(&rope.contacts, dt).norm();
            // Pulled along itself beyond the grip, the rope slides through the jaws (the solver
            // holds the pull there), which hand the hold on as it goes, until none is left to come
            // in; yanked far harder than the grip (across the jaws, say), it is torn out.
            let mut out = force > SLIP_OUT_FACTOR * self.grip_force_n;
            let pose = *self.physics.bodies[grasp.body].position();
            while !out {
                match grasp.follow_slide(&rope.ropes, &mut rope.contacts, &pose, rope.spacing_m) {
                    Some(true) => {}
                    Some(false) => out = true,
                    None => break,
                }
            }
            let sliding = rope.contacts.grips.iter().any(|g| g.body == grasp.body && g.sliding);
            let started = sliding && !std::mem::replace(&mut arm.sliding, sliding);
            let (name, time_s) = (arm.name, self.time_s);
            if out {
                self.release_rope(a);
                self.arms[a].slipped = true;
                self.events.push(GraspEvent::Slipped { arm: name, force_n: force, time_s });
            } else if started {
                self.events.push(GraspEvent::Slid { arm: name, force_n: force, time_s });
            }
        }
        for a in 0..self.arms.len() {
            let Some(grasp) = &self.arms[a].grasp else { continue };
            let force = grasp.force_n(&self.physics);
            let grip =
                if grasp.on_needle { self.config.sensor.needle_grip_force_n } else { self.grip_force_n };
            if force > grip {
                if let Some(grasp) = self.arms[a].grasp.take() {
                    self.let_rope_out_of_jaws(a, grasp.on_needle);
                    grasp.release(&mut self.physics);
                }
                self.arms[a].slipped = true;
                let arm = self.arms[a].name;
                self.events.push(GraspEvent::Slipped { arm, force_n: force, time_s: self.time_s });
            }
        }
    }

    fn read_forces(&mut self) {
        let dt = self.config.solver.dt_s;
        for a in 0..self.arms.len() {
            let mut total = Vector3::zeros();
            for h in &self.arms[a].instrument_bodies {
                for &c in self.physics.bodies[*h].colliders() {
                    for pair in self.physics.narrow_phase.contact_pairs_with(c) {
                        let impulse = pair.total_impulse();
                        // The impulse pushes collider 1 away from collider 2 along the normal.
                        let sign = if pair.collider1 == c { -1.0 } else { 1.0 };
                        total += Vector3::new(impulse.x, impulse.y, impulse.z) * (sign / dt);
                    }
                }
            }
            if let Some(grasp) = &self.arms[a].grasp {
                total += grasp.force_vector_n(&self.physics);
            }
            if let Some(rope) = &self.rope {
                // What the rope did to the instrument's bodies: its contacts and its grasp.
                for h in &self.arms[a].instrument_bodies {
                    total += rope.contacts.impulse_on(*h) / dt;
                }
                // ... and its pull on the needle these jaws hold, which reaches them through the
                // needle: applied to the needle before Rapier's step, the joint takes it up in its
                // first substeps and its last one (all the grasp reads) shows none of it
                // (`sim/tests/integration/needle_gauge_missed_the_ropes_pull.rs`).
                if self.arms[a].grasp.as_ref().is_some_and(|g| g.on_needle) {
                    total += rope.contacts.impulse_on(rope.needle_body) / dt;
                }
            }
            let arm = &mut self.arms[a];
            arm.filtered_force_n =
                crate::gauge::low_pass(&arm.filtered_force_n, &total, dt, self.config.sensor.force_filter_s);
            let mut total = arm.filtered_force_n;
            if let Ok(noise) = Normal::new(0.0, self.config.sensor.force_noise_n) {
                for k in 0..3 {
                    total[k] += noise.sample(&mut self.noise);
                }
            }
            self.arms[a].force_n = total;
        }
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

/// Thread within this distance of the centre of jaws whose grasp slipped (beyond a segment's length)
/// does not collide with them until they reopen, m.
pub const HELD_CLEARANCE_M: f64 = 0.003;

/// The rope held by jaws passes through them this far either side of the held run, m.
pub const JAW_CLEAR_M: f64 = 0.008;

/// Jaws holding the rope let it go when pulled this many times harder than their grip (across
/// them: along the rope, it slides through them at the grip).
pub const SLIP_OUT_FACTOR: f64 = 3.0;

/// The jaws hold what lies this far behind the tip, along the tip's z axis, m.
pub const JAW_CENTRE_OFFSET_M: f64 = 0.005;

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
