//! The stitch: where the suture passes through the two flaps. At each entry or exit point a joint
//! ties the flap's point to the axis of the thread segment passing through it: the two translations
//! across the segment are locked, the thread slides along its length against a friction force, and
//! turns freely. Two more points, one deep in each flap by the wound (at the stitch's depth), guide
//! the thread the same way (each flap's friction is shared between its two points): the suture runs
//! down through flap B, under the wound and up through flap A, so that nothing on the surface
//! reaches round the part under the wound (laid straight from point to point on the surface, that
//! part was where the expert's coils slid down to and cinched: a knot in the wound's gap). After
//! each step the joints move on to the neighbouring segment when a point has slid past the
//! segment's end, so the whole thread can be pulled through; a point slides at most 0.5 mm past its
//! segment's end, so where the thread bends back at it (a knot drawn down onto the hole) it stops
//! there instead of leaving the thread. Between the two surface points the
//! thread runs inside the tissue, so contacts between those segments and the flaps are filtered
//! out.

use nalgebra::Vector3;
use rapier3d::prelude::*;

use crate::convert::{to_na, to_rapier};
use crate::physics::Physics;
use crate::thread::Thread;
use crate::tissue::{Flap, Tissue};

/// One point where the thread passes through a flap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StitchHole {
    /// Which flap.
    pub flap: Flap,
    /// The segment passing through, if the thread is still in.
    pub segment: Option<usize>,
    /// The joint holding it.
    pub joint: Option<ImpulseJointHandle>,
    /// A deep point (a guide under the surface, by the wound) rather than the entry or exit point.
    pub deep: bool,
}

impl StitchHole {
    /// Where the point is, world frame, m.
    fn at_m(&self, physics: &Physics, tissue: &Tissue) -> Vector3<f64> {
        if self.deep { tissue.deep_m(physics, self.flap) } else { tissue.hole_m(physics, self.flap) }
    }

    /// Where the point is in its flap's frame, m.
    fn in_flap_m(&self, tissue: &Tissue) -> Vector3<f64> {
        if self.deep {
            tissue.flap_from_deep_m[self.flap.index()]
        } else {
            tissue.flap_from_hole_m(self.flap)
        }
    }
}

/// Something the stitch noticed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StitchEvent {
    /// The thread's end slid out of a flap.
    PulledOut {
        /// The flap.
        flap: Flap,
        /// When, s.
        time_s: f64,
    },
}

/// Both stitch points, exit (B) first: the order the thread meets them from the needle end.
#[derive(Clone, Debug, PartialEq)]
pub struct Stitch {
    /// [B, A].
    pub holes: [StitchHole; 2],
    /// The deep points, [B, A].
    pub guides: [StitchHole; 2],
    /// Friction force against sliding, N.
    pub slide_friction_n: f64,
}

/// How far past its segment's end a stitch point may slide before `follow` hands it on, m: a
/// pulled thread slides about 0.1 mm a step. It also caps how fast the thread can be drawn through
/// the tissue: this much a step (0.5 m/s at the scenes' 1 ms steps; the expert draws the tail at a few
/// centimetres a second).
const SLIDE_PAST_END_M: f64 = 0.0005;

/// Where `hole_m` (world) lies along segment `i`'s axis, m from its centre (+ towards the tail).
fn along_segment(physics: &Physics, thread: &Thread, i: usize, hole_m: &Vector3<f64>) -> f64 {
    let pose = physics.bodies[thread.segments[i]].position();
    to_na(pose.inverse_transform_point(to_rapier(hole_m))).x
}

