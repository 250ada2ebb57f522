//! Adaptive time-step control (Griebel et al., eq. 3.50): the largest step that keeps the explicit scheme
//! stable, times a safety factor, and the donor-cell parameter that step needs.

use super::momentum::Mixing;
use super::params::DonorCell;

/// The stable time step: `tau * min(h^2 / (4 nu), h / |u|max, h / |v|max)`, s. The viscous limit is the
/// book's `Re / 2 (1 / dx^2 + 1 / dy^2)^-1` with `dx = dy = h` and `1 / Re = nu`; a velocity of zero sets
/// no limit.
pub fn stable_dt(tau: f64, h_m: f64, viscosity_m2ps: f64, max_abs_u_mps: f64, max_abs_v_mps: f64) -> f64 {
    let mut dt = h_m * h_m / (4.0 * viscosity_m2ps);
    for speed in [max_abs_u_mps, max_abs_v_mps] {
        if speed > 0.0 {
            dt = dt.min(h_m / speed);
        }
    }
    tau * dt
}

/// The convective mixing for a step of `dt_s`: fixed, the global bound `max(|u|, |v|) dt / h` times a
/// factor (capped at 1), or per flux.
pub fn donor_cell_mixing(
    donor_cell: DonorCell,
    dt_s: f64,
    h_m: f64,
    max_abs_u_mps: f64,
    max_abs_v_mps: f64,
) -> Mixing {
    match donor_cell {
        DonorCell::Fixed(gamma) => Mixing::Global(gamma),
        DonorCell::Global { factor } => {
            Mixing::Global((factor * max_abs_u_mps.max(max_abs_v_mps) * dt_s / h_m).clamp(0.0, 1.0))
        }
        DonorCell::Local { factor } => Mixing::Local { factor_dt_per_h: factor * dt_s / h_m },
    }
}

/// Largest absolute value in `values`.
pub fn max_abs(values: &[f64]) -> f64 {
    values.iter().fold(0.0, |m, x| m.max(x.abs()))
}
