//! One synthetic instrument's script: rests and minimum-jerk moves along paths, jaw movements, what the
//! jaws hold, force pulses and drags, an optional offset following another instrument; sampled into
//! demonstration samples with tremor and noise.

use nalgebra::{UnitQuaternion, Vector3};
use rand::Rng;
use rand_distr::{Distribution, Normal};

use super::motion::{Polyline, Tremor, minimum_jerk, ramped};
use crate::demonstration::{GraspState, Sample};

/// A minimum-jerk move along a path.
#[derive(Clone, Debug)]
pub struct Move {
    /// Start, s.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// The path, stitch frame, m.
    pub path: Polyline,
    /// The fraction of the time the speed takes to rise (and to fall): 0.5 a plain minimum-jerk move,
    /// less a move that cruises in between.
    pub ramp: f64,
}

/// A minimum-jerk jaw movement.
#[derive(Clone, Copy, Debug)]
pub struct JawMove {
    /// Start, s.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// Angle at the end, rad.
    pub to_rad: f64,
}

/// A pull that tightens: no force until `t_tight_s`, then rising to `peak_n` at `t_release_s`, then
/// decaying in 15 ms (the jaws let go).
#[derive(Clone, Copy, Debug)]
pub struct ForcePulse {
    /// When the thread becomes taut, s.
    pub t_tight_s: f64,
    /// When the jaws start to open, s.
    pub t_release_s: f64,
    /// The force then, N.
    pub peak_n: f64,
    /// Unit direction of the force on the instrument, stitch frame.
    pub direction: Vector3<f64>,
}

/// A small drag force, a smooth bump over `[t0, t1]`.
#[derive(Clone, Copy, Debug)]
pub struct Drag {
    /// Start, s.
    pub t0: f64,
    /// End, s.
    pub t1: f64,
    /// Largest force, N.
    pub peak_n: f64,
    /// Unit direction, stitch frame.
    pub direction: Vector3<f64>,
}

/// An instrument's script.
#[derive(Clone, Debug)]
pub struct Track {
    /// Position before the first move, stitch frame, m.
    pub rest_m: Vector3<f64>,
    /// The moves, in time order, not overlapping.
    pub moves: Vec<Move>,
    /// Jaw angle before the first jaw move, rad.
    pub jaw0_rad: f64,
    /// The jaw moves, in time order.
    pub jaw_moves: Vec<JawMove>,
    /// Whether the jaws hold something from the start.
    pub holding0: bool,
    /// From these times on the jaws hold (true) or let go (false).
    pub holding: Vec<(f64, bool)>,
    /// Force pulses.
    pub pulses: Vec<ForcePulse>,
    /// Drags.
    pub drags: Vec<Drag>,
    /// An extra displacement (a synchronized movement), stitch frame, m.
    pub offset: Option<Offset>,
    /// `stitch_from_tip` at rest.
    pub orientation: UnitQuaternion<f64>,
    /// Axis of the slow wrist wobble (stitch frame).
    pub wobble_axis: Vector3<f64>,
}

/// A displacement as a function of time (stitch frame, m).
#[derive(Clone)]
pub struct Offset(pub std::sync::Arc<dyn Fn(f64) -> Vector3<f64> + Send + Sync>);

impl std::fmt::Debug for Offset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Offset(fn)")
    }
}

impl Track {
    /// A track resting at `rest_m`.
    pub fn new(
        rest_m: Vector3<f64>,
        orientation: UnitQuaternion<f64>,
        jaw0_rad: f64,
        holding0: bool,
    ) -> Self {
        Self {
            rest_m,
            moves: Vec::new(),
            jaw0_rad,
            jaw_moves: Vec::new(),
            holding0,
            holding: Vec::new(),
            pulses: Vec::new(),
            drags: Vec::new(),
            offset: None,
            orientation,
            wobble_axis: Vector3::x(),
        }
    }

    /// Where the tip rests after its last move.
    pub fn end_position(&self) -> Vector3<f64> {
        self.moves.last().map_or(self.rest_m, |m| m.path.end())
    }

