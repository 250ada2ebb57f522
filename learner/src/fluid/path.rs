//! The demonstrated 2D path: points in plane coordinates with the speed along it, its exact arc-length
//! parametrisation, sampling at equal arc-length steps, and its timing.
//!
//! The paper samples its spline at equal arc-length steps `d` by a binary search on the spline parameter
//! with a tolerance. Here the path is a polyline (a spline is sampled densely into one), whose arc length
//! is exact: a sample at arc length `s` is found by a binary search over the cumulative lengths of the
//! segments and a linear interpolation, exact to rounding. The speed is linear in arc length between the
//! points, so the time along the path is also exact: `t = integral ds / v(s)`, a logarithm per segment.

use nalgebra::{Isometry2, Vector2};

use super::error::FluidError;

/// A path in plane coordinates with the speed of the demonstration at each point.
#[derive(Clone, Debug, PartialEq)]
pub struct SpeedPath {
    /// Points in plane coordinates, m, in the order of the movement.
    pub points_m: Vec<Vector2<f64>>,
    /// Speed along the path at each point, m/s, positive.
    pub speed_mps: Vec<f64>,
}

impl SpeedPath {
    /// A checked path: at least two points, finite, as many speeds as points, every speed positive, and a
    /// positive length.
    pub fn new(points_m: Vec<Vector2<f64>>, speed_mps: Vec<f64>) -> Result<Self, FluidError> {
        if points_m.len() < 2 {
            return Err(FluidError::invalid(
                "path.points_m",
                format!("need at least 2 points, got {}", points_m.len()),
            ));
        }
        if speed_mps.len() != points_m.len() {
            return Err(FluidError::invalid(
                "path.speed_mps",
                format!("{} speeds for {} points", speed_mps.len(), points_m.len()),
            ));
        }
        if let Some(i) = points_m.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(FluidError::invalid(format!("path.points_m[{i}]"), "not finite"));
        }
        if let Some(i) = speed_mps.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(FluidError::invalid(
                format!("path.speed_mps[{i}]"),
                format!("must be a positive speed, got {}", speed_mps[i]),
            ));
        }
        let path = Self { points_m, speed_mps };
        if path.length_m().is_nan() || path.length_m() <= 0.0 {
            return Err(FluidError::invalid("path.points_m", "the path has no length"));
        }
        Ok(path)
    }

    /// A path at one constant speed.
    pub fn constant_speed(points_m: Vec<Vector2<f64>>, speed_mps: f64) -> Result<Self, FluidError> {
        let speeds = vec![speed_mps; points_m.len()];
        Self::new(points_m, speeds)
    }

    /// The built-in test path, a knot's double wrap: it comes in from outside along `+x`, winds twice
    /// counter-clockwise around `centre_m` with the radius shrinking from `radius_m` to 0.8 `radius_m`,
    /// and leaves along `+x`; about 2.5 turns of length, at `speed_mps` throughout (slower by a fifth in
    /// the first and last tenth of the length, as a hand starts and stops).
    pub fn double_loop(centre_m: Vector2<f64>, radius_m: f64, speed_mps: f64) -> Result<Self, FluidError> {
        if !(radius_m.is_finite() && radius_m > 0.0) {
            return Err(FluidError::invalid("radius_m", format!("must be positive, got {radius_m}")));
        }
        let mut points = Vec::new();
        // Lead in from below the start of the first turn.
        let start = centre_m + Vector2::new(0.0, -radius_m);
        for k in 0..20 {
            points.push(start + Vector2::new(-radius_m * (1.0 - k as f64 / 20.0), 0.0));
        }
        let turns = 2.0;
        let steps = 400;
        for k in 0..=steps {
            let f = k as f64 / steps as f64;
            let angle = -std::f64::consts::FRAC_PI_2 + turns * std::f64::consts::TAU * f;
            let r = radius_m * (1.0 - 0.2 * f);
            points.push(centre_m + Vector2::new(r * angle.cos(), r * angle.sin()));
        }
        let end = points[points.len() - 1];
        for k in 1..=20 {
            points.push(end + Vector2::new(radius_m * k as f64 / 20.0, 0.0));
        }
        let mut arc = vec![0.0];
        for w in points.windows(2) {
            arc.push(arc[arc.len() - 1] + (w[1] - w[0]).norm());
        }
        let total = arc[arc.len() - 1];
        let speeds = arc
            .iter()
            .map(|s| {
                let edge = (s / total).min(1.0 - s / total);
                speed_mps * if edge < 0.1 { 0.8 + 2.0 * edge } else { 1.0 }
            })
            .collect();
        Self::new(points, speeds)
    }

    /// Length of the path, m.
    pub fn length_m(&self) -> f64 {
        self.points_m.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
    }

    /// The path moved rigidly inside its plane.
    pub fn transformed(&self, moved_from_old: &Isometry2<f64>) -> Self {
        Self {
            points_m: self
                .points_m
                .iter()
                .map(|p| moved_from_old.transform_point(&(*p).into()).coords)
                .collect(),
            speed_mps: self.speed_mps.clone(),
        }
    }
}

