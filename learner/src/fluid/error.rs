//! What can go wrong in the fluid solver and in the instantiation of a 2D primitive.

use thiserror::Error;

/// An error of the fluid solver, the stirring or the particle tracing.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FluidError {
    /// An input is out of range or malformed: the field and the reason.
    #[error("{field}: {reason}")]
    Invalid {
        /// The offending input, e.g. `path.speed_mps[3]` or `mask`.
        field: String,
        /// Why it was refused.
        reason: String,
    },
    /// The pressure solve stopped before the divergence it leaves fell below the tolerance.
    #[error(
        "pressure solve ({solver}) at step {step} stopped after {iterations} iterations with divergence \
         {divergence_per_s:.3e} 1/s above the tolerance {tolerance_per_s:.3e} 1/s"
    )]
    PressureNotConverged {
        /// Which solver.
        solver: &'static str,
        /// The time step (counted from 0).
        step: usize,
        /// Iterations done.
        iterations: usize,
        /// Largest divergence the solve would leave, 1/s.
        divergence_per_s: f64,
        /// The tolerance, 1/s.
        tolerance_per_s: f64,
    },
    /// The sparse Cholesky factorization of the pressure matrix failed.
    #[error("pressure matrix factorization failed: {0}")]
    Factorization(String),
    /// The flow became non-finite.
    #[error("the flow became non-finite at step {step} (t = {t_s:.6} s)")]
    Diverged {
        /// The time step (counted from 0).
        step: usize,
        /// Simulated time, s.
        t_s: f64,
    },
    /// No fluid cell with the required clearance where the path is to be stirred.
    #[error("no room to stir: {0}")]
    NoRoom(String),
}

impl FluidError {
    /// An [`FluidError::Invalid`] for `field` with `reason`.
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Invalid { field: field.into(), reason: reason.into() }
    }
}