    /// The noise-free position at `t_s`.
    pub fn position_at(&self, t_s: f64) -> Vector3<f64> {
        let base = match self.moves.iter().rev().find(|m| m.t0 <= t_s) {
            None => self.rest_m,
            Some(m) => m.path.at(ramped((t_s - m.t0) / (m.t1 - m.t0), m.ramp) * m.path.length_m()),
        };
        base + self.offset.as_ref().map_or(Vector3::zeros(), |f| (f.0)(t_s))
    }

    /// The jaw angle at `t_s`.
    pub fn jaw_at(&self, t_s: f64) -> f64 {
        let mut angle = self.jaw0_rad;
        for j in &self.jaw_moves {
            if t_s >= j.t1 {
                angle = j.to_rad;
            } else if t_s > j.t0 {
                angle += (j.to_rad - angle) * minimum_jerk((t_s - j.t0) / (j.t1 - j.t0));
                break;
            } else {
                break;
            }
        }
        angle
    }

    /// Whether the jaws hold something at `t_s`.
    pub fn holding_at(&self, t_s: f64) -> bool {
        self.holding.iter().rev().find(|(t, _)| *t <= t_s).map_or(self.holding0, |(_, h)| *h)
    }

    /// The noise-free force on the instrument at `t_s`, stitch frame, N.
    pub fn force_at(&self, t_s: f64) -> Vector3<f64> {
        let mut f = Vector3::zeros();
        for p in &self.pulses {
            let magnitude = if t_s < p.t_tight_s {
                0.0
            } else if t_s <= p.t_release_s {
                p.peak_n * ((t_s - p.t_tight_s) / (p.t_release_s - p.t_tight_s)).powf(1.5)
            } else {
                p.peak_n * (-(t_s - p.t_release_s) / 0.015).exp()
            };
            f += p.direction * magnitude;
        }
        for d in &self.drags {
            if (d.t0..=d.t1).contains(&t_s) {
                let s = (std::f64::consts::PI * (t_s - d.t0) / (d.t1 - d.t0)).sin();
                f += d.direction * d.peak_n * s * s;
            }
        }
        f
    }

    /// Samples at `times_s`: positions and forces carried to the world by `world_from_stitch`, tremor
    /// and sensor noise added.
    pub fn sample(
        &self,
        times_s: &[f64],
        world_from_stitch: &nalgebra::Isometry3<f64>,
        tremor: &Tremor,
        force_noise_n: f64,
        rng: &mut impl Rng,
    ) -> Vec<Sample> {
        let position_noise =
            Normal::new(0.0, tremor.noise_m.max(1e-12)).expect("a positive standard deviation");
        let force_noise = Normal::new(0.0, force_noise_n.max(1e-12)).expect("a positive standard deviation");
        let jaw_noise = Normal::new(0.0, 0.002).expect("a positive standard deviation");
        times_s
            .iter()
            .map(|&t| {
                let noise = Vector3::from_fn(|_, _| position_noise.sample(rng));
                let p = self.position_at(t) + tremor.at(t) + noise;
                let wobble = UnitQuaternion::from_scaled_axis(self.wobble_axis * 0.08 * (0.7 * t).sin());
                let q = world_from_stitch.rotation * wobble * self.orientation;
                let f = self.force_at(t) + Vector3::from_fn(|_, _| force_noise.sample(rng));
                let jaw_rad = (self.jaw_at(t) + jaw_noise.sample(rng)).max(0.0);
                let grasp = if jaw_rad > 0.2 {
                    GraspState::Open
                } else if self.holding_at(t) {
                    GraspState::Holding
                } else {
                    GraspState::ClosedEmpty
                };
                let qc = q.quaternion();
                Sample {
                    time_s: t,
                    position_m: world_from_stitch.transform_point(&p.into()).coords,
                    quaternion_xyzw: [qc.i, qc.j, qc.k, qc.w],
                    jaw_rad,
                    grasp,
                    force_n: world_from_stitch.rotation * f,
                }
            })
            .collect()
    }
}
