//! Motion primitives extracted from a decomposed demonstration, and the knowledge base that stores
//! them (versioned JSON). Everything is relative to the demonstration's stitch frame, so a skill can be
//! moved to another site:
//! - 2D ([`TwoDPrimitive`]): the fitted plane, the path in plane coordinates (a polyline at equal
//!   arc-length steps, dense enough to stand for the spline), the speed along it; convertible into the
//!   fluid solver's [`crate::fluid::PlanarDemonstration`].
//! - linear ([`LinearPrimitive`]): start, end, the speed profile along the line.
//! - force-controlled ([`ForcePrimitive`]): start, end, the recorded maximum force, the jaw action.
//! - synchronized ([`SynchronizedPrimitive`]): the mapping from its reference 2D primitive's progress
//!   to where this instrument is in the reference's plane.
//!
//! [`extract()`] builds a [`KnowledgeBase`]; [`knowledge`] writes and reads the JSON file, and
//! [`check`] says what a file read must hold beyond its schema; [`learn()`] does it all from a
//! demonstration and a pattern.

pub mod check;
pub mod extract;
pub mod knowledge;
pub mod learn;
pub mod timing;

pub use extract::{ExtractError, extract};
pub use knowledge::{
    KB_FORMAT, KB_FORMAT_VERSION, KnowledgeError, load_knowledge_base, parse_knowledge_base,
    write_knowledge_base,
};
pub use learn::{LearnError, learn};

use nalgebra::{Isometry3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::fluid::{FluidError, PlanarDemonstration, PlaneFrame, SpeedPath};

/// A pose: position (m) and rotation as a unit quaternion `x, y, z, w`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pose {
    /// Position, m.
    pub position_m: [f64; 3],
    /// Rotation, `x, y, z, w`.
    pub quaternion_xyzw: [f64; 4],
}

/// A point of a speed profile: arc length from the primitive's start and the speed there.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProfilePoint {
    /// Arc length, m.
    pub s_m: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
}

/// A plane in the stitch frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plane {
    /// Origin, stitch frame, m.
    pub origin_m: [f64; 3],
    /// First in-plane axis (unit).
    pub axis_x: [f64; 3],
    /// Second in-plane axis (unit, perpendicular to the first).
    pub axis_y: [f64; 3],
}

impl Plane {
    /// The normal `axis_x x axis_y`.
    pub fn normal(&self) -> Vector3<f64> {
        Vector3::from(self.axis_x).cross(&Vector3::from(self.axis_y))
    }

    /// The plane in the world, given where the stitch frame is.
    pub fn in_world(&self, world_from_stitch: &Isometry3<f64>) -> Result<PlaneFrame, FluidError> {
        PlaneFrame::new(
            world_from_stitch.transform_point(&Vector3::from(self.origin_m).into()).coords,
            world_from_stitch.transform_vector(&Vector3::from(self.axis_x)),
            world_from_stitch.transform_vector(&Vector3::from(self.axis_y)),
        )
    }
}

/// A 2D movement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TwoDPrimitive {
    /// The primitive's name.
    pub name: String,
    /// Start in the demonstration, s.
    pub start_s: f64,
    /// End in the demonstration, s.
    pub end_s: f64,
    /// The plane fitted to the path (least squares), stitch frame; its origin is the path's centroid.
    pub plane: Plane,
    /// Root-mean-square distance of the path from the plane, m.
    pub rms_out_of_plane_m: f64,
    /// Spacing of the path's points along the arc, m.
    pub step_m: f64,
    /// The path in plane coordinates, m, at equal arc-length steps (the last step may be shorter).
    pub path_m: Vec<[f64; 2]>,
    /// The demonstration's speed at each path point, m/s.
    pub speed_mps: Vec<f64>,
    /// How far the direction turned in the plane, in turns (signed: positive counter-clockwise about
    /// the plane's normal).
    pub turns: f64,
    /// The tip's pose at the start, stitch frame.
    pub start_pose: Pose,
    /// The tip's pose at the end, stitch frame.
    pub end_pose: Pose,
    /// The jaw angle over the movement (it holds what it held), rad.
    pub jaw_rad: f64,
}

