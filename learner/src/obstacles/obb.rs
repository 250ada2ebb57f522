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
        let a = &self.half_extents_m;
        let b = &other.half_extents_m;
        // r[i][j] = A_i . B_j; t = centre offset in A's frame.
        let ra_m = &self.rotation;
        let rb_m = &other.rotation;
        let mut r = [[0.0; 3]; 3];
        let mut abs_r = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                r[i][j] = ra_m.column(i).dot(&rb_m.column(j));
                abs_r[i][j] = r[i][j].abs() + SAT_EPSILON;
            }
        }
        let d = other.centre_m - self.centre_m;
        let t = [d.dot(&ra_m.column(0)), d.dot(&ra_m.column(1)), d.dot(&ra_m.column(2))];
        for i in 0..3 {
            let rb = b[0] * abs_r[i][0] + b[1] * abs_r[i][1] + b[2] * abs_r[i][2];
            if t[i].abs() > a[i] + rb {
                return false;
            }
        }
        for j in 0..3 {
            let ra = a[0] * abs_r[0][j] + a[1] * abs_r[1][j] + a[2] * abs_r[2][j];
            let proj = t[0] * r[0][j] + t[1] * r[1][j] + t[2] * r[2][j];
            if proj.abs() > ra + b[j] {
                return false;
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
                    return false;
                }
            }
        }
        true
    }
}
