//! The suture: a chain of capsules joined at their ends, with bending stiffness and damping, the twist
//! between segments free or locked ([`ThreadParams::twist_free`]), friction, and collisions between all
//! non-adjacent segments.
//!
//! Discretisation chosen by measurement (`cargo bench -p knotlab-lab --bench thread` prints the full
//! curve). Rapier's impulse joints are solved by projected Gauss-Seidel, whose error along a chain grows
//! about as segments^2 / (substeps x sweeps): a 0.25 m thread held at one end and pulled with 2 N, dt
//! 1 ms, on one core of the 2-core reference machine (worst joint gap / segment length, ms per step):
//!
//! | segments | 4 x 4 | 8 x 1 | 8 x 4 | 16 x 1 | 16 x 4 |
//! |---|---|---|---|---|---|
//! | 40 | 4.0 %, 0.16 | 4.0 %, 0.19 | 1.0 %, 0.29 | 1.0 %, 0.37 | 0.25 %, 0.61 |
//! | 60 | 9.3 %, 0.24 | 9.5 %, 0.29 | 2.3 %, 0.44 | 2.3 %, 0.55 | 0.57 %, 0.86 |
//! | 80 | explodes | 19 %, 0.41 | 4.1 %, 0.60 | 4.2 %, 0.74 | 1.0 %, 1.15 |
//! | 100 | explodes | 30 %, 0.52 | 7.2 %, 0.79 | 7.5 %, 0.92 | 1.6 %, 1.49 |
//!
//! (columns: solver iterations x Gauss-Seidel sweeps per iteration). Halving dt equals doubling the
//! iterations; the thread's mass does not matter. Default: 80 segments of 3.1 mm, 8 x 4: 4.1 % stretch
//! under 2 N (the expert's pulls peak at 0.2-0.9 N: 0.4-1.8 %). At 40 segments (1.0 %) a wrap round
//! the jaws was a triangle and the scripted expert's knot held in 1 of 50 runs; at 80, in 19 of 50
//! (with the wound starting at its rest gap), at about 1.7 times the cost of a trial.

use rapier3d::prelude::*;

use crate::convert::{to_na, to_rapier};
use crate::groups::THREAD_GROUP;
use crate::physics::Physics;

/// The rope's particle spacings, in its radii, a scene may ask for (`thread.rope_spacing_radii`).
/// Its contacts pass over segments one and two along the strand from each other; closer than the
/// least, segments three along lie within a diameter of each other where the strand curves round
/// another of its size (its axis two radii from the other's) and push the strand apart along itself
/// (straight, at 0.5 radii a strand left alone stretched 26-fold in 50 ms). The most lays a 3-0
/// suture (0.225 mm across) at the nominal scene's 1.2 mm spacing.
pub const ROPE_SPACING_RADII_RANGE: (f64, f64) = (1.25, 12.0);

