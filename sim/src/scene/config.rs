//! The scene file's contents, with the range checks that name each key.

use serde::{Deserialize, Serialize};

use crate::physics::SolverParams;
use crate::thread::ThreadParams;

/// A whole scene.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SceneConfig {
    /// A line saying what the scene is.
    pub description: String,
    /// Physics integration.
    pub solver: SolverParams,
    /// The suture.
    pub thread: ThreadParams,
    /// The needle at the thread's first segment.
    pub needle: NeedleParams,
    /// The tissue pad with its wound.
    pub tissue: TissueParams,
    /// Where the suture passes through the flaps.
    pub stitch: StitchParams,
    /// Trocar points, world frame, m.
    pub trocars: Trocars,
    /// Joint servos of the arms and instruments.
    pub servo: ServoParams,
    /// The instruments' strain gauges.
    pub sensor: SensorParams,
    /// The knot-tying task's initial condition.
    pub start: StartParams,
    /// How the knot is judged.
    #[serde(default)]
    pub evaluation: super::EvaluationParams,
    /// Extra boxes in the workspace.
    #[serde(default)]
    pub obstacles: Vec<Obstacle>,
    /// What a Monte Carlo run draws per trial (uniform between each pair of bounds); none: nothing.
    #[serde(default)]
    pub randomization: Randomization,
    /// Named changes to `randomization` a Monte Carlo run may pick (`knotlab mc --preset NAME`), such as
    /// `endopar` (the paper's hardware) and `ideal` (no play, no calibration error).
    #[serde(default)]
    pub presets: std::collections::BTreeMap<String, RandomizationPreset>,
}

/// A preset: the bounds it sets, the others left as `[randomization]` has them.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomizationPreset {
    /// A line saying what the preset stands for and where its figures come from.
    pub description: String,
    /// See [`Randomization::stitch_x_m`].
    pub stitch_x_m: Option<[f64; 2]>,
    /// See [`Randomization::stitch_y_m`].
    pub stitch_y_m: Option<[f64; 2]>,
    /// See [`Randomization::stitch_z_m`].
    pub stitch_z_m: Option<[f64; 2]>,
    /// See [`Randomization::stitch_rotate_rad`].
    pub stitch_rotate_rad: Option<[f64; 2]>,
    /// See [`Randomization::stitch_tilt_rad`].
    pub stitch_tilt_rad: Option<[f64; 2]>,
    /// See [`Randomization::play_rad`].
    pub play_rad: Option<[f64; 2]>,
    /// See [`Randomization::calibration_rad`].
    pub calibration_rad: Option<[f64; 2]>,
    /// See [`Randomization::thread_friction`].
    pub thread_friction: Option<[f64; 2]>,
    /// See [`Randomization::thread_bend_stiffness`].
    pub thread_bend_stiffness: Option<[f64; 2]>,
    /// See [`Randomization::force_noise_n`].
    pub force_noise_n: Option<[f64; 2]>,
}

impl RandomizationPreset {
    /// `base` with this preset's bounds in place of its own.
    pub fn apply(&self, base: &Randomization) -> Randomization {
        Randomization {
            stitch_x_m: self.stitch_x_m.unwrap_or(base.stitch_x_m),
            stitch_y_m: self.stitch_y_m.unwrap_or(base.stitch_y_m),
            stitch_z_m: self.stitch_z_m.unwrap_or(base.stitch_z_m),
            stitch_rotate_rad: self.stitch_rotate_rad.unwrap_or(base.stitch_rotate_rad),
            stitch_tilt_rad: self.stitch_tilt_rad.unwrap_or(base.stitch_tilt_rad),
            play_rad: self.play_rad.unwrap_or(base.play_rad),
            calibration_rad: self.calibration_rad.unwrap_or(base.calibration_rad),
            thread_friction: self.thread_friction.unwrap_or(base.thread_friction),
            thread_bend_stiffness: self.thread_bend_stiffness.unwrap_or(base.thread_bend_stiffness),
            force_noise_n: self.force_noise_n.unwrap_or(base.force_noise_n),
            obstacles: base.obstacles.clone(),
        }
    }
}

/// A preset the scene does not have.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("presets.{name}: the scene has no such preset (it has: {available})")]
pub struct UnknownPreset {
    /// The name asked for.
    pub name: String,
    /// The scene's presets, comma-separated (or "none").
    pub available: String,
}

