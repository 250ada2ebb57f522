//! The lid-driven cavity (the solver's validation, after Ghia, Ghia and Shin 1982): the unit square, the
//! lid at `y = 1` sliding at `u = 1`, viscosity `1 / Re`, run from rest to a steady state, and the
//! velocity profiles along the two centrelines.

use nalgebra::Vector2;

use super::boundary::Walls;
use super::error::FluidError;
use super::mask::ObstacleMask;
use super::params::{DonorCell, FluidParams, PressureSolverKind};
use super::simulation::{FluidSim, StepReport};

/// The `y` stations of Ghia et al.'s table I (`u` along `x = 0.5`).
pub const GHIA_U_Y: [f64; 17] = [
    1.0, 0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5, 0.4531, 0.2813, 0.1719, 0.1016, 0.0703,
    0.0625, 0.0547, 0.0,
];

/// The `x` stations of Ghia et al.'s table II (`v` along `y = 0.5`).
pub const GHIA_V_X: [f64; 17] = [
    1.0, 0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5, 0.2344, 0.2266, 0.1563, 0.0938, 0.0781,
    0.0703, 0.0625, 0.0,
];

/// Largest Reynolds number the cavity runs at: the largest of Ghia et al.'s table. The flow in the
/// square cavity stops being steady not far beyond it, and a run to a steady state means nothing there.
pub const MAX_REYNOLDS: f64 = 10_000.0;

/// How to run the cavity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CavityConfig {
    /// Reynolds number (lid speed 1, side 1, viscosity 1 / Re).
    pub reynolds: f64,
    /// Cells per side.
    pub n: usize,
    /// The pressure solver.
    pub solver: PressureSolverKind,
    /// The donor-cell parameter.
    pub donor_cell: DonorCell,
    /// Safety factor on the stable time step.
    pub tau: f64,
    /// Divergence tolerance of every pressure solve, 1/s (dimensionless time units here).
    pub divergence_tol: f64,
    /// The run is steady when no velocity changes faster than this (per unit time).
    pub steady_tol: f64,
    /// Give up after this much simulated time.
    pub max_time: f64,
    /// Start from the steady state of a grid this many times coarser (1: from rest), interpolated; each
    /// coarser level is itself started the same way down to a grid of 16 cells or more.
    pub coarsening: usize,
}

impl CavityConfig {
    /// Defaults for `Re` and `n`: the direct pressure solve, per-flux donor-cell mixing (factor 1; one
    /// gamma for the grid, by the book's rule 0.96 at tau 0.8, missed Ghia's Re 1000 profiles by 0.072 at
    /// n = 128, this 0.020), tau 0.8, divergence below 1e-8, steady when every velocity changes by less
    /// than 1e-4 per unit time, at most 300 time units, started from a grid half as fine.
    pub fn new(reynolds: f64, n: usize) -> Self {
        Self {
            reynolds,
            n,
            solver: PressureSolverKind::Direct,
            donor_cell: DonorCell::Local { factor: 1.0 },
            tau: 0.8,
            divergence_tol: 1e-8,
            steady_tol: 1e-4,
            max_time: 300.0,
            coarsening: 2,
        }
    }

    fn params(&self) -> FluidParams {
        FluidParams {
            viscosity_m2ps: 1.0 / self.reynolds,
            donor_cell: self.donor_cell,
            tau: self.tau,
            divergence_tol_per_s: self.divergence_tol,
            solver: self.solver,
            max_sor_iterations: 200_000,
        }
    }

    fn validate(&self) -> Result<(), FluidError> {
        if !(self.reynolds > 0.0 && self.reynolds <= MAX_REYNOLDS) {
            return Err(FluidError::invalid(
                "re",
                format!("must be above 0 and at most {MAX_REYNOLDS}, got {}", self.reynolds),
            ));
        }
        if !(4..=1024).contains(&self.n) {
            return Err(FluidError::invalid("n", format!("must be in 4..=1024, got {}", self.n)));
        }
        for (name, x) in [("steady_tol", self.steady_tol), ("max_time", self.max_time)] {
            if !(x.is_finite() && x > 0.0) {
                return Err(FluidError::invalid(name, format!("must be positive, got {x}")));
            }
        }
        if self.coarsening == 0 {
            return Err(FluidError::invalid("coarsening", "must be at least 1"));
        }
        self.params().validate()
    }
}