/// The suture's material and discretisation.
#[derive(Clone, Copy, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct ThreadParams {
    /// Total length, m.
    pub length_m: f64,
    /// Number of capsule segments.
    pub segments: usize,
    /// Collision radius, m (a 3-0 suture is 0.2-0.25 mm thick; the radius may exceed half of it).
    pub radius_m: f64,
    /// Mass of the whole thread, kg (heavier than real nylon for solver conditioning).
    pub mass_kg: f64,
    /// Bending stiffness of each joint, N m/rad.
    pub bend_stiffness_n_m_per_rad: f64,
    /// Bending damping of each joint, N m s/rad (the chain's; a chain scene must give it, a rope
    /// scene must not).
    #[serde(default)]
    pub bend_damping_n_m_s_per_rad: f64,
    /// Coulomb friction coefficient of the thread surface (against the instruments, the needle, the
    /// tissue: combined with theirs as Rapier combines coefficients).
    pub friction: f64,
    /// The friction of the thread on itself, if not `friction`: every contact between two segments
    /// takes it as it is ([`crate::hooks::ThreadOnItself`]). Knots hold by this friction alone.
    #[serde(default)]
    pub friction_on_itself: Option<f64>,
    /// Linear velocity damping of each segment, 1/s (air and tissue drag).
    pub linear_damping_per_s: f64,
    /// Whether neighbouring segments may turn about the thread's axis relative to each other (`false`:
    /// twist locked, a torsion-stiff thread). A capsule 0.4 mm round spins at the slightest torque (its
    /// inertia about its axis is 1e-11 kg m^2, so no twist spring the solver can hold resists it), and
    /// strands that spin roll over each other instead of sliding: friction then holds almost nothing
    /// (`cargo bench -p knotlab-lab --bench thread_capstan`).
    #[serde(default = "twist_free")]
    pub twist_free: bool,
    /// How the suture is simulated: Rapier's capsule chain (the default) or the XPBD rope
    /// ([`crate::rope`], `model = "rope"`), whose knots hold.
    #[serde(default)]
    pub model: ThreadModel,
    /// The rope's axial stiffness EA, N ([`crate::rope::RopeParams::axial_stiffness_n`]); left out,
    /// the rope is inextensible. The chain's joints ignore it.
    #[serde(default)]
    pub axial_stiffness_n: Option<f64>,
    /// The rope's substeps per step ([`crate::rope::RopeParams::substeps`]); left out, the rope's
    /// default (20). The chain ignores it.
    #[serde(default)]
    pub rope_substeps: Option<usize>,
    /// How many of its radii apart the rope's particles lie, about: as near it as whole segments fit
    /// the length ([`crate::rope::suture::SPACING_RADII`] if left out; within
    /// [`ROPE_SPACING_RADII_RANGE`]). The chain ignores it.
    #[serde(default)]
    pub rope_spacing_radii: Option<f64>,
    /// The rope's inertial mass per metre, kg/m ([`crate::rope::RopeParams::mass_per_m_kg`]): what
    /// its particles weigh to the solver, apart from the weight `mass_kg` puts on them; left out, the
    /// rope's default (0.67 kg/m). The chain ignores it.
    #[serde(default)]
    pub rope_inertial_mass_kg_per_m: Option<f64>,
    /// The radius at which the instruments and the needle push the rope, m
    /// ([`crate::rope::RopeParams::metal_radius_m`]): the suture's own, where `radius_m` is the
    /// section its knots (and the tissue) push it at; at most `radius_m`, which it is if left out.
    /// The chain ignores it.
    #[serde(default)]
    pub rope_radius_at_metal_m: Option<f64>,
    /// Whether the rope's bending joints are solved a strand at once
    /// ([`crate::rope::RopeParams::direct_bending`]); left out, one pass a joint. The chain ignores it.
    #[serde(default)]
    pub rope_direct_bending: bool,
    /// The rope's passes over its lengths and joints together in each substep
    /// ([`crate::rope::RopeParams::constraint_passes`]); left out, one. The chain ignores it.
    #[serde(default)]
    pub rope_constraint_passes: Option<usize>,
    /// Whether the rope's contacts with itself are solved from either end in turn
    /// ([`crate::rope::RopeParams::contacts_both_ways`]); left out, they are. `false`: always from
    /// the needle end, which drags a knot towards it. The chain ignores it.
    #[serde(default = "contacts_both_ways")]
    pub rope_contacts_both_ways: bool,
}

/// How the suture is simulated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ThreadModel {
    /// `segments` capsules joined by Rapier's joints ([`Thread`]).
    #[default]
    Chain,
    /// The XPBD rope ([`crate::rope::suture`]): particles about 1.5 radii apart (unless
    /// `rope_spacing_radii` says otherwise), the chain's bending stiffness per joint times its
    /// segment's length as the rope's EI, friction solved on positions.
    Rope,
}

fn twist_free() -> bool {
    true
}

fn contacts_both_ways() -> bool {
    true
}

