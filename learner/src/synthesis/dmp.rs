//! Discrete dynamic movement primitives (Ijspeert, Nakanishi, Hoffmann, Pastor and Schaal, "Dynamical
//! movement primitives: learning attractor models for motor behaviors", Neural Computation 2013), one
//! per coordinate: a critically damped spring to the goal, plus a forcing term of Gaussian basis
//! functions of a decaying phase, fitted to the demonstration by locally weighted regression.
//!
//! The forcing term is not scaled by `goal - start`: a primitive that ends near where it starts (the
//! double loop of a winding) would otherwise have its shape blown up or flipped by a tiny change of its
//! ends. The shape is kept, the spring absorbs a moved start or goal.

/// A learned DMP of one coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct Dmp {
    /// Duration of the demonstration, s.
    pub tau_s: f64,
    /// Basis centres in phase.
    centres: Vec<f64>,
    /// Basis widths.
    widths: Vec<f64>,
    /// Basis weights.
    weights: Vec<f64>,
}

/// Spring constant of the transformation system (critically damped with `BETA = ALPHA / 4`).
const ALPHA: f64 = 25.0;
const BETA: f64 = ALPHA / 4.0;
/// Decay of the canonical system: the phase falls to e^-4 (1.8 %) by the end.
const ALPHA_X: f64 = 4.0;

impl Dmp {
    /// Fits a DMP with `basis` functions to `y` sampled every `dt_s` (at least 3 samples).
    pub fn fit(y: &[f64], dt_s: f64, basis: usize) -> Option<Self> {
        let n = y.len();
        if n < 3 || !(dt_s.is_finite() && dt_s > 0.0) || basis == 0 {
            return None;
        }
        let tau = dt_s * (n - 1) as f64;
        let (y0, g) = (y[0], y[n - 1]);
        let yd: Vec<f64> = (0..n)
            .map(|k| {
                let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
                (y[b] - y[a]) / (dt_s * (b - a) as f64)
            })
            .collect();
        let ydd: Vec<f64> = (0..n)
            .map(|k| {
                let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
                (yd[b] - yd[a]) / (dt_s * (b - a) as f64)
            })
            .collect();
        let centres: Vec<f64> =
            (0..basis).map(|i| (-ALPHA_X * i as f64 / (basis - 1).max(1) as f64).exp()).collect();
        let widths: Vec<f64> = (0..basis)
            .map(|i| {
                let next = if i + 1 < basis { centres[i + 1] } else { centres[i] * 0.5 };
                1.0 / (next - centres[i]).powi(2).max(1e-12)
            })
            .collect();
        let phase = |t: f64| (-ALPHA_X * t / tau).exp();
        // Target forcing: tau^2 ydd - alpha (beta (g - y) - tau yd).
        let target: Vec<f64> =
            (0..n).map(|k| tau * tau * ydd[k] - ALPHA * (BETA * (g - y[k]) - tau * yd[k])).collect();
        let weights = (0..basis)
            .map(|i| {
                let (mut num, mut den) = (0.0, 0.0);
                for (k, f) in target.iter().enumerate() {
                    let x = phase(k as f64 * dt_s);
                    let psi = (-widths[i] * (x - centres[i]).powi(2)).exp();
                    num += psi * x * f;
                    den += psi * x * x;
                }
                if den > 1e-300 { num / den } else { 0.0 }
            })
            .collect();
        let _ = y0;
        Some(Self { tau_s: tau, centres, widths, weights })
    }

    fn forcing(&self, x: f64) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for ((c, h), w) in self.centres.iter().zip(&self.widths).zip(&self.weights) {
            let psi = (-h * (x - c).powi(2)).exp();
            num += psi * w;
            den += psi;
        }
        if den > 1e-300 { num / den * x } else { 0.0 }
    }

    /// Runs from `start` to `goal` over `duration_s` (the demonstration's pace scaled), integrating every
    /// `dt_s`; returns the positions at `0, dt, 2 dt, ..., duration`.
    pub fn rollout(&self, start: f64, goal: f64, duration_s: f64, dt_s: f64) -> Vec<f64> {
        let steps = (duration_s / dt_s).round().max(1.0) as usize;
        let dt = duration_s / steps as f64;
        let tau = duration_s;
        let (mut y, mut z, mut x) = (start, 0.0, 1.0);
        let mut out = Vec::with_capacity(steps + 1);
        out.push(y);
        // Substeps keep the stiff spring stable at coarse output steps.
        let sub = 10;
        let h = dt / sub as f64;
        for _ in 0..steps {
            for _ in 0..sub {
                let zd = (ALPHA * (BETA * (goal - y) - z) + self.forcing(x)) / tau;
                let yd = z / tau;
                z += zd * h;
                y += yd * h;
                x += -ALPHA_X * x / tau * h;
            }
            out.push(y);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A DMP fitted to a demonstration reproduces it within 2 mm, and rolled out to a moved start and goal
    /// starts exactly at the start and ends within 2 mm of the goal.
    #[test]
    fn reproduces_its_demonstration_and_follows_a_moved_goal() {
        let dt = 0.01;
        let demo: Vec<f64> = (0..=200)
            .map(|k| {
                let s = k as f64 / 200.0;
                // From rest to rest, as a demonstrated primitive is: two wiggles on a minimum-jerk reach.
                let envelope = 16.0 * s * s * (1.0 - s) * (1.0 - s);
                0.02 * (2.0 * std::f64::consts::TAU * s).sin() * envelope
                    + 0.05 * knotlab_hw::skill::profile::min_jerk(s)
            })
            .collect();
        let dmp = Dmp::fit(&demo, dt, 40).unwrap();
        let again = dmp.rollout(demo[0], demo[200], 2.0, dt);
        let worst = again.iter().zip(&demo).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 2e-3, "reproduction error {worst} m");
        let moved = dmp.rollout(0.01, 0.07, 2.0, dt);
        assert!((moved[0] - 0.01).abs() < 1e-12);
        assert!((moved[200] - 0.07).abs() < 2e-3, "ends at {}", moved[200]);
    }
}
