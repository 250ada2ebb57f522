//! Grasping as a constraint, as working surgical simulators do it: closing jaws attach the thread
//! segment between them with a fixed joint; opening releases; a pull beyond the grip force slips.

use knotlab_hw::rig::ArmName;
use nalgebra::{IsometryMatrix3, Vector3};
use rapier3d::prelude::*;

use crate::physics::Physics;
use knotlab_hw::geometry::segment_distance;

use crate::tunnelling::Capsule;

/// The jaws close on what passes within this distance of their line (hinge to tip), m: about a jaw's
/// radius, so what lies between them, not a coil wound around them (the thread touching the outside
/// of closed jaws is a jaw radius plus its own radius, 1.9 mm, from that line).
pub const GRASP_REACH_M: f64 = 0.0016;

/// The jaws hold what lies this far behind the tip, along the tip's z axis, m.
pub const JAW_CENTRE_OFFSET_M: f64 = 0.005;

/// What happened to a grasp.
#[derive(Clone, Debug, PartialEq)]
pub enum GraspEvent {
    /// The jaws closed on a segment.
    Grasped {
        /// The arm.
        arm: ArmName,
        /// The thread segment.
        segment: usize,
        /// When, s.
        time_s: f64,
    },
    /// The jaws opened.
    Released {
        /// The arm.
        arm: ArmName,
        /// When, s.
        time_s: f64,
    },
    /// Pulled along itself harder than the grip, the rope began to slide through the jaws, which go
    /// on holding it ([`crate::rope::rigid::Grip`]); once each time it starts.
    Slid {
        /// The arm.
        arm: ArmName,
        /// The pull, N.
        force_n: f64,
        /// When, s.
        time_s: f64,
    },
    /// The pull exceeded the grip.
    Slipped {
        /// The arm.
        arm: ArmName,
        /// The pull, N.
        force_n: f64,
        /// When, s.
        time_s: f64,
    },
}

/// A held thread segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grasp {
    /// The index of the held segment (0 for the needle, which is part of the first segment).
    pub segment: usize,
    /// Whether the jaws hold the needle rather than the thread.
    pub on_needle: bool,
    /// The constraint.
    pub joint: ImpulseJointHandle,
}

/// The jaws' line, from their hinge (twice `jaw_offset_m` behind the tip) to the tip, world frame:
/// what lies near it lies between the jaws.
pub fn jaw_line_m(world_from_tip: &IsometryMatrix3<f64>, jaw_offset_m: f64) -> (Vector3<f64>, Vector3<f64>) {
    let hinge = (world_from_tip * nalgebra::Point3::new(0.0, 0.0, -2.0 * jaw_offset_m)).coords;
    (hinge, world_from_tip.translation.vector)
}

/// Where the jaws' faces are: the jaws turn about their hinge (the tip frame's y) and face each
/// other across the plane through their line square to it, as wide either side of it as they are
/// round. Thread held between them lies with its whole width inside that band; thread near their
/// line but further along the hinge lies beside the jaws, not between them: a coil wound round them
/// (on the rope scene's seed 3 a coil of the left's own lies in the notch beside its opening jaws,
/// 1.32 mm from their line and all of it along the hinge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JawFaces {
    /// A point on the jaws' line (world, m).
    pub on_line_m: Vector3<f64>,
    /// The hinge's direction (world, unit).
    pub hinge: Vector3<f64>,
    /// How far either side of the faces' plane along the hinge a thread's centre may lie to be held
    /// between them, m.
    pub half_width_m: f64,
}

impl JawFaces {
    /// The faces of jaws of `jaw_radius_m` whose tip frame is `world_from_tip`, for a thread of
    /// `thread_radius_m`: its centre no further along the hinge than the jaws' radius less its own.
    pub fn of(world_from_tip: &IsometryMatrix3<f64>, jaw_radius_m: f64, thread_radius_m: f64) -> Self {
        Self {
            on_line_m: world_from_tip.translation.vector,
            hinge: world_from_tip.rotation * Vector3::y(),
            half_width_m: (jaw_radius_m - thread_radius_m).max(0.0),
        }
    }

    /// Whether a thread's centre at `p_m` (world) lies between the faces (not beside the jaws).
    pub fn between(&self, p_m: &Vector3<f64>) -> bool {
        (p_m - self.on_line_m).dot(&self.hinge).abs() <= self.half_width_m
    }
}