impl SceneConfig {
    /// The scene with preset `name`'s bounds in its `[randomization]` (and no presets left: the result
    /// is the scene a run draws from).
    pub fn with_preset(&self, name: &str) -> Result<SceneConfig, UnknownPreset> {
        let preset = self.presets.get(name).ok_or_else(|| UnknownPreset {
            name: name.to_owned(),
            available: if self.presets.is_empty() {
                "none".to_owned()
            } else {
                self.presets.keys().cloned().collect::<Vec<_>>().join(", ")
            },
        })?;
        let mut scene = self.clone();
        scene.randomization = preset.apply(&self.randomization);
        scene.presets.clear();
        Ok(scene)
    }
}

/// The distributions of a Monte Carlo run's per-trial draws, each uniform within `[low, high]`.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Randomization {
    /// Shift of the stitch (the tissue) along the world's x, m.
    pub stitch_x_m: [f64; 2],
    /// ... along y, m.
    pub stitch_y_m: [f64; 2],
    /// ... along z, m.
    pub stitch_z_m: [f64; 2],
    /// Turn of the stitch about the tissue's normal, rad.
    pub stitch_rotate_rad: [f64; 2],
    /// Tilt of the tissue about the wound (a wound on a sloped surface), rad ([`TissueParams::tilt_rad`]).
    pub stitch_tilt_rad: [f64; 2],
    /// Backlash of every arm joint, rad (servo.play_rad).
    pub play_rad: [f64; 2],
    /// Calibration error: every arm joint's offset, drawn each, rad.
    pub calibration_rad: [f64; 2],
    /// The thread's friction coefficient.
    pub thread_friction: [f64; 2],
    /// The thread's bending stiffness, N m/rad.
    pub thread_bend_stiffness: [f64; 2],
    /// The strain gauges' noise, N.
    pub force_noise_n: [f64; 2],
    /// Boxes a trial may place near the stitch (`[[randomization.obstacle]]`), each drawn apart.
    #[serde(rename = "obstacle")]
    pub obstacles: Vec<RandomObstacle>,
}

/// A box a trial places near the stitch with some probability, its place and size drawn uniformly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RandomObstacle {
    /// The chance that a trial has it, 0 to 1.
    pub probability: f64,
    /// Bounds of its centre in the tissue frame as drawn (origin at the wound's centre on the surface, x
    /// along the wound, y across it, z out of the tissue), per axis, m.
    pub offset_m: [[f64; 2]; 3],
    /// Bounds of its half sizes along the world axes, per axis, m.
    pub half_extents_m: [[f64; 2]; 3],
}

/// The half-circle needle.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct NeedleParams {
    /// Length along the arc, m (a "26 mm half circle": radius = arc / pi).
    pub arc_length_m: f64,
    /// Wire radius, m.
    pub wire_radius_m: f64,
    /// Mass, kg.
    pub mass_kg: f64,
}

/// The tissue pad on the chest: two flaps either side of a wound along the pad's x axis, pulled apart
/// by an elastic load.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TissueParams {
    /// Centre of the pad's top surface, world frame, m.
    pub centre_m: [f64; 3],
    /// Rotation of the pad about the world z axis, rad (the wound runs along the rotated x).
    pub yaw_rad: f64,
    /// Tilt of the pad about the wound (the yawed x axis), rad: a wound on a sloped surface, the
    /// flap on the tail's side (+y) raised for a positive tilt. None by default.
    #[serde(default)]
    pub tilt_rad: f64,
    /// Size of each flap: along the wound, across it, thickness, m.
    pub flap_size_m: [f64; 3],
    /// Wound gap at rest, m.
    pub rest_gap_m: f64,
    /// Stiffness of the load that pulls each flap away from the wound, N/m.
    pub opening_stiffness_n_per_m: f64,
    /// Damping of the flaps' motion, N s/m.
    pub opening_damping_n_s_per_m: f64,
    /// Mass of each flap, kg.
    pub flap_mass_kg: f64,
}

