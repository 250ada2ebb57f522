//! The flag field (Griebel et al., section 3.4): which cells hold fluid, which obstacle cells border
//! fluid and on which sides, which faces carry a computed velocity, and the connected fluid regions.

use std::collections::VecDeque;

use super::error::FluidError;
use super::grid::StaggeredGrid;
use super::mask::ObstacleMask;

/// An obstacle cell's fluid neighbour to the north.
pub const NORTH: u8 = 1;
/// An obstacle cell's fluid neighbour to the south.
pub const SOUTH: u8 = 2;
/// An obstacle cell's fluid neighbour to the east.
pub const EAST: u8 = 4;
/// An obstacle cell's fluid neighbour to the west.
pub const WEST: u8 = 8;

/// The flag field of one grid and mask.
#[derive(Clone, Debug)]
pub struct Flags {
    /// The grid the flags belong to.
    pub grid: StaggeredGrid,
    /// Per cell (ghosts included, always obstacle): whether it holds fluid.
    pub fluid: Vec<bool>,
    /// Per cell: 1 for fluid, 0 otherwise.
    pub fluid_weight: Vec<f64>,
    /// Interior obstacle cells next to fluid: array index and the sides (`NORTH | EAST`, ...) where the
    /// fluid is. Never two opposite sides.
    pub boundary: Vec<(usize, u8)>,
    /// Per `u` face: whether both neighbouring cells hold fluid (its velocity is computed).
    pub u_fluid: Vec<bool>,
    /// Per `v` face: whether both neighbouring cells hold fluid.
    pub v_fluid: Vec<bool>,
    /// Interior `u` faces (`i` in `1..n`, `j` in `1..=n`) not between two fluid cells.
    pub u_solid: Vec<usize>,
    /// Interior `v` faces (`i` in `1..=n`, `j` in `1..n`) not between two fluid cells.
    pub v_solid: Vec<usize>,
    /// Per cell: the connected fluid region (4-neighbourhood) it belongs to, `u32::MAX` for obstacles.
    pub region: Vec<u32>,
    /// Number of fluid regions.
    pub regions: usize,
    /// Number of fluid cells.
    pub fluid_cells: usize,
}

impl Flags {
    /// Flags for `mask` on a grid of cell side `h_m`. Refuses a mask that breaks the rule of
    /// [`ObstacleMask::violations`] (repair it with [`ObstacleMask::repaired`]) or has no fluid cell.
    pub fn new(mask: &ObstacleMask, h_m: f64) -> Result<Self, FluidError> {
        let n = mask.n;
        if n < 2 || mask.blocked.len() != n * n {
            return Err(FluidError::invalid("mask", format!("needs n >= 2 and n * n cells, got n = {n}")));
        }
        if !(h_m.is_finite() && h_m > 0.0) {
            return Err(FluidError::invalid("cell size", format!("must be positive, got {h_m} m")));
        }
        let bad = mask.violations();
        if let Some(&(i, j)) = bad.first() {
            return Err(FluidError::invalid(
                "mask",
                format!(
                    "{} obstacle cells have fluid on two opposite sides, first ({i}, {j}); repair the mask \
                     first (ObstacleMask::repaired)",
                    bad.len()
                ),
            ));
        }
        let grid = StaggeredGrid { n, h_m };
        let mut fluid = vec![false; grid.len()];
        for j in 1..=n {
            for i in 1..=n {
                fluid[grid.idx(i, j)] = !mask.blocked[(j - 1) * n + (i - 1)];
            }
        }
        let fluid_cells = fluid.iter().filter(|f| **f).count();
        if fluid_cells == 0 {
            return Err(FluidError::invalid("mask", "every cell is blocked"));
        }
        let s = grid.stride();
        let mut boundary = Vec::new();
        for j in 1..=n {
            for i in 1..=n {
                let k = grid.idx(i, j);
                if fluid[k] {
                    continue;
                }
                let mut sides = 0;
                for (nb, bit) in [(k + s, NORTH), (k - s, SOUTH), (k + 1, EAST), (k - 1, WEST)] {
                    if fluid[nb] {
                        sides |= bit;
                    }
                }
                if sides != 0 {
                    boundary.push((k, sides));
                }
            }
        }
        let mut u_fluid = vec![false; grid.len()];
        let mut v_fluid = vec![false; grid.len()];
        let (mut u_solid, mut v_solid) = (Vec::new(), Vec::new());
        for j in 1..=n {
            for i in 1..=n {
                let k = grid.idx(i, j);
                u_fluid[k] = i < n && fluid[k] && fluid[k + 1];
                v_fluid[k] = j < n && fluid[k] && fluid[k + s];
                if i < n && !u_fluid[k] {
                    u_solid.push(k);
                }
                if j < n && !v_fluid[k] {
                    v_solid.push(k);
                }
            }
        }
        let (region, regions) = label_regions(&grid, &fluid);
        let fluid_weight = fluid.iter().map(|&f| if f { 1.0 } else { 0.0 }).collect();
        Ok(Self {
            grid,
            fluid,
            fluid_weight,
            boundary,
            u_fluid,
            v_fluid,
            u_solid,
            v_solid,
            region,
            regions,
            fluid_cells,
        })
    }
}

/// Labels the connected fluid regions (4-neighbourhood) in array order.
fn label_regions(grid: &StaggeredGrid, fluid: &[bool]) -> (Vec<u32>, usize) {
    let s = grid.stride();
    let mut region = vec![u32::MAX; grid.len()];
    let mut count = 0u32;
    let mut queue = VecDeque::new();
    for start in 0..grid.len() {
        if !fluid[start] || region[start] != u32::MAX {
            continue;
        }
        region[start] = count;
        queue.push_back(start);
        while let Some(k) = queue.pop_front() {
            for nb in [k + 1, k - 1, k + s, k - s] {
                if fluid[nb] && region[nb] == u32::MAX {
                    region[nb] = count;
                    queue.push_back(nb);
                }
            }
        }
        count += 1;
    }
    (region, count as usize)
}