impl Default for ThreadParams {
    fn default() -> Self {
        Self {
            length_m: 0.25,
            segments: 40,
            radius_m: 0.0004,
            mass_kg: 0.01,
            bend_stiffness_n_m_per_rad: 2e-5,
            bend_damping_n_m_s_per_rad: 2e-7,
            friction: 0.3,
            friction_on_itself: None,
            axial_stiffness_n: None,
            rope_substeps: None,
            rope_spacing_radii: None,
            rope_inertial_mass_kg_per_m: None,
            rope_radius_at_metal_m: None,
            rope_direct_bending: false,
            rope_constraint_passes: None,
            rope_contacts_both_ways: contacts_both_ways(),
            linear_damping_per_s: 1.0,
            twist_free: true,
            model: ThreadModel::Chain,
        }
    }
}

impl ThreadParams {
    /// Length of one segment, m.
    pub fn segment_length_m(&self) -> f64 {
        self.length_m / self.segments as f64
    }
}

/// A thread in a [`Physics`] world.
pub struct Thread {
    /// Segment bodies from the needle end to the tail end.
    pub segments: Vec<RigidBodyHandle>,
    /// Joint i links segment i to segment i + 1.
    pub links: Vec<ImpulseJointHandle>,
    /// Segment length, m.
    pub segment_length_m: f64,
}

impl Thread {
    /// Lays a straight thread from `start_m` along `direction` in `physics`.
    pub fn build(
        physics: &mut Physics,
        params: &ThreadParams,
        start_m: &nalgebra::Vector3<f64>,
        direction: &nalgebra::Vector3<f64>,
    ) -> Self {
        let seg = params.segment_length_m();
        let dir = direction.normalize();
        let half = 0.5 * seg;
        // Segment frames: x along the thread.
        let rotation = Rotation::from_rotation_arc(Vector::X, to_rapier(&dir));
        let segment_mass = params.mass_kg / params.segments as f64;
        // The capsule's cylinder spans the segment minus its caps, so neighbours just touch.
        let cylinder_half = (half - params.radius_m).max(0.25 * half);
        let mut segments = Vec::with_capacity(params.segments);
        for i in 0..params.segments {
            let centre = start_m + dir * (seg * (i as f64 + 0.5));
            let body = RigidBodyBuilder::dynamic()
                .pose(Pose::from_parts(to_rapier(&centre), rotation))
                .linear_damping(params.linear_damping_per_s)
                .can_sleep(false)
                .build();
            let handle = physics.bodies.insert(body);
            let collider = ColliderBuilder::capsule_x(cylinder_half, params.radius_m)
                .mass(segment_mass)
                .friction(params.friction)
                .collision_groups(InteractionGroups::new(THREAD_GROUP, Group::ALL, InteractionTestMode::And))
                .active_hooks(if params.friction_on_itself.is_some() {
                    ActiveHooks::MODIFY_SOLVER_CONTACTS
                } else {
                    ActiveHooks::empty()
                })
                .build();
            physics.colliders.insert_with_parent(collider, handle, &mut physics.bodies);
            segments.push(handle);
        }
        let mut links = Vec::with_capacity(params.segments.saturating_sub(1));
        let k = params.bend_stiffness_n_m_per_rad;
        let c = params.bend_damping_n_m_s_per_rad;
        for pair in segments.windows(2) {
            // Both anchors on the segments' axes: the joint's x is the thread's axis (twist), y and z
            // bend it.
            let (locked, sprung) = if params.twist_free {
                (JointAxesMask::LIN_AXES, &[JointAxis::AngX, JointAxis::AngY, JointAxis::AngZ][..])
            } else {
                (JointAxesMask::LIN_AXES | JointAxesMask::ANG_X, &[JointAxis::AngY, JointAxis::AngZ][..])
            };
            let mut joint = GenericJointBuilder::new(locked)
                .local_anchor1(Vector::new(half, 0.0, 0.0))
                .local_anchor2(Vector::new(-half, 0.0, 0.0))
                .contacts_enabled(false);
            for axis in sprung {
                joint = joint.motor_position(*axis, 0.0, k, c);
            }
            links.push(physics.impulse_joints.insert(pair[0], pair[1], joint, true));
        }
        Self { segments, links, segment_length_m: seg }
    }