/// Where the suture passes through the flaps, in the tissue frame (x along the wound, y across it,
/// z up, origin at the wound's centre on the surface).
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StitchParams {
    /// Distance of the entry and exit points from the wound's centre line, m.
    pub bite_m: f64,
    /// Depth below the surface at which the suture crosses the wound, m.
    pub depth_m: f64,
    /// Position along the wound, m.
    pub along_m: f64,
    /// Friction force resisting the thread sliding through each flap, N (the rope splits it between
    /// the flap's two stitch points).
    pub slide_friction_n: f64,
}

/// The strain gauges on the instrument shafts.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SensorParams {
    /// Standard deviation of the noise on each axis of a force reading, N.
    pub force_noise_n: f64,
    /// Time constant of the gauges' first-order low-pass filter, s (0: none). The physical force
    /// is filtered, then the noise added: a thread's contact impulses, computed every step, otherwise
    /// reach the controller as one-step spikes (0.6 N in a pull that holds 0.1 N) and fire its force
    /// events.
    #[serde(default)]
    pub force_filter_s: f64,
    /// Grasped thread slips out of the jaws above this pull, N.
    pub grip_force_n: f64,
    /// A needle held in a needle driver's jaws slips above this pull, N.
    pub needle_grip_force_n: f64,
}

/// The knot-tying task's initial condition, in the tissue frame (x along the wound, y across it
/// towards the tail's flap, z up, origin at the wound's centre on the surface), m. The needle has
/// pierced both flaps (the thread runs through the stitch) and is held by the right instrument; the
/// assist holds the tail; the long end between the needle and the stitch lies on the pad.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StartParams {
    /// Where the right instrument's jaws hold the needle (at its back, where the thread is swaged).
    pub needle_m: [f64; 3],
    /// Where the assist's jaws hold the tail's end.
    pub tail_m: [f64; 3],
}

/// How far above the tissue's top surface a trocar must be, m.
pub const MIN_TROCAR_HEIGHT_M: f64 = 0.02;

/// Trocar points for the four arms, world frame, m.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Trocars {
    /// Left instrument.
    pub left: [f64; 3],
    /// Right instrument.
    pub right: [f64; 3],
    /// Assisting instrument.
    pub assist: [f64; 3],
    /// Endoscope.
    pub camera: [f64; 3],
}

/// How every joint follows its command (the knobs Monte Carlo turns: play and calibration).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ServoParams {
    /// First-order lag time constant of the arm axes, s.
    pub time_constant_s: f64,
    /// Largest acceleration of the arm axes, rad/s^2 (speed limits come from the URDF).
    pub max_acceleration_rad_s2: f64,
    /// Backlash of the arm axes: dead band between motor and link, rad.
    pub play_rad: f64,
    /// First-order lag of the instrument's small servos (roll, wrist, jaws), s.
    pub instrument_time_constant_s: f64,
    /// Largest acceleration of the instrument's servos, rad/s^2.
    pub instrument_max_acceleration_rad_s2: f64,
    /// Calibration offsets of the six arm axes, per arm, rad: the link sits at command + offset.
    #[serde(default)]
    pub calibration_offset_rad: CalibrationOffsets,
}

/// Per-arm calibration offsets of axes 1-6, rad.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CalibrationOffsets {
    /// Left arm.
    #[serde(default)]
    pub left: [f64; 6],
    /// Right arm.
    #[serde(default)]
    pub right: [f64; 6],
    /// Assisting arm.
    #[serde(default)]
    pub assist: [f64; 6],
    /// Camera arm.
    #[serde(default)]
    pub camera: [f64; 6],
}

/// A box obstacle.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Obstacle {
    /// Centre, world frame, m.
    pub centre_m: [f64; 3],
    /// Half sizes along the world axes, m.
    pub half_extents_m: [f64; 3],
}

/// The steepest tilt of the tissue a scene or a draw may give, rad (45 degrees; with a trial's tilt
/// added to the scene's, the sum is checked again when the trial's world is built).
pub const MAX_TILT_RAD: f64 = std::f64::consts::FRAC_PI_4;

/// One value out of its range: the key and why.
pub(crate) type RangeProblem = (String, String);

struct Check<'a>(&'a mut Vec<RangeProblem>);

