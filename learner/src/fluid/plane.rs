//! Where a 2D primitive lives: the plane of the demonstration in the world (origin and two orthonormal
//! in-plane axes) and the square grid region of the simulation inside that plane.

use nalgebra::{Isometry3, Vector2, Vector3};

use super::error::FluidError;
use super::mask::ObstacleMask;

/// A plane in the world: a point of it and two orthonormal in-plane axes. Plane coordinates `(x, y)`
/// are metres along `axis_x` and `axis_y` from `origin_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFrame {
    /// The plane's origin in the world, m.
    pub origin_m: Vector3<f64>,
    /// First in-plane axis, unit length.
    pub axis_x: Vector3<f64>,
    /// Second in-plane axis, unit length, perpendicular to `axis_x`.
    pub axis_y: Vector3<f64>,
}

impl PlaneFrame {
    /// A checked frame: the axes are normalised and must be finite, non-zero and perpendicular within
    /// 1e-6 (cosine).
    pub fn new(
        origin_m: Vector3<f64>,
        axis_x: Vector3<f64>,
        axis_y: Vector3<f64>,
    ) -> Result<Self, FluidError> {
        if !origin_m.iter().all(|x| x.is_finite()) {
            return Err(FluidError::invalid("plane.origin_m", format!("not finite: {origin_m:?}")));
        }
        let unit = |field: &str, v: Vector3<f64>| {
            let norm = v.norm();
            if norm.is_finite() && norm > 1e-12 {
                Ok(v / norm)
            } else {
                Err(FluidError::invalid(field, "must be finite and not zero"))
            }
        };
        let x = unit("plane.axis_x", axis_x)?;
        let y = unit("plane.axis_y", axis_y)?;
        if x.dot(&y).abs() > 1e-6 {
            return Err(FluidError::invalid(
                "plane.axis_y",
                format!("must be perpendicular to axis_x (cosine {:.3e})", x.dot(&y)),
            ));
        }
        Ok(Self { origin_m, axis_x: x, axis_y: y })
    }

    /// The world's xy plane at height `z_m`.
    pub fn horizontal(z_m: f64) -> Self {
        Self { origin_m: Vector3::new(0.0, 0.0, z_m), axis_x: Vector3::x(), axis_y: Vector3::y() }
    }

    /// The normal `axis_x x axis_y`.
    pub fn normal(&self) -> Vector3<f64> {
        self.axis_x.cross(&self.axis_y)
    }

    /// The world point of plane coordinates `p`, m.
    pub fn to_world(&self, p: &Vector2<f64>) -> Vector3<f64> {
        self.origin_m + self.axis_x * p.x + self.axis_y * p.y
    }

    /// The plane coordinates of the world point `w` projected onto the plane, m.
    pub fn to_plane(&self, w: &Vector3<f64>) -> Vector2<f64> {
        let d = w - self.origin_m;
        Vector2::new(d.dot(&self.axis_x), d.dot(&self.axis_y))
    }

    /// The frame carried by a rigid motion of the world (`new_world_from_old`): a path given in plane
    /// coordinates moves with it.
    pub fn moved(&self, new_world_from_old: &Isometry3<f64>) -> Self {
        Self {
            origin_m: new_world_from_old.transform_point(&self.origin_m.into()).coords,
            axis_x: new_world_from_old.transform_vector(&self.axis_x),
            axis_y: new_world_from_old.transform_vector(&self.axis_y),
        }
    }
}

/// The simulation's square in a plane: `n x n` cells of side `cell_m`, cell `(i, j)` covering
/// `[origin + i h, origin + (i + 1) h)` along each plane axis (the obstacle-mask convention).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridRegion {
    /// Plane coordinates of the corner of cell (0, 0), m.
    pub origin_m: Vector2<f64>,
    /// Cell side, m.
    pub cell_m: f64,
    /// Cells per side.
    pub n: usize,
}

