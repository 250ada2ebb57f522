//! The pressure equation by sparse Cholesky factorization (faer, approximate minimum degree ordering):
//! the matrix depends only on the flag field, so it is factored once per obstacle layout and every step
//! costs one forward and one backward substitution, exact to rounding.
//!
//! The Neumann problem fixes the pressure only up to a constant in each connected fluid region: one cell
//! per region is held at zero (its unknown removed, which leaves the matrix symmetric positive definite),
//! and the mean of the right-hand side over each region is removed first so that the held cell's own
//! equation holds too (the discrete compatibility condition, exact up to rounding).

use std::fmt;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, Triplet};
use faer::{Conj, MatMut, Par, Side};

use super::super::error::FluidError;
use super::super::flags::Flags;
use super::PressureSolve;

/// The factored pressure matrix of one flag field.
pub struct DirectSolver {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Per unknown: its cell's array index.
    cell_of_unknown: Vec<usize>,
    /// Per fluid cell: array index and region.
    fluid_cells: Vec<(usize, usize)>,
    /// The held cells (one per region).
    held_cells: Vec<usize>,
    /// Per region: sum of the right-hand side, then its mean.
    region_mean: Vec<f64>,
    /// Per region: number of fluid cells.
    region_cells: Vec<f64>,
    /// The right-hand side, then the solution.
    x: Vec<f64>,
    scratch: MemBuffer,
}

impl fmt::Debug for DirectSolver {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DirectSolver")
            .field("unknowns", &self.x.len())
            .field("factor_entries", &self.values.len())
            .finish()
    }
}

impl DirectSolver {
    /// Builds and factors the matrix of `flags`.
    pub fn new(flags: &Flags) -> Result<Self, FluidError> {
        let grid = flags.grid;
        let (n, s) = (grid.n, grid.stride());
        // Number the unknowns: every fluid cell but the first of each region (held at zero).
        let mut held = vec![false; flags.regions];
        let mut unknown = vec![usize::MAX; grid.len()];
        let mut count = 0;
        let mut region_cells = vec![0.0; flags.regions];
        for j in 1..=n {
            for i in 1..=n {
                let k = j * s + i;
                if !flags.fluid[k] {
                    continue;
                }
                let r = flags.region[k] as usize;
                region_cells[r] += 1.0;
                if held[r] {
                    unknown[k] = count;
                    count += 1;
                } else {
                    held[r] = true;
                }
            }
        }
        // A fill-reducing order (approximate minimum degree), then the unknowns renumbered in it, so that
        // the solves need no permutation.
        let order = {
            let matrix = assemble(flags, &unknown, count)?;
            let symbolic = symbolic(&matrix, SymmetricOrdering::Amd)?;
            symbolic.perm().map(|perm| perm.arrays().0.to_vec())
        };
        if let Some(forward) = order {
            let mut renumber = vec![0; count];
            for (new, &old) in forward.iter().enumerate() {
                renumber[old] = new;
            }
            for x in unknown.iter_mut().filter(|x| **x != usize::MAX) {
                *x = renumber[*x];
            }
        }
        let matrix = assemble(flags, &unknown, count)?;
        let symbolic = symbolic(&matrix, SymmetricOrdering::Identity)?;
        let mut values = vec![0.0; symbolic.len_val()];
        let mut factor_scratch =
            MemBuffer::try_new(symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()))
                .map_err(|e| factor_error("scratch memory", &e))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                matrix.as_ref(),
                Side::Upper,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut factor_scratch),
                Default::default(),
            )
            .map_err(|e| factor_error("numeric factorization", &e))?;
        let scratch = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|e| factor_error("scratch memory", &e))?;
        let mut cell_of_unknown = vec![0; count];
        let mut fluid_cells = Vec::with_capacity(flags.fluid_cells);
        let mut held_cells = Vec::new();
        for (k, &row) in unknown.iter().enumerate() {
            if flags.fluid[k] {
                fluid_cells.push((k, flags.region[k] as usize));
                if row == usize::MAX {
                    held_cells.push(k);
                } else {
                    cell_of_unknown[row] = k;
                }
            }
        }
        Ok(Self {
            symbolic,
            values,
            cell_of_unknown,
            fluid_cells,
            held_cells,
            region_mean: vec![0.0; flags.regions],
            region_cells,
            x: vec![0.0; count],
            scratch,
        })
    }

    /// Entries of the Cholesky factor (a measure of its cost).
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// Solves for `p` exactly (to rounding) in the fluid cells; the held cells get zero, obstacle cells
    /// keep their values. Reports no residual (NaN): the step measures the divergence itself.
    pub fn solve(&mut self, flags: &Flags, rhs: &[f64], p: &mut [f64]) -> PressureSolve {
        let h2 = flags.grid.h_m * flags.grid.h_m;
        self.region_mean.fill(0.0);
        if let [sum] = &mut self.region_mean[..] {
            *sum = self.fluid_cells.iter().map(|&(k, _)| rhs[k]).sum();
        } else {
            for &(k, region) in &self.fluid_cells {
                self.region_mean[region] += rhs[k];
            }
        }
        for (mean, cells) in self.region_mean.iter_mut().zip(&self.region_cells) {
            *mean /= cells;
        }
        if let [mean] = self.region_mean[..] {
            for (x, &k) in self.x.iter_mut().zip(&self.cell_of_unknown) {
                *x = -h2 * (rhs[k] - mean);
            }
        } else {
            for (x, &k) in self.x.iter_mut().zip(&self.cell_of_unknown) {
                *x = -h2 * (rhs[k] - self.region_mean[flags.region[k] as usize]);
            }
        }
        if !self.x.is_empty() {
            let count = self.x.len();
            LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
                Conj::No,
                MatMut::from_column_major_slice_mut(&mut self.x, count, 1),
                Par::Seq,
                MemStack::new(&mut self.scratch),
            );
        }
        for (x, &k) in self.x.iter().zip(&self.cell_of_unknown) {
            p[k] = *x;
        }
        for &k in &self.held_cells {
            p[k] = 0.0;
        }
        PressureSolve { iterations: 1, max_residual_per_s2: f64::NAN }
    }
}