/// The range checks of a `[randomization]` table (or a preset applied to it), keys under `prefix`.
/// `scene_tilt_rad` is the scene's own tilt, to which a trial's is added.
fn randomization_problems(c: &mut Check<'_>, prefix: &str, r: &Randomization, scene_tilt_rad: f64) {
    for (key, [lo, hi], min, max) in [
        ("stitch_x_m", r.stitch_x_m, -0.1, 0.1),
        ("stitch_y_m", r.stitch_y_m, -0.1, 0.1),
        ("stitch_z_m", r.stitch_z_m, -0.1, 0.1),
        ("stitch_rotate_rad", r.stitch_rotate_rad, -3.2, 3.2),
        ("stitch_tilt_rad", r.stitch_tilt_rad, -MAX_TILT_RAD, MAX_TILT_RAD),
        ("play_rad", r.play_rad, 0.0, 0.1),
        ("calibration_rad", r.calibration_rad, -0.2, 0.2),
        ("thread_friction", r.thread_friction, 0.0, 2.0),
        ("thread_bend_stiffness", r.thread_bend_stiffness, 0.0, 1.0),
        ("force_noise_n", r.force_noise_n, 0.0, 10.0),
    ] {
        c.range(&format!("{prefix}.{key}[0]"), lo, min, max);
        c.range(&format!("{prefix}.{key}[1]"), hi, min, max);
        if hi < lo {
            problems_push(c, format!("{prefix}.{key}"), format!("the high bound {hi} is below the low {lo}"));
        }
    }
    let [lo, hi] = r.stitch_tilt_rad;
    for bound in [lo, hi] {
        let sum = scene_tilt_rad + bound;
        if scene_tilt_rad.is_finite() && bound.is_finite() && sum.abs() > MAX_TILT_RAD {
            problems_push(
                c,
                format!("{prefix}.stitch_tilt_rad"),
                format!(
                    "the tissue's tilt {scene_tilt_rad} plus {bound} is {sum}, beyond the {MAX_TILT_RAD} a tissue may tilt"
                ),
            );
            break;
        }
    }
    for (i, o) in r.obstacles.iter().enumerate() {
        let key = format!("{prefix}.obstacle[{i}]");
        c.range(&format!("{key}.probability"), o.probability, 0.0, 1.0);
        for (name, bounds, min, max) in
            [("offset_m", &o.offset_m, -0.3, 0.3), ("half_extents_m", &o.half_extents_m, 1e-4, 0.2)]
        {
            for (axis, [lo, hi]) in ["x", "y", "z"].iter().zip(bounds) {
                c.range(&format!("{key}.{name}.{axis}[0]"), *lo, min, max);
                c.range(&format!("{key}.{name}.{axis}[1]"), *hi, min, max);
                if hi < lo {
                    problems_push(
                        c,
                        format!("{key}.{name}.{axis}"),
                        format!("the high bound {hi} is below the low {lo}"),
                    );
                }
            }
        }
    }
}

fn problems_push(c: &mut Check<'_>, key: String, reason: String) {
    c.0.push((key, reason));
}

impl Check<'_> {
    fn range(&mut self, key: &str, value: f64, lo: f64, hi: f64) {
        if !(value.is_finite() && value >= lo && value <= hi) {
            self.0.push((key.to_owned(), format!("must be within {lo}..{hi}, got {value}")));
        }
    }

    fn count(&mut self, key: &str, value: usize, lo: usize, hi: usize) {
        if value < lo || value > hi {
            self.0.push((key.to_owned(), format!("must be within {lo}..{hi}, got {value}")));
        }
    }

    fn point(&mut self, key: &str, p: &[f64; 3]) {
        for (axis, v) in ["x", "y", "z"].iter().zip(p) {
            self.range(&format!("{key}.{axis}"), *v, -5.0, 5.0);
        }
    }
}

