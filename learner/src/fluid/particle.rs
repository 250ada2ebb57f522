//! Particle tracing: a particle carried by the stream, classical Runge-Kutta (4th order) in time on the
//! velocity bilinearly interpolated on the staggered grid and linearly between the two time levels of a
//! step. The particle never enters an obstacle cell, by construction rather than by hope: every step of it
//! is a straight segment checked cell by cell against the obstacles and the walls; a step that would
//! cross one is split in halves and retried, and where even a tiny step would, the particle holds still
//! for it (counted).

use nalgebra::Vector2;

use super::flags::Flags;
use super::raster::cells_on_segment;

/// Largest particle step, in cell sides.
const MAX_STEP_CELLS: f64 = 0.25;
/// How many times a step is halved before the particle holds still for it.
const MAX_HALVINGS: u32 = 10;

/// One step of the flow, for tracing: the velocities at its start and its end.
#[derive(Clone, Copy, Debug)]
pub struct FlowInterval<'a> {
    /// `u` and `v` at the start, m/s.
    pub start: (&'a [f64], &'a [f64]),
    /// `u` and `v` at the end, m/s.
    pub end: (&'a [f64], &'a [f64]),
    /// Time at the start, s.
    pub t0_s: f64,
    /// Time at the end, s.
    pub t1_s: f64,
    /// Largest speed anywhere in either field, m/s (sets the number of substeps).
    pub max_speed_mps: f64,
}

/// A traced particle.
#[derive(Clone, Debug)]
pub struct Particle {
    position_m: Vector2<f64>,
    /// Its positions so far with their times: `(t_s, position in grid coordinates, m)`.
    pub trace: Vec<(f64, Vector2<f64>)>,
    /// Steps that had to be split because they would have crossed an obstacle or wall.
    pub splits: usize,
    /// Steps for which the particle held still because even the smallest split would have crossed one.
    pub holds: usize,
}

impl Particle {
    /// A particle at `position_m` (grid coordinates) at time `t_s`.
    pub fn new(position_m: Vector2<f64>, t_s: f64) -> Self {
        Self { position_m, trace: vec![(t_s, position_m)], splits: 0, holds: 0 }
    }

    /// Where it is, grid coordinates, m.
    pub fn position_m(&self) -> Vector2<f64> {
        self.position_m
    }

    /// Carries the particle through one step of the flow, recording every substep.
    pub fn advance(&mut self, flags: &Flags, flow: &FlowInterval<'_>) {
        let h = flags.grid.h_m;
        let dt = flow.t1_s - flow.t0_s;
        if dt.is_nan() || dt <= 0.0 {
            return;
        }
        let substeps = ((flow.max_speed_mps * dt / (MAX_STEP_CELLS * h)).ceil() as usize).clamp(1, 10_000);
        for k in 0..substeps {
            let ta = flow.t0_s + dt * k as f64 / substeps as f64;
            let tb = flow.t0_s + dt * (k + 1) as f64 / substeps as f64;
            self.substep(flags, flow, ta, tb, 0);
        }
    }

    fn substep(&mut self, flags: &Flags, flow: &FlowInterval<'_>, ta: f64, tb: f64, depth: u32) {
        let next = rk4(flags, flow, self.position_m, ta, tb);
        if segment_free(flags, self.position_m, next) {
            self.position_m = next;
            self.trace.push((tb, next));
        } else if depth < MAX_HALVINGS {
            self.splits += usize::from(depth == 0);
            let mid = 0.5 * (ta + tb);
            self.substep(flags, flow, ta, mid, depth + 1);
            self.substep(flags, flow, mid, tb, depth + 1);
        } else {
            self.holds += 1;
            self.trace.push((tb, self.position_m));
        }
    }
}

/// The velocity at `p` and time `t`: bilinear in space, linear between the step's two fields.
pub fn velocity_at(flags: &Flags, flow: &FlowInterval<'_>, p: Vector2<f64>, t: f64) -> Vector2<f64> {
    let grid = flags.grid;
    let span = flow.t1_s - flow.t0_s;
    let w = if span > 0.0 { ((t - flow.t0_s) / span).clamp(0.0, 1.0) } else { 1.0 };
    let a = grid.velocity(flow.start.0, flow.start.1, p);
    let b = grid.velocity(flow.end.0, flow.end.1, p);
    a * (1.0 - w) + b * w
}

/// One classical Runge-Kutta step from `p` over `[ta, tb]`.
fn rk4(flags: &Flags, flow: &FlowInterval<'_>, p: Vector2<f64>, ta: f64, tb: f64) -> Vector2<f64> {
    let dt = tb - ta;
    let tm = 0.5 * (ta + tb);
    let k1 = velocity_at(flags, flow, p, ta);
    let k2 = velocity_at(flags, flow, p + k1 * (0.5 * dt), tm);
    let k3 = velocity_at(flags, flow, p + k2 * (0.5 * dt), tm);
    let k4 = velocity_at(flags, flow, p + k3 * dt, tb);
    p + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (dt / 6.0)
}

/// Whether the segment from `a` to `b` stays in fluid cells inside the grid.
pub fn segment_free(flags: &Flags, a: Vector2<f64>, b: Vector2<f64>) -> bool {
    let grid = flags.grid;
    let n = grid.n as isize;
    cells_on_segment(a, b, grid.h_m, |i, j| {
        i >= 0 && j >= 0 && i < n && j < n && flags.fluid[grid.idx(i as usize + 1, j as usize + 1)]
    })
}
