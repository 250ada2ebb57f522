//! The staggered grid (Griebel et al., section 3.1.1): n x n square cells of side h with a ring of ghost
//! cells, pressure at cell centres, `u` on the east faces, `v` on the north faces, and the bilinear
//! interpolation of the velocities at any point.
//!
//! Arrays are `(n + 2) x (n + 2)`, index `j * (n + 2) + i`; interior cell `(i, j)`, `i, j` in `1..=n`,
//! covers `[(i - 1) h, i h) x [(j - 1) h, j h)` in grid coordinates (metres from the grid's corner), so it
//! is cell `(i - 1, j - 1)` of an [`ObstacleMask`](super::ObstacleMask). `u[i, j]` sits at
//! `(i h, (j - 1/2) h)`, `v[i, j]` at `((i - 1/2) h, j h)`, `p[i, j]` at `((i - 1/2) h, (j - 1/2) h)`.

use nalgebra::Vector2;

/// Size of a staggered grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaggeredGrid {
    /// Interior cells per side.
    pub n: usize,
    /// Cell side, m.
    pub h_m: f64,
}

impl StaggeredGrid {
    /// Cells per row of the arrays, ghosts included (`n + 2`).
    pub fn stride(&self) -> usize {
        self.n + 2
    }

    /// Length of every field array, ghosts included.
    pub fn len(&self) -> usize {
        self.stride() * self.stride()
    }

    /// Whether the grid has no interior cell.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// Array index of `(i, j)`, ghosts included.
    pub fn idx(&self, i: usize, j: usize) -> usize {
        j * self.stride() + i
    }

    /// Side of the grid, m.
    pub fn size_m(&self) -> f64 {
        self.n as f64 * self.h_m
    }

    /// The `u` velocity at `p` (grid coordinates, m), bilinear between the four nearest `u` values; ghost
    /// values carry the wall conditions, so the result is zero on a no-slip wall.
    pub fn interpolate_u(&self, u: &[f64], p: Vector2<f64>) -> f64 {
        self.bilinear(u, p.x / self.h_m, p.y / self.h_m + 0.5, self.n - 1, self.n)
    }

    /// The `v` velocity at `p` (grid coordinates, m), as [`StaggeredGrid::interpolate_u`].
    pub fn interpolate_v(&self, v: &[f64], p: Vector2<f64>) -> f64 {
        self.bilinear(v, p.x / self.h_m + 0.5, p.y / self.h_m, self.n, self.n - 1)
    }

    /// The velocity `(u, v)` at `p`, m/s.
    pub fn velocity(&self, u: &[f64], v: &[f64], p: Vector2<f64>) -> Vector2<f64> {
        Vector2::new(self.interpolate_u(u, p), self.interpolate_v(v, p))
    }

    /// Bilinear interpolation of `field` at fractional node coordinates `(fx, fy)` (node `(i, j)` at
    /// `(i, j)`), the lower node clamped to `0..=max_i` and `0..=max_j`.
    fn bilinear(&self, field: &[f64], fx: f64, fy: f64, max_i: usize, max_j: usize) -> f64 {
        let i0 = clamp_floor(fx, max_i);
        let j0 = clamp_floor(fy, max_j);
        let a = (fx - i0 as f64).clamp(0.0, 1.0);
        let b = (fy - j0 as f64).clamp(0.0, 1.0);
        let k = self.idx(i0, j0);
        let s = self.stride();
        (1.0 - b) * ((1.0 - a) * field[k] + a * field[k + 1])
            + b * ((1.0 - a) * field[k + s] + a * field[k + s + 1])
    }
}

/// `floor(x)` clamped to `0..=max` (NaN gives 0).
fn clamp_floor(x: f64, max: usize) -> usize {
    if x.is_nan() || x < 0.0 { 0 } else { (x.floor() as usize).min(max) }
}