impl GridRegion {
    /// A checked region: finite origin, positive cell side, 8 to 1024 cells per side.
    pub fn new(origin_m: Vector2<f64>, cell_m: f64, n: usize) -> Result<Self, FluidError> {
        if !origin_m.iter().all(|x| x.is_finite()) {
            return Err(FluidError::invalid("region.origin_m", format!("not finite: {origin_m:?}")));
        }
        if !(cell_m.is_finite() && cell_m > 0.0) {
            return Err(FluidError::invalid("region.cell_m", format!("must be positive, got {cell_m}")));
        }
        if !(8..=1024).contains(&n) {
            return Err(FluidError::invalid("region.n", format!("must be in 8..=1024, got {n}")));
        }
        Ok(Self { origin_m, cell_m, n })
    }

    /// The square of `n x n` cells centred on the bounding box of `points` with `margin_m` on every side
    /// of it (along the box's longer side).
    pub fn around(points: &[Vector2<f64>], n: usize, margin_m: f64) -> Result<Self, FluidError> {
        if points.is_empty() || !points.iter().all(|p| p.iter().all(|x| x.is_finite())) {
            return Err(FluidError::invalid("points", "need at least one finite point"));
        }
        if !(margin_m.is_finite() && margin_m >= 0.0) {
            return Err(FluidError::invalid("margin_m", format!("must be >= 0, got {margin_m}")));
        }
        let lo = points.iter().fold(points[0], |a, p| a.inf(p));
        let hi = points.iter().fold(points[0], |a, p| a.sup(p));
        let side = (hi - lo).max() + 2.0 * margin_m;
        let centre = (lo + hi) / 2.0;
        Self::new(centre - Vector2::repeat(side / 2.0), side / n as f64, n)
    }

    /// Side of the square, m.
    pub fn size_m(&self) -> f64 {
        self.cell_m * self.n as f64
    }

    /// Grid coordinates (m from the corner of cell (0, 0)) of plane coordinates `p`.
    pub fn to_grid(&self, p: &Vector2<f64>) -> Vector2<f64> {
        p - self.origin_m
    }

    /// Plane coordinates of grid coordinates `g`.
    pub fn to_plane(&self, g: &Vector2<f64>) -> Vector2<f64> {
        g + self.origin_m
    }

    /// The cell holding plane point `p`, if inside the region.
    pub fn cell_of(&self, p: &Vector2<f64>) -> Option<(usize, usize)> {
        let g = self.to_grid(p) / self.cell_m;
        let n = self.n as f64;
        (g.x >= 0.0 && g.y >= 0.0 && g.x < n && g.y < n).then(|| (g.x as usize, g.y as usize))
    }

    /// Blocks in `mask` every cell that overlaps the box `[min_m, max_m]` (plane coordinates, closed):
    /// a real obstacle cutting the plane. Returns the number of cells newly blocked.
    pub fn block_box(&self, mask: &mut ObstacleMask, min_m: Vector2<f64>, max_m: Vector2<f64>) -> usize {
        let lo = self.to_grid(&min_m.inf(&max_m)) / self.cell_m;
        let hi = self.to_grid(&min_m.sup(&max_m)) / self.cell_m;
        let n = self.n.min(mask.n) as f64;
        if !(lo.iter().chain(hi.iter()).all(|x| x.is_finite()))
            || hi.x < 0.0
            || hi.y < 0.0
            || lo.x >= n
            || lo.y >= n
        {
            return 0;
        }
        let first = |x: f64| x.floor().max(0.0) as usize;
        let last = |x: f64| (x.floor().min(n - 1.0)) as usize;
        let mut added = 0;
        for j in first(lo.y)..=last(hi.y) {
            for i in first(lo.x)..=last(hi.x) {
                if !mask.blocked[j * mask.n + i] {
                    mask.blocked[j * mask.n + i] = true;
                    added += 1;
                }
            }
        }
        added
    }

    /// The world position of the corner of cell (0, 0) in `plane` (where the virtual obstacles' grid
    /// starts), m.
    pub fn world_corner_m(&self, plane: &PlaneFrame) -> Vector3<f64> {
        plane.to_world(&self.origin_m)
    }
}
