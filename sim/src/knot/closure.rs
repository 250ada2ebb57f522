//! Closure far from the knot, in one projection: each free end is extended radially outward from the
//! knot region's centre (a straight ray in space), then the rays are joined around a circle far
//! outside the picture of the thread.
//!
//! In space the closure is: both rays out to a sphere far outside the ball that holds the thread, and
//! an arc joining them that projects outside the thread's picture. Any two such arcs are isotopic in
//! the complement of the ball, so every projection sees the same closed knot; choosing the arc per
//! projection keeps it from drawing crossings over the knot. Only the rays can cross the thread, and
//! their heights are exact (a straight ray projects to a straight segment with linear height).

use nalgebra::Vector3;

use super::centreline::KnotRegion;
use super::projection::Projection;

/// The far circle's radius, in units of the region's radius.
const FAR_RADIUS_FACTOR: f64 = 2.5;
/// Largest angle, rad, one chord of the far circle spans (the chords stay outside the picture).
const MAX_CHORD_RAD: f64 = 0.25;

/// The closed curve as seen in one projection: vertex `i` joins vertex `i + 1` (and the last the first).
/// Vertices `0..thread_points` are the thread's; segments `0..thread_points - 1` lie on the thread,
/// the rest on the closure.
#[derive(Debug, Clone)]
pub struct ClosedPicture {
    /// Picture-plane coordinates of each vertex.
    pub xy: Vec<[f64; 2]>,
    /// Height of each vertex along the projection direction.
    pub height: Vec<f64>,
    /// How many vertices belong to the thread.
    pub thread_points: usize,
}

impl ClosedPicture {
    /// Projects a validated centreline and closes it far from the knot.
    pub fn new(points: &[Vector3<f64>], region: &KnotRegion, view: &Projection) -> Self {
        let n = points.len();
        let far = FAR_RADIUS_FACTOR * region.radius_m.max(f64::MIN_POSITIVE);
        let mut xy = Vec::with_capacity(n + 32);
        let mut height = Vec::with_capacity(n + 32);
        for p in points {
            let (q, h) = view.project(&(p - region.centre_m));
            xy.push(q);
            height.push(h);
        }
        // Each end's ray: the outward direction in space, its picture, the far point and its height.
        let ray = |end: usize, inward_neighbour: usize| -> ([f64; 2], f64, f64) {
            let mut out = points[end] - region.centre_m;
            if out.norm() < 1e-9 * region.radius_m {
                // The end sits at the centre: leave along the thread's own end tangent instead.
                out = points[end] - points[inward_neighbour];
            }
            let out = out.normalize();
            let (dir_xy, rise) = view.project(&out);
            let planar = (dir_xy[0] * dir_xy[0] + dir_xy[1] * dir_xy[1]).sqrt().max(1e-9);
            let unit = [dir_xy[0] / planar, dir_xy[1] / planar];
            let start = xy[end];
            let far_xy = [unit[0] * far, unit[1] * far];
            // Distance in the picture from the end to the far point, and the height gained on the way.
            let run = ((far_xy[0] - start[0]).powi(2) + (far_xy[1] - start[1]).powi(2)).sqrt();
            (far_xy, height[end] + run * rise / planar, unit[1].atan2(unit[0]))
        };
        let (tail_far, tail_h, tail_angle) = ray(n - 1, n - 2);
        let (needle_far, needle_h, needle_angle) = ray(0, 1);
        // From the tail's far point around the shorter way to the needle's far point.
        let mut sweep = needle_angle - tail_angle;
        if sweep > std::f64::consts::PI {
            sweep -= std::f64::consts::TAU;
        } else if sweep < -std::f64::consts::PI {
            sweep += std::f64::consts::TAU;
        }
        let chords = (sweep.abs() / MAX_CHORD_RAD).ceil().max(1.0) as usize;
        xy.push(tail_far);
        height.push(tail_h);
        for k in 1..chords {
            let f = k as f64 / chords as f64;
            let a = tail_angle + sweep * f;
            xy.push([far * a.cos(), far * a.sin()]);
            height.push(tail_h + (needle_h - tail_h) * f);
        }
        xy.push(needle_far);
        height.push(needle_h);
        Self { xy, height, thread_points: n }
    }

    /// Number of segments (equal to the number of vertices: the curve is closed).
    pub fn segments(&self) -> usize {
        self.xy.len()
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Unit;

    use super::*;

    /// Every closure vertex lies beyond twice the radius of the thread's picture, so the closure draws no
    /// crossing over the knot.
    #[test]
    fn closure_leaves_radially_and_stays_outside_the_picture() {
        let points: Vec<Vector3<f64>> =
            (0..20).map(|i| Vector3::new(i as f64 * 0.1, (i as f64 * 0.7).sin(), 0.01 * i as f64)).collect();
        let region = KnotRegion::of(&points);
        let view = Projection::new(Unit::new_normalize(Vector3::new(0.1, 0.2, 1.0)));
        let pic = ClosedPicture::new(&points, &region, &view);
        assert_eq!(pic.thread_points, 20);
        assert!(pic.segments() > 21);
        let r_thread = (0..20).map(|i| pic.xy[i][0].hypot(pic.xy[i][1])).fold(0.0, f64::max);
        for q in &pic.xy[20..] {
            assert!(q[0].hypot(q[1]) > 2.0 * r_thread, "closure vertex {q:?} inside the picture");
        }
    }
}