impl SceneConfig {
    /// Every value out of its range, with its key.
    pub(crate) fn range_problems(&self) -> Vec<RangeProblem> {
        let mut problems = Vec::new();
        let mut c = Check(&mut problems);
        let s = &self.solver;
        c.range("solver.dt_s", s.dt_s, 1e-5, 0.01);
        c.count("solver.solver_iterations", s.solver_iterations, 1, 256);
        c.count("solver.pgs_iterations_per_substep", s.pgs_iterations_per_substep, 1, 64);
        c.range("solver.length_unit_m", s.length_unit_m, 1e-5, 1.0);
        c.range("solver.prediction_distance_m", s.prediction_distance_m, 0.0, 0.05);
        c.range("solver.contact_frequency_hz", s.contact_frequency_hz, 1.0, 1e5);
        c.range("solver.contact_damping_ratio", s.contact_damping_ratio, 0.0, 100.0);
        c.range("solver.max_corrective_speed_m_s", s.max_corrective_speed_m_s, 0.0, 10.0);
        c.range("solver.max_speed_m_s", s.max_speed_m_s, 0.1, 1000.0);
        let t = &self.thread;
        c.range("thread.length_m", t.length_m, 0.01, 2.0);
        c.count("thread.segments", t.segments, 4, 1000);
        c.range("thread.radius_m", t.radius_m, 1e-5, 0.005);
        c.range("thread.mass_kg", t.mass_kg, 1e-6, 1.0);
        c.range("thread.bend_stiffness_n_m_per_rad", t.bend_stiffness_n_m_per_rad, 0.0, 1.0);
        c.range("thread.bend_damping_n_m_s_per_rad", t.bend_damping_n_m_s_per_rad, 0.0, 1.0);
        c.range("thread.friction", t.friction, 0.0, 2.0);
        if let Some(f) = t.friction_on_itself {
            c.range("thread.friction_on_itself", f, 0.0, 2.0);
        }
        if let Some(ea) = t.axial_stiffness_n {
            c.range("thread.axial_stiffness_n", ea, 1.0, 1e6);
        }
        if let Some(n) = t.rope_substeps {
            c.count("thread.rope_substeps", n, 1, 1000);
        }
        if let Some(n) = t.rope_constraint_passes {
            c.count("thread.rope_constraint_passes", n, 1, 100);
        }
        if let Some(k) = t.rope_spacing_radii {
            let (least, most) = crate::thread::ROPE_SPACING_RADII_RANGE;
            c.range("thread.rope_spacing_radii", k, least, most);
        }
        if let Some(m) = t.rope_inertial_mass_kg_per_m {
            c.range("thread.rope_inertial_mass_kg_per_m", m, 1e-6, 10.0);
        }
        if let Some(r) = t.rope_radius_at_metal_m
            && !(r.is_finite() && r >= 1e-5 && r <= t.radius_m)
        {
            c.0.push((
                "thread.rope_radius_at_metal_m".to_owned(),
                format!("must be within 1e-5..{} (thread.radius_m), got {r}", t.radius_m),
            ));
        }
        c.range("thread.linear_damping_per_s", t.linear_damping_per_s, 0.0, 100.0);
        if t.radius_m * 2.0 >= t.length_m / t.segments.max(1) as f64 {
            c.0.push((
                "thread.radius_m".to_owned(),
                "the thread's diameter must be shorter than a segment (length_m / segments)".to_owned(),
            ));
        }
        let n = &self.needle;
        c.range("needle.arc_length_m", n.arc_length_m, 0.005, 0.1);
        c.range("needle.wire_radius_m", n.wire_radius_m, 1e-5, 0.002);
        c.range("needle.mass_kg", n.mass_kg, 1e-6, 0.1);
        let ti = &self.tissue;
        c.point("tissue.centre_m", &ti.centre_m);
        c.range("tissue.yaw_rad", ti.yaw_rad, -7.0, 7.0);
        c.range("tissue.tilt_rad", ti.tilt_rad, -MAX_TILT_RAD, MAX_TILT_RAD);
        for (axis, v) in ["along", "across", "thickness"].iter().zip(&ti.flap_size_m) {
            c.range(&format!("tissue.flap_size_m.{axis}"), *v, 0.002, 0.3);
        }
        c.range("tissue.rest_gap_m", ti.rest_gap_m, 0.0, 0.05);
        c.range("tissue.opening_stiffness_n_per_m", ti.opening_stiffness_n_per_m, 0.0, 1e5);
        c.range("tissue.opening_damping_n_s_per_m", ti.opening_damping_n_s_per_m, 0.0, 1e3);
        c.range("tissue.flap_mass_kg", ti.flap_mass_kg, 1e-4, 10.0);
        let st = &self.stitch;
        c.range("stitch.bite_m", st.bite_m, 0.001, 0.05);
        c.range("stitch.depth_m", st.depth_m, 0.0, ti.flap_size_m[2]);
        c.range("stitch.along_m", st.along_m, -0.5 * ti.flap_size_m[0], 0.5 * ti.flap_size_m[0]);
        c.range("stitch.slide_friction_n", st.slide_friction_n, 0.0, 10.0);
        c.range("sensor.force_noise_n", self.sensor.force_noise_n, 0.0, 10.0);
        c.range("sensor.force_filter_s", self.sensor.force_filter_s, 0.0, 1.0);
        c.range("sensor.grip_force_n", self.sensor.grip_force_n, 0.01, 100.0);
        c.range("sensor.needle_grip_force_n", self.sensor.needle_grip_force_n, 0.01, 100.0);
        for (axis, v) in ["x", "y", "z"].iter().zip(&self.start.needle_m) {
            c.range(&format!("start.needle_m.{axis}"), *v, -0.2, 0.2);
        }
        for (axis, v) in ["x", "y", "z"].iter().zip(&self.start.tail_m) {
            c.range(&format!("start.tail_m.{axis}"), *v, -0.2, 0.2);
        }
        let ev = &self.evaluation;
        c.range("evaluation.max_knot_height_m", ev.max_knot_height_m, 0.0, 0.05);
        c.range("evaluation.max_stitch_distance_m", ev.max_stitch_distance_m, 0.0, 0.05);
        c.range("evaluation.settle_s", ev.settle_s, 0.0, 60.0);
        c.range("evaluation.max_wound_gap_m", ev.max_wound_gap_m, 0.0, 0.05);
        c.range("evaluation.holding_load_n", ev.holding_load_n, 0.0, 10.0);
        if ev.accepted.is_empty() {
            c.0.push(("evaluation.accepted".to_owned(), "must name at least one knot".to_owned()));
        }
        let tr = &self.trocars;
        for (name, p) in
            [("left", &tr.left), ("right", &tr.right), ("assist", &tr.assist), ("camera", &tr.camera)]
        {
            c.point(&format!("trocars.{name}"), p);
            // A trocar is a port in the body wall, over the tissue: inside or under the pad no
            // instrument can reach the wound through it.
            let lowest_m = ti.centre_m[2] + MIN_TROCAR_HEIGHT_M;
            if p[2] < lowest_m {
                c.0.push((
                    format!("trocars.{name}"),
                    format!(
                        "z = {} m is not above the tissue: a trocar must be at least {MIN_TROCAR_HEIGHT_M} m above its top surface (tissue.centre_m z = {} m), so at least {lowest_m} m",
                        p[2], ti.centre_m[2]
                    ),
                ));
            }
        }
        let sv = &self.servo;
        c.range("servo.time_constant_s", sv.time_constant_s, 0.0, 1.0);
        c.range("servo.max_acceleration_rad_s2", sv.max_acceleration_rad_s2, 0.1, 1e4);
        c.range("servo.play_rad", sv.play_rad, 0.0, 0.1);
        c.range("servo.instrument_time_constant_s", sv.instrument_time_constant_s, 0.0, 1.0);
        c.range("servo.instrument_max_acceleration_rad_s2", sv.instrument_max_acceleration_rad_s2, 0.1, 1e5);
        let o = &sv.calibration_offset_rad;
        for (name, offsets) in
            [("left", &o.left), ("right", &o.right), ("assist", &o.assist), ("camera", &o.camera)]
        {
            for (i, v) in offsets.iter().enumerate() {
                c.range(&format!("servo.calibration_offset_rad.{name}[{i}]"), *v, -0.2, 0.2);
            }
        }
        let tilt = self.tissue.tilt_rad;
        randomization_problems(&mut c, "randomization", &self.randomization, tilt);
        for (name, preset) in &self.presets {
            randomization_problems(
                &mut c,
                &format!("presets.{name}"),
                &preset.apply(&self.randomization),
                tilt,
            );
        }
        for (i, obstacle) in self.obstacles.iter().enumerate() {
            c.point(&format!("obstacles[{i}].centre_m"), &obstacle.centre_m);
            for (axis, v) in ["x", "y", "z"].iter().zip(&obstacle.half_extents_m) {
                c.range(&format!("obstacles[{i}].half_extents_m.{axis}"), *v, 1e-4, 2.0);
            }
        }
        problems
    }
}