/// A finished cavity run.
#[derive(Debug)]
pub struct CavityRun {
    /// The simulation at its last step.
    pub sim: FluidSim,
    /// Steps on the finest grid.
    pub steps: usize,
    /// Steps on the coarser grids that started it.
    pub coarse_steps: usize,
    /// Whether the steady-state criterion was met before `max_time`.
    pub steady: bool,
    /// Largest divergence left after any step on the finest grid, 1/s.
    pub max_divergence: f64,
    /// Largest velocity change per unit time at the last step.
    pub final_acceleration: f64,
}

impl CavityRun {
    /// `u` along the vertical centreline `x = 0.5` at height `y`.
    pub fn u_centreline(&self, y: f64) -> f64 {
        self.sim.velocity_at(Vector2::new(0.5, y)).x
    }

    /// `v` along the horizontal centreline `y = 0.5` at `x`.
    pub fn v_centreline(&self, x: f64) -> f64 {
        self.sim.velocity_at(Vector2::new(x, 0.5)).y
    }
}

/// Runs the cavity from rest (or from a coarser steady state) until steady; `on_step` sees every step of
/// the finest grid. Not reaching the steady state is no error: see [`CavityRun::steady`].
pub fn run_cavity(
    config: &CavityConfig,
    mut on_step: impl FnMut(&StepReport),
) -> Result<CavityRun, FluidError> {
    run(config, &mut on_step)
}

fn run(config: &CavityConfig, on_step: &mut dyn FnMut(&StepReport)) -> Result<CavityRun, FluidError> {
    config.validate()?;
    let coarse_n = config.n / config.coarsening.max(1);
    let (start, coarse_steps) =
        if config.coarsening > 1 && coarse_n >= 16 && coarse_n * config.coarsening == config.n {
            let coarse = run(&CavityConfig { n: coarse_n, ..*config }, &mut |_| {})?;
            (Some(coarse.sim), coarse.steps + coarse.coarse_steps)
        } else {
            (None, 0)
        };
    let walls = Walls { top_u_mps: 1.0, ..Walls::default() };
    let h = 1.0 / config.n as f64;
    let mut sim = FluidSim::new(&ObstacleMask::free(config.n), h, walls, config.params())?;
    if let Some(coarse) = start {
        let (u, v) = prolong(&coarse, &sim);
        sim.set_velocities(u, v)?;
    }
    let mut steps = 0;
    let mut max_divergence = 0.0f64;
    let mut final_acceleration = f64::INFINITY;
    while sim.time_s() < config.max_time {
        let report = sim.step(sim.stable_dt())?;
        steps += 1;
        max_divergence = max_divergence.max(report.max_divergence_per_s);
        final_acceleration = report.max_acceleration_mps2;
        on_step(&report);
        if final_acceleration < config.steady_tol {
            return Ok(CavityRun {
                sim,
                steps,
                coarse_steps,
                steady: true,
                max_divergence,
                final_acceleration,
            });
        }
    }
    Ok(CavityRun { sim, steps, coarse_steps, steady: false, max_divergence, final_acceleration })
}

/// The coarse run's velocities interpolated onto the fine grid's faces.
fn prolong(coarse: &FluidSim, fine: &FluidSim) -> (Vec<f64>, Vec<f64>) {
    let grid = fine.grid();
    let h = grid.h_m;
    let mut u = vec![0.0; grid.len()];
    let mut v = vec![0.0; grid.len()];
    for j in 1..=grid.n {
        for i in 1..=grid.n {
            let k = grid.idx(i, j);
            let (x, y) = (i as f64 * h, (j as f64 - 0.5) * h);
            u[k] = coarse.velocity_at(Vector2::new(x, y)).x;
            let (x, y) = ((i as f64 - 0.5) * h, j as f64 * h);
            v[k] = coarse.velocity_at(Vector2::new(x, y)).y;
        }
    }
    (u, v)
}
