//! The pressure Poisson equation `lap(p) = div(F, G) / dt` with Neumann conditions on walls and obstacles
//! (Griebel et al., section 3.2): the residual both solvers stop on, SOR (the reference) and the
//! factor-once sparse Cholesky solve.
//!
//! Both solve the same matrix: in every fluid cell `sum over fluid neighbours (p_nb - p) / h^2 = rhs`
//! (the book's epsilon form, eq. 3.44). After the velocity correction the divergence of a cell is
//! `dt * (rhs - lap(p))`, so the tolerance is set on that: the solve ends when the divergence it leaves
//! is below `divergence_tol_per_s` in every fluid cell.

mod direct;
mod sor;

pub use direct::DirectSolver;
pub use sor::SorSolver;

use super::error::FluidError;
use super::flags::Flags;
use super::params::PressureSolverKind;

/// What one pressure solve did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PressureSolve {
    /// Iterations (SOR sweeps; 1 for the direct solve).
    pub iterations: usize,
    /// Largest `|rhs - lap(p)|` over the fluid cells after the solve, 1/s^2 (SOR's stopping measure;
    /// NaN for the direct solve, which does not compute it).
    pub max_residual_per_s2: f64,
}

/// A pressure solver bound to one flag field.
#[derive(Debug)]
pub enum PressureSolver {
    /// Successive over-relaxation.
    Sor(SorSolver),
    /// Sparse Cholesky, factored once.
    Direct(Box<DirectSolver>),
}

impl PressureSolver {
    /// A solver of `kind` for `flags` (the direct solver factors the matrix here).
    pub fn new(kind: PressureSolverKind, flags: &Flags) -> Result<Self, FluidError> {
        Ok(match kind {
            PressureSolverKind::Sor => Self::Sor(SorSolver::new(flags)),
            PressureSolverKind::Direct => Self::Direct(Box::new(DirectSolver::new(flags)?)),
        })
    }

    /// Which kind this is.
    pub fn kind(&self) -> PressureSolverKind {
        match self {
            Self::Sor(_) => PressureSolverKind::Sor,
            Self::Direct(_) => PressureSolverKind::Direct,
        }
    }

    /// Solves for `p` (SOR: warm-started from its values, until `max |rhs - lap(p)| <= max_residual_per_s2`
    /// or `max_iterations` sweeps; direct: exactly). Returns what it did, converged or not: the caller
    /// checks the divergence the solution leaves.
    pub fn solve(
        &mut self,
        flags: &Flags,
        rhs: &[f64],
        p: &mut [f64],
        max_residual_per_s2: f64,
        max_iterations: usize,
    ) -> PressureSolve {
        match self {
            Self::Sor(sor) => sor.solve(flags, rhs, p, max_residual_per_s2, max_iterations),
            Self::Direct(direct) => direct.solve(flags, rhs, p),
        }
    }
}

/// The largest `|rhs - lap(p)|` over the fluid cells, 1/s^2 (the epsilon-form Laplacian).
pub fn max_residual(flags: &Flags, rhs: &[f64], p: &[f64]) -> f64 {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let inv_h2 = 1.0 / (grid.h_m * grid.h_m);
    let fl = &flags.fluid;
    let mut worst = 0.0f64;
    for j in 1..=n {
        for i in 1..=n {
            let k = j * s + i;
            if !fl[k] {
                continue;
            }
            let mut lap = 0.0;
            for nb in [k + 1, k - 1, k + s, k - s] {
                if fl[nb] {
                    lap += p[nb] - p[k];
                }
            }
            worst = worst.max((rhs[k] - lap * inv_h2).abs());
        }
    }
    worst
}
