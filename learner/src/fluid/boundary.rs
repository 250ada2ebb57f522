//! Boundary conditions (Griebel et al., sections 3.1.2 and 3.4): no-slip walls that may slide along
//! themselves (the lid of the cavity), no-slip obstacle cells, and the velocities preset by stirring.

use super::flags::{EAST, Flags, NORTH, SOUTH, WEST};
use super::grid::StaggeredGrid;

/// The four walls of the grid: no fluid through them, and the fluid at a wall moves with it. Each wall
/// may slide along itself at the given speed (the lid-driven cavity's top wall moves at 1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Walls {
    /// Velocity of the top wall (`y = n h`) along x, m/s.
    pub top_u_mps: f64,
    /// Velocity of the bottom wall (`y = 0`) along x, m/s.
    pub bottom_u_mps: f64,
    /// Velocity of the left wall (`x = 0`) along y, m/s.
    pub left_v_mps: f64,
    /// Velocity of the right wall (`x = n h`) along y, m/s.
    pub right_v_mps: f64,
}

/// Which velocity component a preset sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Component {
    /// `u`, on an east face.
    U,
    /// `v`, on a north face.
    V,
}

/// A velocity imposed on one fluid face for one time level (stirring).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacePreset {
    /// The component.
    pub component: Component,
    /// Array index of the face (see [`StaggeredGrid::idx`]).
    pub index: usize,
    /// The velocity, m/s.
    pub velocity_mps: f64,
}

/// Sets the ghost and wall values of `u` and `v` for `walls`: zero normal velocity on the walls, the
/// ghost tangential velocity mirrored so that the mean at the wall is the wall's velocity.
pub fn apply_walls(grid: &StaggeredGrid, walls: &Walls, u: &mut [f64], v: &mut [f64]) {
    let n = grid.n;
    for j in 1..=n {
        u[grid.idx(0, j)] = 0.0;
        u[grid.idx(n, j)] = 0.0;
        v[grid.idx(0, j)] = 2.0 * walls.left_v_mps - v[grid.idx(1, j)];
        v[grid.idx(n + 1, j)] = 2.0 * walls.right_v_mps - v[grid.idx(n, j)];
    }
    for i in 1..=n {
        v[grid.idx(i, 0)] = 0.0;
        v[grid.idx(i, n)] = 0.0;
        u[grid.idx(i, 0)] = 2.0 * walls.bottom_u_mps - u[grid.idx(i, 1)];
        u[grid.idx(i, n + 1)] = 2.0 * walls.top_u_mps - u[grid.idx(i, n)];
    }
}

/// Sets the velocities on and inside the boundary of obstacle cells (no-slip): zero on faces between
/// fluid and obstacle, tangential values mirrored so that they average to zero on the obstacle's surface.
pub fn apply_obstacles(flags: &Flags, u: &mut [f64], v: &mut [f64]) {
    let s = flags.grid.stride();
    for &(k, sides) in &flags.boundary {
        // k is cell (i, j): u[k] its east face, u[k - 1] its west face, v[k] north, v[k - s] south.
        match sides {
            NORTH => {
                v[k] = 0.0;
                u[k] = -u[k + s];
                u[k - 1] = -u[k - 1 + s];
            }
            SOUTH => {
                v[k - s] = 0.0;
                u[k] = -u[k - s];
                u[k - 1] = -u[k - 1 - s];
            }
            EAST => {
                u[k] = 0.0;
                v[k] = -v[k + 1];
                v[k - s] = -v[k - s + 1];
            }
            WEST => {
                u[k - 1] = 0.0;
                v[k] = -v[k - 1];
                v[k - s] = -v[k - s - 1];
            }
            s_ if s_ == NORTH | EAST => {
                u[k] = 0.0;
                v[k] = 0.0;
                u[k - 1] = -u[k - 1 + s];
                v[k - s] = -v[k - s + 1];
            }
            s_ if s_ == SOUTH | EAST => {
                u[k] = 0.0;
                v[k - s] = 0.0;
                u[k - 1] = -u[k - 1 - s];
                v[k] = -v[k + 1];
            }
            s_ if s_ == SOUTH | WEST => {
                u[k - 1] = 0.0;
                v[k - s] = 0.0;
                u[k] = -u[k - s];
                v[k] = -v[k - 1];
            }
            s_ if s_ == NORTH | WEST => {
                u[k - 1] = 0.0;
                v[k] = 0.0;
                u[k] = -u[k + s];
                v[k - s] = -v[k - s - 1];
            }
            // Opposite sides are refused when the flags are built.
            _ => {}
        }
    }
}

/// Writes the preset velocities into `u` and `v`.
pub fn apply_presets(presets: &[FacePreset], u: &mut [f64], v: &mut [f64]) {
    for preset in presets {
        match preset.component {
            Component::U => u[preset.index] = preset.velocity_mps,
            Component::V => v[preset.index] = preset.velocity_mps,
        }
    }
}
