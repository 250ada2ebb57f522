//! Building blocks of human-like synthetic motion: minimum-jerk timing, paths as polylines with their
//! arc length, Hermite curves joining them, and physiological tremor.

use nalgebra::Vector3;
use rand::Rng;

/// The minimum-jerk position fraction at the time fraction `tau` (0 to 1): `10 tau^3 - 15 tau^4 + 6 tau^5`.
pub fn minimum_jerk(tau: f64) -> f64 {
    let t = tau.clamp(0.0, 1.0);
    t * t * t * (10.0 - 15.0 * t + 6.0 * t * t)
}

/// The position fraction at the time fraction `tau` of a movement whose speed rises as a minimum-jerk
/// movement's does over the first `ramp` of the time, holds, and falls over the last `ramp` (`ramp` =
/// 0.5: a plain minimum-jerk movement).
pub fn ramped(tau: f64, ramp: f64) -> f64 {
    let a = ramp.clamp(1e-6, 0.5);
    let t = tau.clamp(0.0, 1.0);
    // The area under the speed: a rising half-bell has area a / 1.875 (speed 1 at its top).
    let half = a / 1.875;
    let total = 2.0 * half + (1.0 - 2.0 * a);
    let area = if t <= a {
        2.0 * a * minimum_jerk(t / (2.0 * a)) / 1.875
    } else if t <= 1.0 - a {
        half + (t - a)
    } else {
        total - 2.0 * a * minimum_jerk((1.0 - t) / (2.0 * a)) / 1.875
    };
    area / total
}

/// A path as a polyline with its cumulative arc length.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The points, m.
    pub points: Vec<Vector3<f64>>,
    /// Arc length at each point, m.
    pub arc_m: Vec<f64>,
}

impl Polyline {
    /// A polyline through `points` (at least one).
    pub fn new(points: Vec<Vector3<f64>>) -> Self {
        let arc_m = knotlab_hw::geometry::arc_lengths(&points);
        Self { points, arc_m }
    }

    /// A straight line.
    pub fn line(from: Vector3<f64>, to: Vector3<f64>) -> Self {
        Self::new(vec![from, to])
    }

    /// Its length, m.
    pub fn length_m(&self) -> f64 {
        self.arc_m.last().copied().unwrap_or(0.0)
    }

    /// The point at arc length `s_m` (clamped to the ends).
    pub fn at(&self, s_m: f64) -> Vector3<f64> {
        let k = self.arc_m.partition_point(|a| *a <= s_m);
        if k == 0 {
            return self.points[0];
        }
        if k >= self.points.len() {
            return self.points[self.points.len() - 1];
        }
        let (a, b) = (self.arc_m[k - 1], self.arc_m[k]);
        let f = if b > a { (s_m - a) / (b - a) } else { 0.0 };
        self.points[k - 1] + (self.points[k] - self.points[k - 1]) * f
    }

    /// The first point.
    pub fn start(&self) -> Vector3<f64> {
        self.points[0]
    }

    /// The last point.
    pub fn end(&self) -> Vector3<f64> {
        self.points[self.points.len() - 1]
    }
}

/// `count + 1` points of the cubic Hermite curve from `p0` (tangent `m0`) to `p1` (tangent `m1`).
pub fn hermite(
    p0: Vector3<f64>,
    m0: Vector3<f64>,
    p1: Vector3<f64>,
    m1: Vector3<f64>,
    count: usize,
) -> Vec<Vector3<f64>> {
    (0..=count)
        .map(|k| {
            let t = k as f64 / count as f64;
            let (t2, t3) = (t * t, t * t * t);
            p0 * (2.0 * t3 - 3.0 * t2 + 1.0)
                + m0 * (t3 - 2.0 * t2 + t)
                + p1 * (-2.0 * t3 + 3.0 * t2)
                + m1 * (t3 - t2)
        })
        .collect()
}

/// Physiological tremor: per axis, two sinusoids between 8 and 12 Hz whose amplitudes wander slowly,
/// plus white sensor noise.
#[derive(Clone, Debug, PartialEq)]
pub struct Tremor {
    /// Per axis: (frequency Hz, amplitude m, phase rad) of each component.
    components: [[(f64, f64, f64); 2]; 3],
    /// Per axis: (frequency Hz, phase rad) of the slow amplitude modulation.
    modulation: [(f64, f64); 3],
    /// Standard deviation of the white noise, m.
    pub noise_m: f64,
}

impl Tremor {
    /// A tremor of about `amplitude_m` per axis (the components' amplitudes add to it).
    pub fn draw(rng: &mut impl Rng, amplitude_m: f64, noise_m: f64) -> Self {
        let mut components = [[(0.0, 0.0, 0.0); 2]; 3];
        let mut modulation = [(0.0, 0.0); 3];
        for axis in 0..3 {
            let split = rng.random_range(0.55..0.75);
            for (c, share) in [split, 1.0 - split].into_iter().enumerate() {
                components[axis][c] = (
                    rng.random_range(8.0..12.0),
                    amplitude_m * share,
                    rng.random_range(0.0..std::f64::consts::TAU),
                );
            }
            modulation[axis] = (rng.random_range(0.2..0.5), rng.random_range(0.0..std::f64::consts::TAU));
        }
        Self { components, modulation, noise_m }
    }

    /// The tremor's displacement at `t_s` (without the white noise), m.
    pub fn at(&self, t_s: f64) -> Vector3<f64> {
        let tau = std::f64::consts::TAU;
        Vector3::from_fn(|axis, _| {
            let (mf, mp) = self.modulation[axis];
            let gain = 1.0 + 0.3 * (tau * mf * t_s + mp).sin();
            gain * self.components[axis].iter().map(|(f, a, p)| a * (tau * f * t_s + p).sin()).sum::<f64>()
        })
    }
}