impl Stitch {
    /// Ties each flap's stitch point to the segment whose axis passes nearest it. The point first
    /// moves onto that axis (a fraction of a millimetre where the laid chain cuts the corner of its
    /// path at the hole): the hole is where the thread lies, and the stitch starts without pulling
    /// the wound (tied to the nominal points, 80 segments of 3.1 mm closed it by 0.6 mm).
    pub fn anchor(
        physics: &mut Physics,
        thread: &Thread,
        tissue: &mut Tissue,
        slide_friction_n: f64,
    ) -> Self {
        let point = |flap: Flap, deep: bool| StitchHole { flap, segment: None, joint: None, deep };
        let mut stitch = Self {
            holes: [point(Flap::B, false), point(Flap::A, false)],
            guides: [point(Flap::B, true), point(Flap::A, true)],
            slide_friction_n,
        };
        let friction = stitch.slide_friction_n;
        for hole in stitch.holes.iter_mut().chain(stitch.guides.iter_mut()) {
            let at = hole.at_m(physics, tissue);
            let nearest = thread
                .capsules(physics, 0.0)
                .iter()
                .enumerate()
                .map(|(i, c)| {
                    let d = c.b_m - c.a_m;
                    let t = ((at - c.a_m).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                    let on_axis = c.a_m + d * t;
                    (i, (on_axis - at).norm(), on_axis)
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((i, _, on_axis)) = nearest {
                let flap_from_world = physics.bodies[tissue.flap(hole.flap)].position().inverse();
                let local = to_na(flap_from_world.transform_point(to_rapier(&on_axis)));
                if hole.deep {
                    tissue.flap_from_deep_m[hole.flap.index()] = local;
                } else {
                    tissue.flap_from_hole_m[hole.flap.index()] = local;
                }
                hole.joint = Some(Self::tie(physics, thread, tissue, hole, i, friction));
                hole.segment = Some(i);
            }
        }
        stitch
    }

    fn tie(
        physics: &mut Physics,
        thread: &Thread,
        tissue: &Tissue,
        hole: &StitchHole,
        segment: usize,
        slide_friction_n: f64,
    ) -> ImpulseJointHandle {
        // Frame 1 on the segment (x along its axis), frame 2 at the flap's point: the point must stay
        // on the segment's axis (y, z locked), sliding along x against friction: each flap's two
        // points share its friction. It slides only a little past the segment's ends, where
        // `follow` hands it on to the neighbour; where the thread bends back at that end (a knot
        // drawn down onto the point), it stops there. (Free along the axis, the point slid on along
        // the straight line past the segment's end into empty space, the thread no longer through
        // it: the wound opened 29 mm under the holding test with a square knot on it.)
        let friction_n = 0.5 * slide_friction_n;
        let reach_m = 0.5 * thread.segment_length_m + SLIDE_PAST_END_M;
        let joint = GenericJointBuilder::new(JointAxesMask::LIN_Y | JointAxesMask::LIN_Z)
            .local_frame1(Pose::IDENTITY)
            .local_frame2(Pose::from_translation(to_rapier(&hole.in_flap_m(tissue))))
            .motor_model(JointAxis::LinX, MotorModel::ForceBased)
            .motor_velocity(JointAxis::LinX, 0.0, 1e3)
            .motor_max_force(JointAxis::LinX, friction_n)
            .limits(JointAxis::LinX, [-reach_m, reach_m])
            .contacts_enabled(false);
        physics.impulse_joints.insert(thread.segments[segment], tissue.flap(hole.flap), joint, true)
    }

    /// After a step: moves each joint to the neighbouring segment where the point has slid past the
    /// segment's end; reports a thread end leaving a flap.
    pub fn follow(
        &mut self,
        physics: &mut Physics,
        thread: &Thread,
        tissue: &Tissue,
        time_s: f64,
    ) -> Vec<StitchEvent> {
        let half = 0.5 * thread.segment_length_m;
        let mut events = Vec::new();
        let friction = self.slide_friction_n;
        for hole in self.holes.iter_mut().chain(self.guides.iter_mut()) {
            let Some(mut i) = hole.segment else { continue };
            let at = hole.at_m(physics, tissue);
            let start = i;
            let mut out = false;
            // Walk towards the point; a point in the gap outside a bent joint lies beyond both
            // neighbours' ends: stay on the segment where the walk would turn back.
            let mut direction = 0i8;
            for _ in 0..4 {
                let x = along_segment(physics, thread, i, &at);
                let step = if x > half {
                    1
                } else if x < -half {
                    -1
                } else {
                    0
                };
                if step == 0 || step == -direction {
                    break;
                }
                direction = step;
                if step > 0 && i + 1 >= thread.segments.len() || step < 0 && i == 0 {
                    out = true;
                    break;
                }
                i = if step > 0 { i + 1 } else { i - 1 };
            }
            if out {
                if let Some(j) = hole.joint.take() {
                    physics.impulse_joints.remove(j, true);
                }
                hole.segment = None;
                if !hole.deep {
                    events.push(StitchEvent::PulledOut { flap: hole.flap, time_s });
                }
            } else if i != start {
                if let Some(j) = hole.joint.take() {
                    physics.impulse_joints.remove(j, true);
                }
                hole.joint = Some(Self::tie(physics, thread, tissue, hole, i, friction));
                hole.segment = Some(i);
            }
        }
        events
    }

    /// The segments inside the tissue (between the two surface points, one more on either side): they
    /// pass through the flaps and must not collide with them.
    pub fn segments_inside(&self) -> Option<std::ops::RangeInclusive<usize>> {
        let indices: Vec<usize> = self.holes.iter().chain(&self.guides).filter_map(|h| h.segment).collect();
        let lo = *indices.iter().min()?;
        let hi = *indices.iter().max()?;
        Some(lo.saturating_sub(1)..=hi + 1)
    }

    /// The length of thread on the needle's side of the exit point, m: grows as the thread is pulled
    /// through.
    pub fn needle_side_length_m(&self, physics: &Physics, thread: &Thread, tissue: &Tissue) -> Option<f64> {
        self.arc_at_m(physics, thread, tissue, self.holes[0].flap)
    }

    /// Where `flap`'s point sits on the thread: the arc length from the needle end, m (`None` while
    /// the thread is not through it).
    pub fn arc_at_m(&self, physics: &Physics, thread: &Thread, tissue: &Tissue, flap: Flap) -> Option<f64> {
        let hole = self.holes.iter().find(|h| h.flap == flap)?;
        let i = hole.segment?;
        let x = along_segment(physics, thread, i, &hole.at_m(physics, tissue));
        Some(thread.segment_length_m * (i as f64 + 0.5) + x)
    }
}
