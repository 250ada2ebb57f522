//! Successive over-relaxation for the pressure equation (Griebel et al., eq. 3.44), lexicographic, the
//! reference solver: simple, slow on fine grids (its iterations grow about linearly with n).

use std::f64::consts::PI;

use super::super::flags::Flags;
use super::{PressureSolve, max_residual};

/// How many sweeps between two residual checks.
const CHECK_EVERY: usize = 4;

/// SOR bound to one flag field.
#[derive(Clone, Debug)]
pub struct SorSolver {
    /// Per cell: 1 for fluid, 0 otherwise (the epsilon coefficients).
    weight: Vec<f64>,
    /// Per fluid cell: 1 / (number of fluid neighbours), 0 where there is none.
    inv_count: Vec<f64>,
    /// The relaxation factor.
    pub omega: f64,
}

impl SorSolver {
    /// SOR for `flags` with the relaxation factor of the model problem, `2 / (1 + sin(pi / (n + 1)))`.
    pub fn new(flags: &Flags) -> Self {
        let grid = flags.grid;
        let s = grid.stride();
        let weight: Vec<f64> = flags.fluid.iter().map(|&f| if f { 1.0 } else { 0.0 }).collect();
        let mut inv_count = vec![0.0; grid.len()];
        for j in 1..=grid.n {
            for i in 1..=grid.n {
                let k = j * s + i;
                let count = weight[k + 1] + weight[k - 1] + weight[k + s] + weight[k - s];
                if flags.fluid[k] && count > 0.0 {
                    inv_count[k] = 1.0 / count;
                }
            }
        }
        let omega = 2.0 / (1.0 + (PI / (grid.n as f64 + 1.0)).sin());
        Self { weight, inv_count, omega }
    }

    /// Sweeps until `max |rhs - lap(p)| <= tol_per_s2` (checked every few sweeps and before the first)
    /// or `max_iterations` sweeps.
    pub fn solve(
        &mut self,
        flags: &Flags,
        rhs: &[f64],
        p: &mut [f64],
        tol_per_s2: f64,
        max_iterations: usize,
    ) -> PressureSolve {
        let grid = flags.grid;
        let (n, s) = (grid.n, grid.stride());
        let h2 = grid.h_m * grid.h_m;
        let omega = self.omega;
        let mut residual = max_residual(flags, rhs, p);
        let mut iterations = 0;
        while residual > tol_per_s2 && iterations < max_iterations {
            for _ in 0..CHECK_EVERY.min(max_iterations - iterations) {
                for j in 1..=n {
                    let row = j * s;
                    for i in 1..=n {
                        let k = row + i;
                        let inv = self.inv_count[k];
                        if inv == 0.0 {
                            continue;
                        }
                        let w = &self.weight;
                        let sum = w[k + 1] * p[k + 1]
                            + w[k - 1] * p[k - 1]
                            + w[k + s] * p[k + s]
                            + w[k - s] * p[k - s];
                        p[k] = (1.0 - omega) * p[k] + omega * inv * (sum - h2 * rhs[k]);
                    }
                }
                iterations += 1;
            }
            residual = max_residual(flags, rhs, p);
        }
        PressureSolve { iterations, max_residual_per_s2: residual }
    }
}
