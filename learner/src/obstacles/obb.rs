//! Oriented bounding boxes and their separating-axis overlap test (Gottschalk's 15 axes).

use nalgebra::{IsometryMatrix3, Matrix3, Vector3};

use knotlab_hw::rig::Shape;

/// Added to the absolute rotation terms of the test, as Ericson's Real-Time Collision Detection
/// advises: it keeps the edge-edge axes of (nearly) parallel edges from reporting a false separation.
/// The GPU kernel uses the same value.
pub const SAT_EPSILON: f64 = 1e-6;

/// An oriented box in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Obb {
    /// Centre, world frame, m.
    pub centre_m: Vector3<f64>,
    /// Its axes as the columns of a rotation (world from box).
    pub rotation: Matrix3<f64>,
    /// Half sizes along its axes, m.
    pub half_extents_m: Vector3<f64>,
}

/// Half extents of the box that bounds a collision shape in the shape's frame: boxes stay as they are,
/// capsules (along z) and spheres become their bounding boxes.
pub fn bounding_half_extents_m(shape: &Shape) -> Vector3<f64> {
    match *shape {
        Shape::Box { half_extents_m } => half_extents_m,
        Shape::Capsule { radius_m, length_m } => Vector3::new(radius_m, radius_m, 0.5 * length_m + radius_m),
        Shape::Sphere { radius_m } => Vector3::repeat(radius_m),
    }
}

impl Obb {
    /// The box with these half extents placed at `world_from_box`.
    pub fn new(world_from_box: &IsometryMatrix3<f64>, half_extents_m: Vector3<f64>) -> Self {
        Self {
            centre_m: world_from_box.translation.vector,
            rotation: *world_from_box.rotation.matrix(),
            half_extents_m,
        }
    }

    /// Radius of the sphere about the centre that holds the box, m.
    pub fn bounding_radius_m(&self) -> f64 {
        self.half_extents_m.norm()
    }

    /// Whether the boxes overlap (touching counts as overlap). Separating-axis test over the 15
    /// candidate axes: the faces of either box and the nine edge-edge cross products.
    pub fn intersects(&self, other: &Obb) -> bool {
        self.separating_axis(other).is_none()
    }

    /// [`Obb::intersects`], trying first the axis that separated a similar pair last time (`hint`, which
    /// it updates): neighbouring subcells pose the arm almost alike, so one axis test usually settles
    /// it. The verdict is the same as without the hint.
    pub fn intersects_hinted(&self, other: &Obb, hint: &mut u8) -> bool {
        if *hint < 15 && self.separated_along(other, *hint) {
            return false;
        }
        match self.separating_axis(other) {
            Some(axis) => {
                *hint = axis;
                false
            }
            None => true,
        }
    }

    /// `A_i . B_j`, the terms of the test.
    #[inline]
    fn r(&self, other: &Obb, i: usize, j: usize) -> f64 {
        self.rotation.column(i).dot(&other.rotation.column(j))
    }

    /// The centre offset along `A_i`.
    #[inline]
    fn t(&self, other: &Obb, i: usize) -> f64 {
        (other.centre_m - self.centre_m).dot(&self.rotation.column(i))
    }

    /// Whether candidate axis `axis` (0-2: A's faces, 3-5: B's faces, 6-14: `A_i x B_j` with
    /// `axis = 6 + 3 i + j`) separates the boxes, computed exactly as [`Obb::separating_axis`] does.
    pub fn separated_along(&self, other: &Obb, axis: u8) -> bool {
        let a = &self.half_extents_m;
        let b = &other.half_extents_m;
        let abs = |i, j| self.r(other, i, j).abs() + SAT_EPSILON;
        match axis {
            0..=2 => {
                let i = usize::from(axis);
                let rb = b[0] * abs(i, 0) + b[1] * abs(i, 1) + b[2] * abs(i, 2);
                self.t(other, i).abs() > a[i] + rb
            }
            3..=5 => {
                let j = usize::from(axis - 3);
                let ra = a[0] * abs(0, j) + a[1] * abs(1, j) + a[2] * abs(2, j);
                let t = [self.t(other, 0), self.t(other, 1), self.t(other, 2)];
                let proj =
                    t[0] * self.r(other, 0, j) + t[1] * self.r(other, 1, j) + t[2] * self.r(other, 2, j);
                proj.abs() > ra + b[j]
            }
            6..=14 => {
                let (i, j) = (usize::from(axis - 6) / 3, usize::from(axis - 6) % 3);
                let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
                let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                let ra = a[i1] * abs(i2, j) + a[i2] * abs(i1, j);
                let rb = b[j1] * abs(i, j2) + b[j2] * abs(i, j1);
                let proj =
                    self.t(other, i2) * self.r(other, i1, j) - self.t(other, i1) * self.r(other, i2, j);
                proj.abs() > ra + rb
            }
            _ => false,
        }
    }

    /// The first candidate axis (numbered as in [`Obb::separated_along`]) that separates the boxes, or
    /// `None` when they overlap.
    pub fn separating_axis(&self, other: &Obb) -> Option<u8> {
        let a = &self.half_extents_m;
        let b = &other.half_extents_m;
        // r[i][j] = A_i . B_j; t = centre offset in A's frame.
        let mut r = [[0.0; 3]; 3];
        let mut abs_r = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = self.r(other, i, j);
                abs_r[i][j] = r[i][j].abs() + SAT_EPSILON;
            }
        }
        let t = [self.t(other, 0), self.t(other, 1), self.t(other, 2)];
        for i in 0..3 {
            let rb = b[0] * abs_r[i][0] + b[1] * abs_r[i][1] + b[2] * abs_r[i][2];
            if t[i].abs() > a[i] + rb {
                return Some(i as u8);
            }
        }
        for j in 0..3 {
            let ra = a[0] * abs_r[0][j] + a[1] * abs_r[1][j] + a[2] * abs_r[2][j];
            let proj = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
            if proj.abs() > ra + b[j] {
                return Some(3 + j as u8);
            }
        }
        for i in 0..3 {
            let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
            for j in 0..3 {
                let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
                let ra = a[i1] * abs_r[i2][j] + a[i2] * abs_r[i1][j];
                let rb = b[j1] * abs_r[i][j2] + b[j2] * abs_r[i][j1];
                let proj = t[i2] * r[i1][j] - t[i1] * r[i2][j];
                if proj.abs() > ra + rb {
                    return Some(6 + (3 * i + j) as u8);
                }
            }
        }
        None
    }
}
