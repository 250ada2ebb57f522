//! The grid a 2D primitive moves in: a square in a plane of the world, cut into n x n cells of s x s
//! subcells each. The tip is placed at every subcell's centre.

use nalgebra::Vector3;

use super::error::ObstacleError;

/// Most subcells along one side of a grid (n * s): 4 million subcells in all.
pub const MAX_SUBCELLS_PER_SIDE: usize = 2000;

/// A square grid in a plane of the world. Cell `(i, j)` covers `[i h, (i + 1) h)` along `axis_u` and
/// `[j h, (j + 1) h)` along `axis_v` from `origin_m`, with `h = size_m / cells`; its subcell `(a, b)` has
/// its centre at `origin_m + ((i s + a + 0.5) u + (j s + b + 0.5) v) size_m / (n s)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPlane {
    /// Corner of cell (0, 0), world frame, m.
    pub origin_m: Vector3<f64>,
    /// First in-plane axis (cell index `i`), unit length.
    pub axis_u: Vector3<f64>,
    /// Second in-plane axis (cell index `j`), unit length, perpendicular to `axis_u`.
    pub axis_v: Vector3<f64>,
    /// Side of the square, m.
    pub size_m: f64,
    /// Cells per side (n).
    pub cells: usize,
    /// Subcells per cell side (s).
    pub subcells: usize,
}

impl GridPlane {
    /// The paper's grid size: 50 x 50 cells.
    pub const DEFAULT_CELLS: usize = 50;
    /// The paper's subdivision: 5 x 5 subcells per cell.
    pub const DEFAULT_SUBCELLS: usize = 5;

    /// A checked grid. The axes are normalised; they must be finite, not zero, and perpendicular within
    /// 1e-6 rad (after normalising).
    pub fn new(
        origin_m: Vector3<f64>,
        axis_u: Vector3<f64>,
        axis_v: Vector3<f64>,
        size_m: f64,
        cells: usize,
        subcells: usize,
    ) -> Result<Self, ObstacleError> {
        let err = |field: &'static str, reason: String| ObstacleError::Plane { field, reason };
        let bad = |field: &'static str, reason: String| Err(err(field, reason));
        if !origin_m.iter().all(|x| x.is_finite()) {
            return bad("origin", format!("not finite: {origin_m:?}"));
        }
        let unit = |field: &'static str, v: Vector3<f64>| {
            let n = v.norm();
            if n.is_finite() && n > 1e-9 {
                Ok(v / n)
            } else {
                Err(err(field, "must be finite and not zero".to_owned()))
            }
        };
        let u = unit("axis_u", axis_u)?;
        let v = unit("axis_v", axis_v)?;
        if u.dot(&v).abs() > 1e-6 {
            return bad("axis_v", format!("must be perpendicular to axis_u (cosine {:.3e})", u.dot(&v)));
        }
        if !(size_m.is_finite() && size_m > 0.0 && size_m <= 10.0) {
            return bad("size", format!("must be within 0..10 m, got {size_m}"));
        }
        if cells < 2 {
            return bad("cells", format!("must be at least 2, got {cells}"));
        }
        if subcells < 1 {
            return bad("subcells", "must be at least 1, got 0".to_owned());
        }
        if cells.saturating_mul(subcells) > MAX_SUBCELLS_PER_SIDE {
            return bad(
                "subcells",
                format!("cells x subcells = {} exceeds {MAX_SUBCELLS_PER_SIDE} per side", cells * subcells),
            );
        }
        Ok(Self { origin_m, axis_u: u, axis_v: v, size_m, cells, subcells })
    }

    /// A checked grid centred on `centre_m` (see [`GridPlane::new`] for the checks).
    pub fn centred(
        centre_m: Vector3<f64>,
        axis_u: Vector3<f64>,
        axis_v: Vector3<f64>,
        size_m: f64,
        cells: usize,
        subcells: usize,
    ) -> Result<Self, ObstacleError> {
        let plane = Self::new(centre_m, axis_u, axis_v, size_m, cells, subcells)?;
        Ok(Self { origin_m: centre_m - (plane.axis_u + plane.axis_v) * (0.5 * size_m), ..plane })
    }

    /// Subcells along one side (n s).
    pub fn side(&self) -> usize {
        self.cells * self.subcells
    }

    /// Number of subcells in all.
    pub fn subcell_count(&self) -> usize {
        self.side() * self.side()
    }

    /// Side of one cell, m.
    pub fn cell_size_m(&self) -> f64 {
        self.size_m / self.cells as f64
    }

    /// Side of one subcell, m.
    pub fn subcell_size_m(&self) -> f64 {
        self.size_m / self.side() as f64
    }

    /// The plane's normal, `axis_u x axis_v`.
    pub fn normal(&self) -> Vector3<f64> {
        self.axis_u.cross(&self.axis_v)
    }

    /// Centre of the subcell at fine-grid column `x` and row `y` (both `0..n s`), world frame, m.
    pub fn subcell_centre_m(&self, x: usize, y: usize) -> Vector3<f64> {
        let h = self.subcell_size_m();
        self.origin_m + self.axis_u * ((x as f64 + 0.5) * h) + self.axis_v * ((y as f64 + 0.5) * h)
    }

    /// The centre of cell `(i, j)`, world frame, m.
    pub fn cell_centre_m(&self, i: usize, j: usize) -> Vector3<f64> {
        let h = self.cell_size_m();
        self.origin_m + self.axis_u * ((i as f64 + 0.5) * h) + self.axis_v * ((j as f64 + 0.5) * h)
    }

    /// The cell a world point falls in, if it lies over the grid (its distance from the plane is ignored).
    pub fn cell_of(&self, point_m: &Vector3<f64>) -> Option<(usize, usize)> {
        let d = point_m - self.origin_m;
        let h = self.cell_size_m();
        let (a, b) = ((d.dot(&self.axis_u) / h).floor(), (d.dot(&self.axis_v) / h).floor());
        let n = self.cells as f64;
        (a >= 0.0 && b >= 0.0 && a < n && b < n).then_some((a as usize, b as usize))
    }
}
