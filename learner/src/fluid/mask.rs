//! Obstacle masks: which cells of the n x n simulation grid are blocked (real obstacles cutting the plane
//! and virtual obstacles alike), and the repair that makes a mask obey the solver's rule.
//!
//! The convention is shared with the virtual obstacles: row-major `Vec<bool>`, cell `(i, j)` at
//! `j * n + i`, `i` along the plane's first in-plane axis, `j` along the second, `true` = blocked; cell
//! `(i, j)` covers `[i h, (i + 1) h) x [j h, (j + 1) h)` from the grid's corner. Outside the grid counts as
//! blocked (the walls).

use super::error::FluidError;

/// Which cells of an n x n grid are blocked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObstacleMask {
    /// Cells per side.
    pub n: usize,
    /// `n * n` flags, `true` = blocked, cell `(i, j)` at `j * n + i`.
    pub blocked: Vec<bool>,
}

/// What [`ObstacleMask::repaired`] did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Repair {
    /// The repaired mask: every cell blocked before is still blocked.
    pub mask: ObstacleMask,
    /// Cells that were free and are now blocked.
    pub added_cells: usize,
}

impl ObstacleMask {
    /// An all-free mask.
    pub fn free(n: usize) -> Self {
        Self { n, blocked: vec![false; n * n] }
    }

    /// A mask from `n * n` flags; refuses a wrong length.
    pub fn new(n: usize, blocked: Vec<bool>) -> Result<Self, FluidError> {
        if blocked.len() != n * n {
            return Err(FluidError::invalid(
                "mask",
                format!("{} cells given for a {n} x {n} grid ({} expected)", blocked.len(), n * n),
            ));
        }
        Ok(Self { n, blocked })
    }

    /// Whether cell `(i, j)` is blocked; cells outside the grid are not.
    pub fn get(&self, i: usize, j: usize) -> bool {
        i < self.n && j < self.n && self.blocked[j * self.n + i]
    }

    /// Whether cell `(i, j)` is blocked; cells outside the grid are blocked (the walls).
    pub fn blocked_or_outside(&self, i: isize, j: isize) -> bool {
        let n = self.n as isize;
        if i < 0 || j < 0 || i >= n || j >= n {
            return true;
        }
        self.blocked[j as usize * self.n + i as usize]
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

    /// Cells blocked in either mask; refuses masks of different sizes.
    pub fn union(&self, other: &ObstacleMask) -> Result<ObstacleMask, FluidError> {
        if other.n != self.n || other.blocked.len() != self.blocked.len() {
            return Err(FluidError::invalid(
                "mask",
                format!("cannot join a {0} x {0} mask with a {1} x {1} one", self.n, other.n),
            ));
        }
        let blocked = self.blocked.iter().zip(&other.blocked).map(|(a, b)| *a || *b).collect();
        Ok(ObstacleMask { n: self.n, blocked })
    }

    /// Blocked cells that break the solver's rule (Griebel et al., section 3.4): an obstacle cell may not
    /// have fluid on two opposite sides (west and east, or south and north). Such a cell would need two
    /// different values for one boundary velocity. Sorted by `(j, i)`.
    pub fn violations(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for j in 0..self.n {
            for i in 0..self.n {
                if self.blocked[j * self.n + i] && self.violates(i as isize, j as isize) {
                    out.push((i, j));
                }
            }
        }
        out
    }

    fn violates(&self, i: isize, j: isize) -> bool {
        let b = |i, j| self.blocked_or_outside(i, j);
        (!b(i - 1, j) && !b(i + 1, j)) || (!b(i, j - 1) && !b(i, j + 1))
    }

    /// The mask made to obey the rule of [`ObstacleMask::violations`] by growing obstacles, never by
    /// removing one (a blocked cell may be a virtual obstacle, where the arm would collide): a blocked
    /// cell with fluid west and east gets its east neighbour blocked, one with fluid south and north its
    /// north neighbour, sweep after sweep until no cell breaks the rule. One-cell walls become two cells
    /// thick and a lone cell a 2 x 2 block. It ends: every sweep that changes anything blocks a cell.
    pub fn repaired(&self) -> Repair {
        let mut mask = self.clone();
        let mut added = 0;
        loop {
            let mut changed = false;
            for j in 0..self.n {
                for i in 0..self.n {
                    if !mask.blocked[j * self.n + i] {
                        continue;
                    }
                    let (ii, jj) = (i as isize, j as isize);
                    if !mask.blocked_or_outside(ii - 1, jj) && !mask.blocked_or_outside(ii + 1, jj) {
                        mask.set(i + 1, j, true);
                        added += 1;
                        changed = true;
                    }
                    if !mask.blocked_or_outside(ii, jj - 1) && !mask.blocked_or_outside(ii, jj + 1) {
                        mask.set(i, j + 1, true);
                        added += 1;
                        changed = true;
                    }
                }
            }
            if !changed {
                return Repair { mask, added_cells: added };
            }
        }
    }
}