impl TwoDPrimitive {
    /// The primitive as the fluid solver takes it: the plane in the world (`world_from_stitch` places
    /// the stitch frame) and the path with its speeds. Speeds below 5 % of the largest (the path's
    /// start and end, where the hand was at rest) are raised to it, as the solver needs positive ones.
    pub fn planar_demonstration(
        &self,
        world_from_stitch: &Isometry3<f64>,
    ) -> Result<PlanarDemonstration, FluidError> {
        let plane = self.plane.in_world(world_from_stitch)?;
        let v_max = self.speed_mps.iter().copied().fold(0.0f64, f64::max);
        let floor = (0.05 * v_max).max(1e-4);
        let path = SpeedPath::new(
            self.path_m.iter().map(|p| Vector2::new(p[0], p[1])).collect(),
            self.speed_mps.iter().map(|v| v.max(floor)).collect(),
        )?;
        Ok(PlanarDemonstration { plane, path })
    }
}

/// A linear movement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinearPrimitive {
    /// The primitive's name.
    pub name: String,
    /// Start in the demonstration, s.
    pub start_s: f64,
    /// End in the demonstration, s.
    pub end_s: f64,
    /// The tip's pose at the start, stitch frame.
    pub start_pose: Pose,
    /// The tip's pose at the end, stitch frame.
    pub end_pose: Pose,
    /// Length of the demonstrated path, m.
    pub path_length_m: f64,
    /// Largest distance of the demonstrated path from the straight line, m.
    pub max_deviation_m: f64,
    /// The speed along the path.
    pub speed_profile: Vec<ProfilePoint>,
    /// Jaw angle at the start and the end, rad.
    pub jaw_rad: [f64; 2],
}

/// What the jaws do in a force-controlled movement.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JawAction {
    /// `open` (the jaws let go after the force is reached, when the demonstration's did) or `hold`.
    pub action: JawActionKind,
    /// The jaw angle before, rad.
    pub from_rad: f64,
    /// The jaw angle after, rad.
    pub to_rad: f64,
    /// When the jaws started to move, from the primitive's start, s.
    pub at_s: f64,
}

/// The jaw action's kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JawActionKind {
    /// Open once the force is reached.
    Open,
    /// Keep holding.
    Hold,
}

/// A force-controlled movement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForcePrimitive {
    /// The primitive's name.
    pub name: String,
    /// Start in the demonstration, s.
    pub start_s: f64,
    /// End in the demonstration (the jaw action), s.
    pub end_s: f64,
    /// The tip's pose at the start, stitch frame.
    pub start_pose: Pose,
    /// The tip's pose at the end, stitch frame.
    pub end_pose: Pose,
    /// Where the movement came to rest (the line's end: the tip may run on after the jaws open),
    /// stitch frame, m.
    pub line_end_m: [f64; 3],
    /// The largest force measured during the movement (the magnitude), N.
    pub max_force_n: f64,
    /// The direction of that force (on the instrument), stitch frame, unit.
    pub force_direction: [f64; 3],
    /// The jaw action.
    pub jaw: JawAction,
    /// The speed along the path.
    pub speed_profile: Vec<ProfilePoint>,
}

/// A sample of a synchronized movement's mapping.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SyncSample {
    /// Progress of the reference movement: its arc length so far over its length (0 to 1).
    pub phase: f64,
    /// Where this instrument's tip is, in the reference plane's coordinates (x, y in the plane, z along
    /// its normal), m.
    pub position_plane_m: [f64; 3],
    /// This tip minus the reference tip, plane coordinates, m.
    pub offset_m: [f64; 3],
    /// This tip's orientation, stitch frame, `x, y, z, w`.
    pub quaternion_xyzw: [f64; 4],
    /// Jaw angle, rad.
    pub jaw_rad: f64,
}

/// A movement synchronized with another instrument's 2D movement.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SynchronizedPrimitive {
    /// The primitive's name.
    pub name: String,
    /// Start in the demonstration, s.
    pub start_s: f64,
    /// End in the demonstration, s.
    pub end_s: f64,
    /// The reference 2D primitive.
    pub reference: String,
    /// The mapping, sampled at equal time steps of the reference movement.
    pub mapping: Vec<SyncSample>,
}

/// A primitive of any type.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type")]
pub enum Primitive {
    /// A 2D movement.
    #[serde(rename = "2d")]
    TwoD(TwoDPrimitive),
    /// A linear movement.
    #[serde(rename = "linear")]
    Linear(LinearPrimitive),
    /// A force-controlled movement.
    #[serde(rename = "force")]
    Force(ForcePrimitive),
    /// A synchronized movement.
    #[serde(rename = "synchronized")]
    Synchronized(SynchronizedPrimitive),
}

