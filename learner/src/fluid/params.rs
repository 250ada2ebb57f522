//! The solver's parameters: viscosity, the donor-cell mixing parameter, the time-step safety factor, the
//! divergence tolerance of the pressure solve and the pressure solver.

use super::error::FluidError;

/// Which pressure Poisson solver a simulation uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PressureSolverKind {
    /// Successive over-relaxation (Griebel et al., section 3.2.5), the reference: iterates until the
    /// divergence it leaves is below the tolerance.
    Sor,
    /// Sparse Cholesky factorization (faer) of the pressure matrix, done once per obstacle layout, then
    /// one forward and one backward substitution per step; chosen by measurement (see `bench/benches/fluid.rs`).
    Direct,
}

impl PressureSolverKind {
    /// A short name (`sor`, `direct`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Sor => "sor",
            Self::Direct => "direct",
        }
    }
}

/// The donor-cell mixing parameter gamma of the convective terms (Griebel et al., eq. 3.19): 0 is central
/// differences, 1 pure upwind (donor cell). Stability needs `gamma >= |w| dt / h` for the velocities `w`
/// that carry the fluxes (eq. 3.51 takes the largest over the grid).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DonorCell {
    /// A fixed gamma in `[0, 1]` (the book uses 0.9).
    Fixed(f64),
    /// One gamma per step, `factor * max(|u| dt / h, |v| dt / h)` over the grid, capped at 1 (eq. 3.51
    /// with a safety factor >= 1).
    Global {
        /// Safety factor, at least 1.
        factor: f64,
    },
    /// A gamma per flux, `min(1, factor |w| dt / h)` for the velocity `w` carrying it: the stability
    /// condition applied where it arises. Upwind diffusion then scales with `w^2 dt` rather than
    /// `|w| h`, which keeps high Reynolds numbers accurate on coarse grids.
    Local {
        /// Safety factor, at least 1.
        factor: f64,
    },
}

/// Parameters of a fluid simulation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FluidParams {
    /// Kinematic viscosity, m^2/s (in the dimensionless lid-driven cavity, 1 / Re).
    pub viscosity_m2ps: f64,
    /// The donor-cell mixing parameter.
    pub donor_cell: DonorCell,
    /// Safety factor tau in `(0, 1]` on the stable time step (Griebel et al., eq. 3.50).
    pub tau: f64,
    /// The pressure solve stops when the divergence it leaves in every fluid cell is below this, 1/s.
    pub divergence_tol_per_s: f64,
    /// The pressure solver.
    pub solver: PressureSolverKind,
    /// Most SOR iterations per step before the step fails with
    /// [`FluidError::PressureNotConverged`].
    pub max_sor_iterations: usize,
}

impl FluidParams {
    /// Checks every field; names the first bad one.
    pub fn validate(&self) -> Result<(), FluidError> {
        let positive = |name: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(FluidError::invalid(name, format!("must be a positive number, got {x}")))
            }
        };
        positive("viscosity_m2ps", self.viscosity_m2ps)?;
        positive("divergence_tol_per_s", self.divergence_tol_per_s)?;
        if !(self.tau > 0.0 && self.tau <= 1.0) {
            return Err(FluidError::invalid("tau", format!("must be in (0, 1], got {}", self.tau)));
        }
        match self.donor_cell {
            DonorCell::Fixed(g) if !(0.0..=1.0).contains(&g) => {
                return Err(FluidError::invalid("donor_cell", format!("gamma must be in [0, 1], got {g}")));
            }
            DonorCell::Global { factor } | DonorCell::Local { factor }
                if !(factor.is_finite() && factor >= 1.0) =>
            {
                return Err(FluidError::invalid("donor_cell", format!("factor must be >= 1, got {factor}")));
            }
            _ => {}
        }
        if self.max_sor_iterations == 0 {
            return Err(FluidError::invalid("max_sor_iterations", "must be at least 1"));
        }
        Ok(())
    }
}
