//! One fluid simulation: the flow on a staggered grid with walls, obstacles and preset velocities,
//! advanced one adaptive time step at a time (Griebel et al., algorithm 1: F and G, the pressure
//! equation, the velocity correction, the boundary values).

use nalgebra::Vector2;

use super::boundary::{Component, FacePreset, Walls, apply_obstacles, apply_presets, apply_walls};
use super::error::FluidError;
use super::flags::Flags;
use super::grid::StaggeredGrid;
use super::mask::ObstacleMask;
use super::momentum::{Mixing, compute_fg, compute_rhs, correct_velocities, max_change, max_divergence};
use super::params::FluidParams;
use super::pressure::PressureSolver;
use super::timestep::{donor_cell_mixing, max_abs, stable_dt};

/// What one time step did.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepReport {
    /// The step, s.
    pub dt_s: f64,
    /// Simulated time after the step, s.
    pub t_s: f64,
    /// The donor-cell parameter used (with per-flux mixing, the largest).
    pub gamma: f64,
    /// Pressure solver iterations.
    pub pressure_iterations: usize,
    /// Largest divergence of the corrected velocities over the fluid cells, 1/s, computed from the
    /// velocities themselves (before stirring presets overwrite any face).
    pub max_divergence_per_s: f64,
    /// Largest change of a velocity on an interior face over the step divided by the step, m/s^2 (zero at
    /// a steady state; a stirred face counts with its preset before the step and its corrected value
    /// after, before the new presets).
    pub max_acceleration_mps2: f64,
}

/// A running fluid simulation.
#[derive(Debug)]
pub struct FluidSim {
    flags: Flags,
    params: FluidParams,
    walls: Walls,
    solver: PressureSolver,
    /// `u` on the east faces, m/s (see [`StaggeredGrid`] for the layout).
    u: Vec<f64>,
    /// `v` on the north faces, m/s.
    v: Vec<f64>,
    /// Pressure (divided by density) at the cell centres, m^2/s^2.
    p: Vec<f64>,
    /// `u` and `v` before the last step.
    u_prev: Vec<f64>,
    v_prev: Vec<f64>,
    f: Vec<f64>,
    g: Vec<f64>,
    rhs: Vec<f64>,
    presets: Vec<FacePreset>,
    /// Largest `|u|` and `|v|`, updated with every change of the velocities.
    speeds: (f64, f64),
    t_s: f64,
    steps: usize,
}

impl FluidSim {
    /// A fluid at rest on an `n x n` grid of cells of side `h_m` (`n = mask.n`), with `mask`'s obstacles
    /// (which must obey [`ObstacleMask::violations`]'s rule), `walls` and `params`.
    pub fn new(mask: &ObstacleMask, h_m: f64, walls: Walls, params: FluidParams) -> Result<Self, FluidError> {
        params.validate()?;
        let flags = Flags::new(mask, h_m)?;
        let solver = PressureSolver::new(params.solver, &flags)?;
        let len = flags.grid.len();
        let mut sim = Self {
            flags,
            params,
            walls,
            solver,
            u: vec![0.0; len],
            v: vec![0.0; len],
            p: vec![0.0; len],
            u_prev: vec![0.0; len],
            v_prev: vec![0.0; len],
            f: vec![0.0; len],
            g: vec![0.0; len],
            rhs: vec![0.0; len],
            presets: Vec::new(),
            speeds: (0.0, 0.0),
            t_s: 0.0,
            steps: 0,
        };
        sim.apply_boundary();
        sim.u_prev.copy_from_slice(&sim.u);
        sim.v_prev.copy_from_slice(&sim.v);
        Ok(sim)
    }

    /// The grid.
    pub fn grid(&self) -> StaggeredGrid {
        self.flags.grid
    }

    /// The flag field.
    pub fn flags(&self) -> &Flags {
        &self.flags
    }

    /// The parameters.
    pub fn params(&self) -> &FluidParams {
        &self.params
    }