impl Primitive {
    /// The primitive's name.
    pub fn name(&self) -> &str {
        match self {
            Primitive::TwoD(p) => &p.name,
            Primitive::Linear(p) => &p.name,
            Primitive::Force(p) => &p.name,
            Primitive::Synchronized(p) => &p.name,
        }
    }

    /// The type's name (`2d`, `linear`, `force`, `synchronized`).
    pub fn type_name(&self) -> &'static str {
        match self {
            Primitive::TwoD(_) => "2d",
            Primitive::Linear(_) => "linear",
            Primitive::Force(_) => "force",
            Primitive::Synchronized(_) => "synchronized",
        }
    }

    /// Its span in the demonstration, s.
    pub fn span_s(&self) -> (f64, f64) {
        match self {
            Primitive::TwoD(p) => (p.start_s, p.end_s),
            Primitive::Linear(p) => (p.start_s, p.end_s),
            Primitive::Force(p) => (p.start_s, p.end_s),
            Primitive::Synchronized(p) => (p.start_s, p.end_s),
        }
    }
}

/// One instrument's primitives, in time order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InstrumentPrimitives {
    /// The instrument: `left`, `right` or `assist`.
    pub instrument: String,
    /// The primitives.
    pub primitives: Vec<Primitive>,
    /// The jaw over the whole demonstration, reduced to where it starts and stops moving (the
    /// demonstration's clock): what the jaws do between primitives (a grasp in a pause) is here.
    /// (Format version 2; empty in version 1.)
    #[serde(default)]
    pub jaw: Vec<JawPoint>,
    /// The tip over the whole demonstration, stitch frame, every [`timing::PATH_PERIOD_S`]: what the
    /// instrument does between primitives (moves the pattern does not cut out) is played from here.
    /// (Format version 2; empty in version 1.)
    #[serde(default)]
    pub path: Vec<PathKey>,
}

/// A point of an instrument's demonstrated path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PathKey {
    /// The demonstration's time, s.
    pub time_s: f64,
    /// The tip, stitch frame, m.
    pub position_m: [f64; 3],
    /// Where the jaws point, stitch frame (unit).
    pub jaw_direction: [f64; 3],
    /// The tip's whole frame, `stitch_from_tip` as a unit quaternion `x, y, z, w` (its z is
    /// `jaw_direction`). (Format version 3; absent before, when keys orient the jaws by direction.)
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quaternion_xyzw: Option<[f64; 4]>,
}

/// A point of an instrument's jaw over time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JawPoint {
    /// The demonstration's time, s.
    pub time_s: f64,
    /// The jaw angle, rad.
    pub jaw_rad: f64,
}

/// A primitive that waits for another instrument's primitive (a cross-instrument `after` of the
/// pattern), and how long after it the demonstration started it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dependency {
    /// The primitive that waits.
    pub primitive: String,
    /// The primitive it waits for.
    pub after: String,
    /// From the end of `after` to the start of `primitive` in the demonstration, s (may be negative
    /// where the pattern allows slack).
    pub pause_s: f64,
}

/// Where the knowledge came from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemonstrationInfo {
    /// Who performed it.
    pub source: String,
    /// The scene file.
    pub scene: String,
    /// The recording's seed.
    pub seed: Option<u64>,
    /// The sample rate, Hz.
    pub sample_rate_hz: f64,
    /// The demonstration's description.
    pub description: String,
}

/// The task knowledge learned from one demonstration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KnowledgeBase {
    /// Always [`KB_FORMAT`].
    pub format: String,
    /// [`KB_FORMAT_VERSION`].
    pub format_version: u32,
    /// The task (the pattern's name).
    pub task: String,
    /// The demonstration.
    pub demonstration: DemonstrationInfo,
    /// The frame positions and orientations are given in: always `stitch`.
    pub frame: String,
    /// Where the stitch frame was in the demonstration's world.
    pub world_from_stitch: Pose,
    /// Per instrument, its primitives.
    pub instruments: Vec<InstrumentPrimitives>,
    /// Which primitive waits for which. (Format version 2; empty in version 1.)
    #[serde(default)]
    pub dependencies: Vec<Dependency>,
}

impl KnowledgeBase {
    /// A primitive by name.
    pub fn primitive(&self, name: &str) -> Option<&Primitive> {
        self.instruments.iter().flat_map(|i| &i.primitives).find(|p| p.name() == name)
    }
}
