//! Real obstacles that cut the primitive's plane: solids in the world (oriented boxes, capsules such as
//! an instrument's shaft, spheres) turned into blocked cells of the obstacle mask. A cell is blocked when
//! its square, in the plane, touches the solid (exact tests: separating axes for boxes, segment-to-square
//! distance for capsules).

use nalgebra::{Isometry3, Vector3};

use super::error::FluidError;
use super::mask::ObstacleMask;
use super::plane::{GridRegion, PlaneFrame};

/// A solid in the world, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid {
    /// A box: its pose in the world and its half extents along its own axes.
    Box {
        /// The box's frame in the world.
        world_from_box: Isometry3<f64>,
        /// Half extents along the box's x, y, z, m.
        half_extents_m: Vector3<f64>,
    },
    /// All points within `radius_m` of the segment from `a_m` to `b_m` (a sphere when they coincide).
    Capsule {
        /// One end of the axis, world, m.
        a_m: Vector3<f64>,
        /// The other end, world, m.
        b_m: Vector3<f64>,
        /// Radius, m.
        radius_m: f64,
    },
}

impl Solid {
    /// Checks that every number is finite and sizes are not negative.
    pub fn validate(&self) -> Result<(), FluidError> {
        let finite = |v: &Vector3<f64>| v.iter().all(|x| x.is_finite());
        match self {
            Solid::Box { world_from_box, half_extents_m } => {
                if !finite(&world_from_box.translation.vector)
                    || !world_from_box.rotation.coords.iter().all(|x| x.is_finite())
                {
                    return Err(FluidError::invalid("solid.world_from_box", "not finite"));
                }
                if !(finite(half_extents_m) && half_extents_m.iter().all(|x| *x >= 0.0)) {
                    return Err(FluidError::invalid(
                        "solid.half_extents_m",
                        format!("must be >= 0, got {half_extents_m:?}"),
                    ));
                }
            }
            Solid::Capsule { a_m, b_m, radius_m } => {
                if !(finite(a_m) && finite(b_m)) {
                    return Err(FluidError::invalid("solid.axis", "not finite"));
                }
                if !(radius_m.is_finite() && *radius_m >= 0.0) {
                    return Err(FluidError::invalid(
                        "solid.radius_m",
                        format!("must be >= 0, got {radius_m}"),
                    ));
                }
            }
        }
        Ok(())
    }
}

/// Blocks in `mask` every cell of `region` (in `plane`) whose square touches `solid`. Returns the number
/// of cells newly blocked.
pub fn block_solid(
    mask: &mut ObstacleMask,
    plane: &PlaneFrame,
    region: &GridRegion,
    solid: &Solid,
) -> Result<usize, FluidError> {
    solid.validate()?;
    if mask.n != region.n {
        return Err(FluidError::invalid(
            "mask",
            format!("a {0} x {0} mask for a {1} x {1} region", mask.n, region.n),
        ));
    }
    let h = region.cell_m;
    let mut added = 0;
    for j in 0..region.n {
        for i in 0..region.n {
            if mask.blocked[j * region.n + i] {
                continue;
            }
            let corner = region.origin_m + nalgebra::Vector2::new(i as f64, j as f64) * h;
            let square = Square {
                centre: plane.to_world(&(corner + nalgebra::Vector2::repeat(0.5 * h))),
                x: plane.axis_x,
                y: plane.axis_y,
                half: 0.5 * h,
            };
            let touches = match solid {
                Solid::Box { world_from_box, half_extents_m } => {
                    square.touches_box(world_from_box, half_extents_m)
                }
                Solid::Capsule { a_m, b_m, radius_m } => square.distance_to_segment(a_m, b_m) <= *radius_m,
            };
            if touches {
                mask.blocked[j * region.n + i] = true;
                added += 1;
            }
        }
    }
    Ok(added)
}

/// A cell's square in the world: centre, unit in-plane axes, half side.
struct Square {
    centre: Vector3<f64>,
    x: Vector3<f64>,
    y: Vector3<f64>,
    half: f64,
}

impl Square {
    /// Separating-axis test against an oriented box (the square is a box of zero thickness).
    fn touches_box(&self, world_from_box: &Isometry3<f64>, half: &Vector3<f64>) -> bool {
        let r = world_from_box.rotation;
        let box_axes = [r * Vector3::x(), r * Vector3::y(), r * Vector3::z()];
        let offset = world_from_box.translation.vector - self.centre;
        let normal = self.x.cross(&self.y);
        let square_axes = [self.x, self.y, normal];
        let square_half = [self.half, self.half, 0.0];
        let separated = |axis: Vector3<f64>| {
            let len = axis.norm();
            if len < 1e-12 {
                return false;
            }
            let axis = axis / len;
            let box_radius: f64 = (0..3).map(|k| half[k] * box_axes[k].dot(&axis).abs()).sum();
            let square_radius: f64 = (0..3).map(|k| square_half[k] * square_axes[k].dot(&axis).abs()).sum();
            offset.dot(&axis).abs() > box_radius + square_radius
        };
        if box_axes.iter().chain(&square_axes).any(|a| separated(*a)) {
            return false;
        }
        !box_axes.iter().any(|a| square_axes.iter().any(|b| separated(a.cross(b))))
    }

    /// Distance from the segment `a`-`b` to the square, m.
    fn distance_to_segment(&self, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
        let normal = self.x.cross(&self.y);
        let (da, db) = ((a - self.centre).dot(&normal), (b - self.centre).dot(&normal));
        // Crossing the plane inside the square.
        if da * db <= 0.0 && da != db {
            let p = a + (b - a) * (da / (da - db));
            if self.in_square(&p) {
                return 0.0;
            }
        }
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .map(|(u, v)| self.centre + self.x * (u * self.half) + self.y * (v * self.half));
        let mut best = self.point_distance(a).min(self.point_distance(b));
        for k in 0..4 {
            best = best.min(segment_segment(a, b, &corners[k], &corners[(k + 1) % 4]));
        }
        best
    }

    fn in_square(&self, p: &Vector3<f64>) -> bool {
        let d = p - self.centre;
        d.dot(&self.x).abs() <= self.half && d.dot(&self.y).abs() <= self.half
    }

    fn point_distance(&self, p: &Vector3<f64>) -> f64 {
        let d = p - self.centre;
        let u = d.dot(&self.x).clamp(-self.half, self.half);
        let v = d.dot(&self.y).clamp(-self.half, self.half);
        (d - self.x * u - self.y * v).norm()
    }
}

/// Distance between the segments `p1`-`q1` and `p2`-`q2`.
fn segment_segment(p1: &Vector3<f64>, q1: &Vector3<f64>, p2: &Vector3<f64>, q2: &Vector3<f64>) -> f64 {
    knotlab_hw::geometry::segment_distance(p1, q1, p2, q2)
}
