//! A computed grid: each cell's verdict, the raw obstacle mask, the mask after the fluid rules, and
//! (when asked for) every subcell's verdict.

use super::check::SubcellVerdict;
use super::mask::ObstacleMask;
use super::plane::GridPlane;
use super::postprocess::apply_fluid_rules;

/// What a cell is: blocked if any of its subcells is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellVerdict {
    /// Every subcell reachable and collision-free.
    Free,
    /// Every subcell reachable, at least one collides.
    Collides,
    /// At least one subcell unreachable (takes precedence: collisions are then not looked for).
    Unreachable,
}

impl CellVerdict {
    /// Whether the cell is a virtual obstacle.
    pub fn blocks(self) -> bool {
        self != CellVerdict::Free
    }

    /// The verdict of a cell with these subcell verdicts.
    pub fn of_subcells(verdicts: impl IntoIterator<Item = SubcellVerdict>) -> Self {
        let mut out = CellVerdict::Free;
        for v in verdicts {
            match v {
                SubcellVerdict::Unreachable => return CellVerdict::Unreachable,
                SubcellVerdict::Collides => out = CellVerdict::Collides,
                SubcellVerdict::Free => {}
            }
        }
        out
    }

    /// A short name for files and reports.
    pub fn as_str(self) -> &'static str {
        match self {
            CellVerdict::Free => "free",
            CellVerdict::Collides => "collision",
            CellVerdict::Unreachable => "unreachable",
        }
    }
}

/// The virtual obstacles of one grid.
#[derive(Clone, Debug, PartialEq)]
pub struct GridResult {
    /// The grid.
    pub plane: GridPlane,
    /// Each cell's verdict, row-major (`j * n + i`).
    pub cells: Vec<CellVerdict>,
    /// The cells blocked by their verdict alone.
    pub raw: ObstacleMask,
    /// `raw` grown to the fluid solver's rules (see [`apply_fluid_rules`]): what the solver gets.
    pub mask: ObstacleMask,
    /// Every subcell's verdict, fine-grid row-major (`y * n s + x`), when asked for.
    pub subcells: Option<Vec<SubcellVerdict>>,
    /// Subcells put through the inverse kinematics (all of them).
    pub subcells_checked: usize,
    /// Subcells whose boxes were tested for collision (fewer than all when a cell is settled early).
    pub subcells_collision_tested: usize,
}

impl GridResult {
    /// Assembles a result from cell verdicts.
    pub fn new(
        plane: GridPlane,
        cells: Vec<CellVerdict>,
        subcells: Option<Vec<SubcellVerdict>>,
        subcells_collision_tested: usize,
    ) -> Self {
        let raw = ObstacleMask { n: plane.cells, blocked: cells.iter().map(|c| c.blocks()).collect() };
        let mask = apply_fluid_rules(&raw);
        Self {
            subcells_checked: plane.subcell_count(),
            plane,
            cells,
            raw,
            mask,
            subcells,
            subcells_collision_tested,
        }
    }

    /// Cells blocked after the fluid rules.
    pub fn cells_blocked(&self) -> usize {
        self.mask.count_blocked()
    }

    /// Cells with the given verdict.
    pub fn count(&self, verdict: CellVerdict) -> usize {
        self.cells.iter().filter(|c| **c == verdict).count()
    }
}