    /// The pressure solver.
    pub fn solver(&self) -> &PressureSolver {
        &self.solver
    }

    /// `u` on the east faces, m/s, ghosts included.
    pub fn u(&self) -> &[f64] {
        &self.u
    }

    /// `v` on the north faces, m/s, ghosts included.
    pub fn v(&self) -> &[f64] {
        &self.v
    }

    /// `u` before the last step (equal to [`FluidSim::u`] before the first), m/s.
    pub fn previous_u(&self) -> &[f64] {
        &self.u_prev
    }

    /// `v` before the last step, m/s.
    pub fn previous_v(&self) -> &[f64] {
        &self.v_prev
    }

    /// Pressure over density at the cell centres, m^2/s^2, ghosts included.
    pub fn p(&self) -> &[f64] {
        &self.p
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.t_s
    }

    /// Steps taken.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Replaces the velocity field (e.g. a solution from a coarser grid) and reapplies the boundary
    /// values; refuses arrays of the wrong length or non-finite values.
    pub fn set_velocities(&mut self, u: Vec<f64>, v: Vec<f64>) -> Result<(), FluidError> {
        let len = self.flags.grid.len();
        if u.len() != len || v.len() != len {
            return Err(FluidError::invalid("velocities", format!("need {len} values per component")));
        }
        if !u.iter().chain(&v).all(|x| x.is_finite()) {
            return Err(FluidError::invalid("velocities", "not finite"));
        }
        self.u = u;
        self.v = v;
        self.apply_boundary();
        self.u_prev.copy_from_slice(&self.u);
        self.v_prev.copy_from_slice(&self.v);
        Ok(())
    }

    /// Sets the velocities imposed on fluid faces from now on (stirring) and applies them to the current
    /// velocities; they stay until replaced. Refuses presets on faces that are not between two fluid
    /// cells.
    pub fn set_presets(&mut self, presets: Vec<FacePreset>) -> Result<(), FluidError> {
        self.check_presets(&presets)?;
        self.presets = presets;
        self.apply_boundary();
        Ok(())
    }

