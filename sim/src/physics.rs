//! The Rapier state of a scene and its step. Like `PhysicsPipeline::step`, the step names every set it
//! touches; after it, a health check turns NaN or exploding bodies into an error of the run, never a
//! panic.
//!
//! Rapier runs in f64 (`rapier3d-f64`): parry's segment-segment closest points treat two segments as
//! parallel when `|d1|^2 |d2|^2 - (d1.d2)^2` is below an absolute epsilon, 1.2e-7 in f32. For the
//! thread's 6 mm segments that quantity is about 1e-9 m^4, so in f32 crossing segments got wrong
//! closest points, no contact, and passed through each other freely; in f64 the epsilon is 2.2e-16.
//! Measured cost of f64 on the thread: none (0.29 ms per step either way).
//!
//! Contacts are stiffened from Rapier's game defaults (30 Hz, damping ratio 10, 3 mm/s correction at
//! a 1 mm length unit): a thread segment weighed 0.25 g (40 segments; 0.125 g in today's 80) and
//! Rapier's contact stiffness scales with mass, so two strands pressed together at 1 N sank through
//! each other. At 3000 Hz, ratio 1, 0.1 m/s they held with 0.26 mm of the 0.8 mm touching distance
//! taken up (1000 Hz: 0.38 mm), at no measurable cost (measured with 0.25 g segments). Tight wraps
//! need more: see `max_corrective_speed_m_s`.

use rapier3d::prelude::*;

/// How a scene's physics is integrated.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct SolverParams {
    /// Time step, s.
    pub dt_s: f64,
    /// Solver iterations per step (Rapier's substeps).
    pub solver_iterations: usize,
    /// Projected Gauss-Seidel sweeps inside each substep (cheaper than substeps; helps long chains).
    pub pgs_iterations_per_substep: usize,
    /// Rapier's length unit, m: about the size of the smallest feature (the thread's segments).
    pub length_unit_m: f64,
    /// Contacts are created this far before bodies touch, m. Rapier scales its default by the length
    /// unit, which leaves 2 um at 1 mm: a light thread segment then crosses a strand in one step
    /// before any contact exists. About the distance a segment travels in a step under load.
    pub prediction_distance_m: f64,
    /// Contact stiffness as a natural frequency, Hz. Rapier's soft contacts scale their stiffness with
    /// the bodies' mass; its game default (30 Hz) lets a 0.25 g thread segment sink through another
    /// under 1 N.
    pub contact_frequency_hz: f64,
    /// Contact damping ratio.
    pub contact_damping_ratio: f64,
    /// Fastest the solver pushes penetrating bodies apart, m/s (Rapier's default, scaled by a 1 mm
    /// length unit, is 3 mm/s). The joints of a chain pulled tight drag its segments into the strand
    /// they press on a little every step; corrected too slowly, the overlap grows until one strand is
    /// through: a strand wound twice round another and pulled apart passed through at 0.7 N with
    /// 0.1 m/s, at 5.9 N with 1 m/s, the thread's twist free (locked: 1.3 N and 6.4 N, 0.8 N and 6.0 N laid untwisted; `cargo bench -p
    /// knotlab-bench --bench thread_cinch`).
    pub max_corrective_speed_m_s: f64,
    /// A body faster than this is reported as exploding, m/s.
    pub max_speed_m_s: f64,
}

impl Default for SolverParams {
    fn default() -> Self {
        Self {
            dt_s: 1e-3,
            solver_iterations: 8,
            pgs_iterations_per_substep: 4,
            length_unit_m: 1e-3,
            prediction_distance_m: 1e-3,
            contact_frequency_hz: 3000.0,
            contact_damping_ratio: 1.0,
            max_corrective_speed_m_s: 1.0,
            max_speed_m_s: 20.0,
        }
    }
}

/// What went wrong in a step.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HealthError {
    /// A body's position or velocity became NaN or infinite.
    #[error("body '{body}' has a non-finite position or velocity at step {step}")]
    NotFinite {
        /// The body's label.
        body: String,
        /// The step index.
        step: u64,
    },
    /// A body moves faster than anything in the scene should.
    #[error("body '{body}' moves at {speed_m_s:.1} m/s at step {step}, above the {limit_m_s} m/s allowed")]
    Exploding {
        /// The body's label.
        body: String,
        /// Its speed, m/s.
        speed_m_s: f64,
        /// The limit, m/s.
        limit_m_s: f64,
        /// The step index.
        step: u64,
    },
}

