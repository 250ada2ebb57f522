//! The obstacle mask shared with the fluid solver: an n x n grid of cells over a square in a plane.

/// Which cells of an n x n grid are blocked. Row-major: cell `(i, j)` is at `j * n + i`, `i` along the
/// plane's first in-plane axis, `j` along its second; `true` = blocked. Cell `(i, j)` covers
/// `[origin + i h, origin + (i + 1) h)` along the first axis and likewise along the second, `h` the cell
/// size. The convention the fluid solver uses for its obstacles.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObstacleMask {
    /// Cells per side.
    pub n: usize,
    /// `n * n` flags, `true` = blocked.
    pub blocked: Vec<bool>,
}

impl ObstacleMask {
    /// An all-free mask.
    pub fn free(n: usize) -> Self {
        Self { n, blocked: vec![false; n * n] }
    }

    /// Whether cell `(i, j)` is blocked; cells outside the grid are not.
    pub fn get(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && self.blocked[j * self.n + i]
    }

    /// Blocks or frees cell `(i, j)` (ignored outside the grid).
    pub fn set(&mut self, i: usize, j: usize, blocked: bool) {
        if i < self.n && j < self.n {
            self.blocked[j * self.n + i] = blocked;
        }
    }

    /// Number of blocked cells.
    pub fn count_blocked(&self) -> usize {
        self.blocked.iter().filter(|b| **b).count()
    }

    /// Cells blocked here and free in `other`, or the other way round (both must be the same size).
    pub fn count_differences(&self, other: &ObstacleMask) -> usize {
        self.blocked.iter().zip(&other.blocked).filter(|(a, b)| a != b).count()
    }
}