impl Grasp {
    /// Attaches the thread segment (of the chain's `segments`, lying as `capsules`; none for the
    /// rope) or the needle that passes nearest the jaws' line (from their hinge, twice
    /// `jaw_offset_m` behind the tip, to the tip), if it comes within reach of it: what lies
    /// between the jaws, not what is wound around them. It is held where it is. `needle_m` are
    /// points along the needle (world frame), on `needle_body` (the first segment's for the chain).
    #[allow(clippy::too_many_arguments)]
    pub fn try_close(
        physics: &mut Physics,
        capsules: &[Capsule],
        segments: &[RigidBodyHandle],
        needle_m: &[Vector3<f64>],
        needle_body: Option<RigidBodyHandle>,
        jaw_body: RigidBodyHandle,
        world_from_tip: &IsometryMatrix3<f64>,
        jaw_offset_m: f64,
    ) -> Option<Self> {
        let (hinge, tip) = jaw_line_m(world_from_tip, jaw_offset_m);
        let reach_m = GRASP_REACH_M;
        // (segment, on the needle, how far beyond reach of the jaws' line it passes)
        let along = capsules
            .iter()
            .enumerate()
            .map(|(i, c)| (i, false, segment_distance(&c.a_m, &c.b_m, &hinge, &tip) - reach_m));
        let needle = needle_m.iter().map(|p| (0, true, segment_distance(p, p, &hinge, &tip) - reach_m));
        let (segment, mut on_needle, beyond) = along.chain(needle).min_by(|a, b| a.2.total_cmp(&b.2))?;
        // The first segment carries the needle, swaged on: jaws that reach the needle too hold it.
        if segment == 0 && needle_m.iter().any(|p| segment_distance(p, p, &hinge, &tip) <= reach_m) {
            on_needle = true;
        }
        if beyond > 0.0 {
            return None;
        }
        // The needle rides on the chain's first segment, or on its own body beside the rope.
        let body = match (on_needle, needle_body) {
            (true, Some(needle)) => needle,
            _ => *segments.get(segment)?,
        };
        let jaw_pose = *physics.bodies[jaw_body].position();
        let segment_pose = *physics.bodies[body].position();
        // Hold the segment where it is relative to the jaws, but pressed between their faces: on their
        // line across the opening (the carrier's x; they turn about its y and point along its z).
        // (Only across the segment: the faces press it sideways, they do not slide it along itself.)
        let mut jaw_from_segment = jaw_pose.inverse() * segment_pose;
        if !on_needle {
            let along = jaw_from_segment.rotation * Vector::X;
            let off = Vector::new(jaw_from_segment.translation.x, 0.0, 0.0);
            jaw_from_segment.translation -= off - along * along.dot(off);
        }
        let joint = FixedJointBuilder::new()
            .local_frame1(jaw_from_segment)
            .local_frame2(Pose::IDENTITY)
            .contacts_enabled(false);
        let handle = physics.impulse_joints.insert(jaw_body, body, joint, true);
        Some(Self { segment, on_needle, joint: handle })
    }

    /// Whether jaws opened `jaw_rad` (between them; each turns half of it about the hinge) squeeze
    /// the thread (as `capsules`: the chain's segments, or the rope's) nearest their line, if it
    /// is within reach of it: where it passes, the room between the jaws' faces (capsules of
    /// `jaw_radius_m`) is no wider than the thread (`thread_radius_m`). Real jaws clamp the thread
    /// then, long before they are shut; rigid capsules closing on past that point squeeze it along
    /// or out sideways instead.
    pub fn squeeze(
        capsules: &[Capsule],
        world_from_tip: &IsometryMatrix3<f64>,
        jaw_offset_m: f64,
        jaw_rad: f64,
        jaw_radius_m: f64,
        thread_radius_m: f64,
    ) -> bool {
        let (hinge, tip) = jaw_line_m(world_from_tip, jaw_offset_m);
        let reach_m = GRASP_REACH_M;
        let faces = JawFaces::of(world_from_tip, jaw_radius_m, thread_radius_m);
        let axis = tip - hinge;
        let length_m = axis.norm();
        let along = |p: &Vector3<f64>| (p - hinge).dot(&axis) / length_m;
        // Each capsule's point nearest the jaws' line (of nine along it).
        let nearest_point = |c: &Capsule| {
            let points = (0..=8).map(|i| c.a_m + (c.b_m - c.a_m) * (i as f64 / 8.0));
            points
                .min_by(|p, q| {
                    let off = |x: &Vector3<f64>| (x - hinge - axis * (along(x) / length_m)).norm();
                    off(p).total_cmp(&off(q))
                })
                .unwrap_or(c.a_m)
        };
        // The nearest capsule within reach that passes between the faces, not beside the jaws.
        let nearest = capsules
            .iter()
            .filter_map(|c| {
                let distance_m = segment_distance(&c.a_m, &c.b_m, &hinge, &tip);
                (distance_m <= reach_m).then(|| (distance_m, nearest_point(c)))
            })
            .filter(|(_, point)| faces.between(point))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let Some((_, nearest_point)) = nearest else { return false };
        // Where along the jaws it passes, measured from the hinge.
        let z_m = along(&nearest_point).clamp(0.0, length_m);
        let room_m = z_m * (0.5 * jaw_rad).sin() - jaw_radius_m;
        room_m <= thread_radius_m
    }

    /// The force the grasp constraint transmitted in the last step, N.
    pub fn force_n(&self, physics: &Physics) -> f64 {
        self.force_vector_n(physics).norm()
    }

    /// The force vector of the constraint in the last step (its linear part), N. Rapier keeps the
    /// impulse of the last solver substep, which lasts `dt / substeps`.
    pub fn force_vector_n(&self, physics: &Physics) -> Vector3<f64> {
        let substep_s = physics.params.dt / physics.params.num_solver_iterations.max(1) as f64;
        physics.impulse_joints.get(self.joint).map_or(Vector3::zeros(), |j| {
            Vector3::new(j.impulses[0], j.impulses[1], j.impulses[2]) / substep_s
        })
    }

    /// Lets go.
    pub fn release(self, physics: &mut Physics) {
        physics.impulse_joints.remove(self.joint, true);
    }
}