/// All Rapier sets of one scene, and what steps them.
pub struct Physics {
    /// Gravity, m/s^2 (world z up).
    pub gravity: Vector,
    /// Integration parameters derived from [`SolverParams`].
    pub params: IntegrationParameters,
    /// The pipeline.
    pub pipeline: PhysicsPipeline,
    /// Active islands.
    pub islands: IslandManager,
    /// Broad phase.
    pub broad_phase: DefaultBroadPhase,
    /// Narrow phase (contacts).
    pub narrow_phase: NarrowPhase,
    /// Bodies.
    pub bodies: RigidBodySet,
    /// Colliders.
    pub colliders: ColliderSet,
    /// Impulse joints (thread links, grasps, stitches).
    pub impulse_joints: ImpulseJointSet,
    /// Multibody joints (unused, required by the step).
    pub multibody_joints: MultibodyJointSet,
    /// Soft bodies (unused, required by the step).
    pub soft_bodies: SoftBodySet,
    /// Continuous collision detection.
    pub ccd: CCDSolver,
    /// Steps taken.
    pub step_count: u64,
    /// The speed above which a body is exploding, m/s.
    pub max_speed_m_s: f64,
}

impl Physics {
    /// An empty world with `solver` settings and gravity along -z.
    pub fn new(solver: &SolverParams) -> Self {
        // The default velocity cap, scaled by a millimetre length unit, would be 0.4 m/s: far too slow
        // for an instrument flicking a thread. The health check catches real explosions instead.
        let params = IntegrationParameters {
            dt: solver.dt_s,
            num_solver_iterations: solver.solver_iterations.max(1),
            num_internal_pgs_iterations: solver.pgs_iterations_per_substep.max(1),
            length_unit: solver.length_unit_m,
            normalized_max_linear_velocity: 1e5,
            normalized_prediction_distance: solver.prediction_distance_m / solver.length_unit_m,
            normalized_max_corrective_velocity: solver.max_corrective_speed_m_s / solver.length_unit_m,
            contact_softness: SpringCoefficients {
                natural_frequency: solver.contact_frequency_hz,
                damping_ratio: solver.contact_damping_ratio,
            },
            static_contact_softness: SpringCoefficients {
                natural_frequency: 2.0 * solver.contact_frequency_hz,
                damping_ratio: solver.contact_damping_ratio,
            },
            ..IntegrationParameters::default()
        };
        Self {
            gravity: Vector::new(0.0, 0.0, -9.81),
            params,
            pipeline: PhysicsPipeline::new(),
            islands: IslandManager::new(),
            broad_phase: DefaultBroadPhase::default(),
            narrow_phase: NarrowPhase::new(),
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            impulse_joints: ImpulseJointSet::new(),
            multibody_joints: MultibodyJointSet::new(),
            soft_bodies: SoftBodySet::new(),
            ccd: CCDSolver::new(),
            step_count: 0,
            max_speed_m_s: solver.max_speed_m_s,
        }
    }

    /// Time step, s.
    pub fn dt_s(&self) -> f64 {
        self.params.dt
    }

    /// Advances one step, then checks every dynamic body. `label` names a body for the report.
    pub fn step(&mut self, label: &dyn Fn(RigidBodyHandle) -> String) -> Result<(), HealthError> {
        self.step_with_hooks(&(), label)
    }

    /// [`Physics::step`] with contact filters (`hooks`).
    pub fn step_with_hooks(
        &mut self,
        hooks: &dyn PhysicsHooks,
        label: &dyn Fn(RigidBodyHandle) -> String,
    ) -> Result<(), HealthError> {
        self.pipeline.step(
            self.gravity,
            &self.params,
            &mut self.islands,
            &mut self.broad_phase,
            &mut self.narrow_phase,
            &mut self.bodies,
            &mut self.colliders,
            &mut self.impulse_joints,
            &mut self.multibody_joints,
            &mut self.soft_bodies,
            &mut self.ccd,
            hooks,
            &(),
        );
        self.step_count += 1;
        self.check_health(label)
    }

    /// NaN and speed check of every dynamic body.
    pub fn check_health(&self, label: &dyn Fn(RigidBodyHandle) -> String) -> Result<(), HealthError> {
        for (handle, body) in self.bodies.iter() {
            if !body.is_dynamic() {
                continue;
            }
            let t = body.translation();
            let v = body.linvel();
            let finite = t.is_finite() && v.is_finite() && body.angvel().is_finite();
            if !finite {
                return Err(HealthError::NotFinite { body: label(handle), step: self.step_count });
            }
            let speed = v.length();
            if speed > self.max_speed_m_s {
                return Err(HealthError::Exploding {
                    body: label(handle),
                    speed_m_s: speed,
                    limit_m_s: self.max_speed_m_s,
                    step: self.step_count,
                });
            }
        }
        Ok(())
    }
}
