//! How far an instrument reaches along a line: its wrist no deeper past the trocar than the tool
//! allows (a pull sent further faults the run: `device_fault`, the insertion 0.2401 m past 0.24 m).

use knotlab_hw::kinematics::InstrumentGeometry;
use knotlab_sim::world::JAW_CENTRE_OFFSET_M;
use nalgebra::Vector3;

/// Kept this far inside the deepest insertion, m.
const REACH_MARGIN_M: f64 = 0.001;

/// The point of the segment `from`..`to` (jaw centres, world) nearest `to` that an instrument through
/// `trocar_m` reaches with its jaws pointing along `jaw`: its yaw axis within the deepest insertion less
/// the wrist (the pitch axis lies a wrist's length from the yaw axis, whichever way the wrist bends).
/// `from` itself when even that is too deep.
pub fn reach_along(
    geometry: &InstrumentGeometry,
    trocar_m: &Vector3<f64>,
    jaw: &Vector3<f64>,
    from: &Vector3<f64>,
    to: &Vector3<f64>,
) -> Vector3<f64> {
    let radius_m = geometry.max_insertion_m - geometry.wrist_m - REACH_MARGIN_M;
    let yaw_from_centre = jaw.normalize() * (JAW_CENTRE_OFFSET_M - geometry.jaw_m);
    let a = from + yaw_from_centre - trocar_m;
    let line = to - from;
    let length_m = line.norm();
    if (a + line).norm() <= radius_m || length_m < 1e-12 {
        return *to;
    }
    // The far root of |a + u s| = r along the unit direction u.
    let u = line / length_m;
    let b = a.dot(&u);
    let discriminant = b * b - a.norm_squared() + radius_m * radius_m;
    if discriminant < 0.0 {
        return *from;
    }
    let s = (-b + discriminant.sqrt()).clamp(0.0, length_m);
    from + u * s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_beyond_reach_is_brought_back_to_the_deepest_insertion() {
        let geometry = InstrumentGeometry::LARGE_NEEDLE_DRIVER;
        let trocar = Vector3::new(0.0, 0.0, 1.0);
        let jaw = Vector3::new(0.0, 0.0, -1.0);
        // Straight down the shaft: the centre reaches 0.24 - 0.0091 - 0.001 + 0.005 m past the trocar.
        let from = Vector3::new(0.0, 0.0, 0.9);
        let to = Vector3::new(0.0, 0.0, 0.6);
        let reached = reach_along(&geometry, &trocar, &jaw, &from, &to);
        let depth_m = 1.0 - reached.z;
        assert!((depth_m - (0.24 - 0.0091 - 0.001 + 0.005)).abs() < 1e-12, "{depth_m}");
        assert_eq!((reached.x, reached.y), (0.0, 0.0));
        // Within reach: the target itself.
        let near = Vector3::new(0.01, 0.02, 0.85);
        assert_eq!(reach_along(&geometry, &trocar, &jaw, &from, &near), near);
        // Sideways from a point already at the limit: nowhere further.
        let edge = Vector3::new(0.0, 0.0, 1.0 - depth_m);
        let side = edge + Vector3::new(0.0, 0.05, -0.01);
        assert!((reach_along(&geometry, &trocar, &jaw, &edge, &side) - edge).norm() < 1e-9);
    }
}