    fn check_presets(&self, presets: &[FacePreset]) -> Result<(), FluidError> {
        for preset in presets {
            let fluid = match preset.component {
                Component::U => self.flags.u_fluid.get(preset.index),
                Component::V => self.flags.v_fluid.get(preset.index),
            };
            if fluid != Some(&true) || !preset.velocity_mps.is_finite() {
                return Err(FluidError::invalid(
                    "preset",
                    format!(
                        "face {} ({:?}) is not between two fluid cells or its velocity is not finite",
                        preset.index, preset.component
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The velocity at `p` (grid coordinates, m): bilinear on the staggered grid.
    pub fn velocity_at(&self, p: Vector2<f64>) -> Vector2<f64> {
        self.flags.grid.velocity(&self.u, &self.v, p)
    }

    /// Largest `|u|` and `|v|` on the grid's faces (not the ghost values) and of the walls, m/s.
    pub fn max_speeds(&self) -> (f64, f64) {
        self.speeds
    }

    fn measure_speeds(&self) -> (f64, f64) {
        let grid = self.flags.grid;
        let (n, s) = (grid.n, grid.stride());
        let w = &self.walls;
        let mut umax = w.top_u_mps.abs().max(w.bottom_u_mps.abs());
        let mut vmax = w.left_v_mps.abs().max(w.right_v_mps.abs());
        for j in 1..=n {
            umax = umax.max(max_abs(&self.u[j * s..=j * s + n]));
        }
        for j in 0..=n {
            vmax = vmax.max(max_abs(&self.v[j * s + 1..=j * s + n]));
        }
        (umax, vmax)
    }

    /// The stable time step for the current velocities (see [`stable_dt`]), s.
    pub fn stable_dt(&self) -> f64 {
        let (umax, vmax) = self.max_speeds();
        stable_dt(self.params.tau, self.flags.grid.h_m, self.params.viscosity_m2ps, umax, vmax)
    }

    /// Largest divergence over the fluid cells of the current velocities, 1/s.
    pub fn max_divergence(&self) -> f64 {
        max_divergence(&self.flags, &self.u, &self.v)
    }

    /// Advances the flow by `dt_s` (at most [`FluidSim::stable_dt`] for a stable run; larger steps are
    /// taken as asked). Fails when the pressure solve misses its tolerance or the flow turns non-finite.
    pub fn step(&mut self, dt_s: f64) -> Result<StepReport, FluidError> {
        self.advance(dt_s)
    }

    /// Advances the flow by `dt_s` as [`FluidSim::step`], with `presets` imposed on the new velocities
    /// (the stirring at the end of the step) and kept from then on.
    pub fn step_with_presets(
        &mut self,
        dt_s: f64,
        presets: Vec<FacePreset>,
    ) -> Result<StepReport, FluidError> {
        self.check_presets(&presets)?;
        self.presets = presets;
        self.advance(dt_s)
    }

    fn advance(&mut self, dt_s: f64) -> Result<StepReport, FluidError> {
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return Err(FluidError::invalid("dt_s", format!("must be positive, got {dt_s}")));
        }
        let grid = self.flags.grid;
        let (umax, vmax) = self.max_speeds();
        let mixing = donor_cell_mixing(self.params.donor_cell, dt_s, grid.h_m, umax, vmax);
        let gamma = match mixing {
            Mixing::Global(gamma) => gamma,
            Mixing::Local { factor_dt_per_h } => (factor_dt_per_h * umax.max(vmax)).min(1.0),
        };
        let nu = self.params.viscosity_m2ps;
        compute_fg(&self.flags, &self.u, &self.v, nu, mixing, dt_s, &mut self.f, &mut self.g);
        compute_rhs(&self.flags, &self.f, &self.g, dt_s, &mut self.rhs);
        let tol_per_s = self.params.divergence_tol_per_s;
        let solve = self.solver.solve(
            &self.flags,
            &self.rhs,
            &mut self.p,
            tol_per_s / dt_s,
            self.params.max_sor_iterations,
        );
        self.u_prev.copy_from_slice(&self.u);
        self.v_prev.copy_from_slice(&self.v);
        correct_velocities(&self.flags, &self.f, &self.g, &self.p, dt_s, &mut self.u, &mut self.v);
        let max_change = max_change(&self.flags, &self.u_prev, &self.v_prev, &self.u, &self.v);
        // The tolerance is checked on the velocities themselves, whatever the solver reported.
        let max_divergence_per_s = max_divergence(&self.flags, &self.u, &self.v);
        if !max_divergence_per_s.is_finite() {
            return Err(FluidError::Diverged { step: self.steps, t_s: self.t_s });
        }
        if max_divergence_per_s > tol_per_s {
            return Err(FluidError::PressureNotConverged {
                solver: self.solver.kind().name(),
                step: self.steps,
                iterations: solve.iterations,
                divergence_per_s: max_divergence_per_s,
                tolerance_per_s: tol_per_s,
            });
        }
        self.apply_boundary();
        self.t_s += dt_s;
        self.steps += 1;
        Ok(StepReport {
            dt_s,
            t_s: self.t_s,
            gamma,
            pressure_iterations: solve.iterations,
            max_divergence_per_s,
            max_acceleration_mps2: max_change / dt_s,
        })
    }

    /// Presets, walls, then obstacles (whose mirrored values then see the presets).
    fn apply_boundary(&mut self) {
        apply_presets(&self.presets, &mut self.u, &mut self.v);
        apply_walls(&self.flags.grid, &self.walls, &mut self.u, &mut self.v);
        apply_obstacles(&self.flags, &mut self.u, &mut self.v);
        self.speeds = self.measure_speeds();
    }
}