/// One sample of a path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcSample {
    /// Arc length from the start, m.
    pub s_m: f64,
    /// Position, m.
    pub point_m: Vector2<f64>,
    /// Speed, m/s.
    pub speed_mps: f64,
}

/// A path's exact arc-length parametrisation (zero-length segments dropped).
#[derive(Clone, Debug, PartialEq)]
pub struct ArcPath {
    points: Vec<Vector2<f64>>,
    speeds: Vec<f64>,
    /// Arc length at each point.
    s: Vec<f64>,
    /// Time at each point, from the start.
    t: Vec<f64>,
}

impl ArcPath {
    /// The parametrisation of `path`.
    pub fn new(path: &SpeedPath) -> Self {
        let mut points = vec![path.points_m[0]];
        let mut speeds = vec![path.speed_mps[0]];
        let mut s = vec![0.0];
        let mut t = vec![0.0];
        for (p, v) in path.points_m.iter().zip(&path.speed_mps).skip(1) {
            let last = points.len() - 1;
            let len = (p - points[last]).norm();
            if len <= 0.0 {
                continue;
            }
            t.push(t[last] + segment_time(len, speeds[last], *v));
            s.push(s[last] + len);
            points.push(*p);
            speeds.push(*v);
        }
        Self { points, speeds, s, t }
    }

    /// Length, m.
    pub fn length_m(&self) -> f64 {
        self.s[self.s.len() - 1]
    }

    /// Time to travel the path at its speeds, s.
    pub fn duration_s(&self) -> f64 {
        self.t[self.t.len() - 1]
    }

    /// The points (zero-length segments dropped).
    pub fn points(&self) -> &[Vector2<f64>] {
        &self.points
    }

    /// The sample at arc length `s_m` (clamped to the path).
    pub fn at(&self, s_m: f64) -> ArcSample {
        let s_m = s_m.clamp(0.0, self.length_m());
        let k = self.segment_at(&self.s, s_m);
        let len = self.s[k + 1] - self.s[k];
        let f = if len > 0.0 { ((s_m - self.s[k]) / len).clamp(0.0, 1.0) } else { 0.0 };
        ArcSample {
            s_m,
            point_m: self.points[k] + (self.points[k + 1] - self.points[k]) * f,
            speed_mps: self.speeds[k] + (self.speeds[k + 1] - self.speeds[k]) * f,
        }
    }

    /// The sample reached at time `t_s` moving at the path's speeds (clamped to the path): the exact
    /// inverse of the time integral.
    pub fn at_time(&self, t_s: f64) -> ArcSample {
        let t_s = t_s.clamp(0.0, self.duration_s());
        let k = self.segment_at(&self.t, t_s);
        let (v0, v1) = (self.speeds[k], self.speeds[k + 1]);
        let len = self.s[k + 1] - self.s[k];
        let tau = t_s - self.t[k];
        // v(x) = v0 + a x along the segment, dx/dt = v: x(t) = v0 (e^(a t) - 1) / a.
        let a = (v1 - v0) / len;
        let x = if (a * tau).abs() < 1e-9 {
            v0 * tau * (1.0 + 0.5 * a * tau)
        } else {
            v0 * (a * tau).exp_m1() / a
        };
        self.at(self.s[k] + x.clamp(0.0, len))
    }

    /// Samples every `d_m` of arc length from the start, and the end point (the last step may be shorter).
    /// A step that is not positive, or below a ten-millionth of the length, is taken as that.
    pub fn sample_equal(&self, d_m: f64) -> Vec<ArcSample> {
        let total = self.length_m();
        let d_m = if d_m.is_finite() && d_m > 0.0 { d_m.max(total * 1e-7) } else { total * 1e-7 };
        let count = (total / d_m).floor() as usize;
        let mut out: Vec<ArcSample> = (0..=count).map(|k| self.at(k as f64 * d_m)).collect();
        if total - count as f64 * d_m > 1e-12 * total.max(1e-9) {
            out.push(self.at(total));
        }
        out
    }

    /// The segment `k` with `xs[k] <= x <= xs[k + 1]` (`xs` increasing).
    fn segment_at(&self, xs: &[f64], x: f64) -> usize {
        let k = xs.partition_point(|v| *v <= x);
        k.saturating_sub(1).min(xs.len() - 2)
    }
}

/// Time to travel `len` with the speed linear in arc length from `v0` to `v1`, s.
fn segment_time(len: f64, v0: f64, v1: f64) -> f64 {
    let r = v1 / v0;
    if (r - 1.0).abs() < 1e-9 { len / v0 * (1.0 - 0.5 * (r - 1.0)) } else { len * r.ln() / (v1 - v0) }
}