fn factor_error(what: &str, e: &dyn fmt::Debug) -> FluidError {
    FluidError::Factorization(format!("{what}: {e:?}"))
}

/// The upper triangle of the matrix `sum over fluid neighbours (p - p_nb) = -h^2 rhs` (symmetric positive
/// definite once one cell per region is held), in the numbering `unknown`.
fn assemble(flags: &Flags, unknown: &[usize], count: usize) -> Result<SparseColMat<usize, f64>, FluidError> {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let mut triplets = Vec::with_capacity(5 * count);
    for j in 1..=n {
        for i in 1..=n {
            let k = j * s + i;
            let row = unknown[k];
            if row == usize::MAX {
                continue;
            }
            let mut diagonal = 0.0;
            for nb in [k + 1, k - 1, k + s, k - s] {
                if flags.fluid[nb] {
                    diagonal += 1.0;
                    // The upper triangle only: with no reordering faer reads the entries as given.
                    if unknown[nb] != usize::MAX && row < unknown[nb] {
                        triplets.push(Triplet::new(row, unknown[nb], -1.0));
                    }
                }
            }
            triplets.push(Triplet::new(row, row, diagonal));
        }
    }
    SparseColMat::<usize, f64>::try_new_from_triplets(count, count, &triplets)
        .map_err(|e| factor_error("assembling the matrix", &e))
}

/// The symbolic factorization in `ordering`, simplicial: fewer factor entries than supernodal here
/// (1.96 M against 2.57 M at 256 x 256), and the solves, not the one factorization, are what counts.
fn symbolic(
    matrix: &SparseColMat<usize, f64>,
    ordering: SymmetricOrdering<'_, usize>,
) -> Result<SymbolicCholesky<usize>, FluidError> {
    factorize_symbolic_cholesky(
        matrix.symbolic(),
        Side::Upper,
        ordering,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
            ..Default::default()
        },
    )
    .map_err(|e| factor_error("symbolic factorization", &e))
}