    /// Moves the whole thread, at rest, onto a straight line from `start_m` along `direction`.
    pub fn lay_straight(
        &self,
        physics: &mut Physics,
        start_m: &nalgebra::Vector3<f64>,
        direction: &nalgebra::Vector3<f64>,
    ) {
        let dir = direction.normalize();
        let rotation = Rotation::from_rotation_arc(Vector::X, to_rapier(&dir));
        for (i, h) in self.segments.iter().enumerate() {
            let centre = start_m + dir * (self.segment_length_m * (i as f64 + 0.5));
            let body = &mut physics.bodies[*h];
            body.set_position(Pose::from_parts(to_rapier(&centre), rotation), true);
            body.set_linvel(Vector::ZERO, true);
            body.set_angvel(Vector::ZERO, true);
        }
    }

    /// Moves the whole thread, at rest, onto `polyline` (needle end first), each segment a chord of it;
    /// thread left over runs on straight beyond the last point. Each segment's frame is carried from
    /// the one before by the smallest turn (parallel transport), so neighbours meet untwisted, as a
    /// twist-locked joint wants them, however the polyline bends in space. (Turning each segment from
    /// the x axis by its own smallest turn left the shipped layout's neighbours up to 2.3 rad apart in
    /// twist, which the twist-locked joints snapped straight in the first steps, and a knot laid that
    /// way came apart: `sim/tests/integration/thread_laid_along_a_bent_path_starts_untwisted.rs`.)
    pub fn lay_along(&self, physics: &mut Physics, polyline: &[nalgebra::Vector3<f64>]) {
        let points = crate::chords::chord_points(polyline, self.segment_length_m, self.segments.len() + 1);
        let mut rotation = Rotation::IDENTITY;
        let mut along = Vector::X;
        for (i, h) in self.segments.iter().enumerate() {
            let (a, b) = (points[i], points[i + 1]);
            let dir = to_rapier(&(b - a).normalize());
            rotation = (Rotation::from_rotation_arc(along, dir) * rotation).normalize();
            along = dir;
            let body = &mut physics.bodies[*h];
            body.set_position(Pose::from_parts(to_rapier(&(0.5 * (a + b))), rotation), true);
            body.set_linvel(Vector::ZERO, true);
            body.set_angvel(Vector::ZERO, true);
        }
    }

    /// The centreline: both ends of every segment's axis, needle end first (segments + 1 points).
    pub fn centreline(&self, physics: &Physics) -> Vec<nalgebra::Vector3<f64>> {
        let half = 0.5 * self.segment_length_m;
        let mut points = Vec::with_capacity(self.segments.len() + 1);
        for (i, h) in self.segments.iter().enumerate() {
            let pose = physics.bodies[*h].position();
            if i == 0 {
                points.push(to_na(pose.transform_point(Vector::new(-half, 0.0, 0.0))));
            }
            points.push(to_na(pose.transform_point(Vector::new(half, 0.0, 0.0))));
        }
        points
    }

    /// The largest gap between the two anchors of a link, as a fraction of the segment length.
    pub fn max_stretch_ratio(&self, physics: &Physics) -> f64 {
        let half = 0.5 * self.segment_length_m;
        self.segments
            .windows(2)
            .map(|pair| {
                let a = physics.bodies[pair[0]].position().transform_point(Vector::new(half, 0.0, 0.0));
                let b = physics.bodies[pair[1]].position().transform_point(Vector::new(-half, 0.0, 0.0));
                (a - b).length() / self.segment_length_m
            })
            .fold(0.0, f64::max)
    }

    /// The segments as capsules (axis ends and collision radius), needle end first.
    pub fn capsules(&self, physics: &Physics, radius_m: f64) -> Vec<crate::tunnelling::Capsule> {
        self.centreline(physics)
            .windows(2)
            .map(|w| crate::tunnelling::Capsule { a_m: w[0], b_m: w[1], radius_m })
            .collect()
    }

    /// The index of a body in the chain, if it is a segment.
    pub fn segment_index(&self, body: RigidBodyHandle) -> Option<usize> {
        self.segments.iter().position(|h| *h == body)
    }
}
