//! Points a fixed straight-line distance apart along a polyline, where a thread's particles or segments
//! are laid.

use nalgebra::Vector3;

/// Points along `polyline` spaced `step_m` apart in straight-line distance (each the first point of
/// the polyline beyond the last at that distance), `count` of them; the polyline is extended along its
/// last piece when it runs out. Chords, not arc length: a chain of rigid segments laid on them has no
/// stretched joint, even at corners.
pub fn chord_points(polyline: &[Vector3<f64>], step_m: f64, count: usize) -> Vec<Vector3<f64>> {
    let mut out = Vec::with_capacity(count);
    let Some(first) = polyline.first() else { return out };
    out.push(*first);
    let mut piece = 0;
    while out.len() < count {
        let p = out[out.len() - 1];
        // Find the first piece whose far end lies at least step_m away from p.
        loop {
            let last_piece = piece + 2 >= polyline.len();
            let (a, b) = if polyline.len() < 2 {
                (*first, *first + Vector3::x())
            } else {
                (polyline[piece.min(polyline.len() - 2)], polyline[(piece + 1).min(polyline.len() - 1)])
            };
            let d = b - a;
            // Solve |a + d t - p| = step for the largest t in [0, 1] (or beyond on the last piece).
            let (qa, qb, qc) = (d.dot(&d), 2.0 * d.dot(&(a - p)), (a - p).norm_squared() - step_m * step_m);
            let disc = qb * qb - 4.0 * qa * qc;
            let t = if qa > 0.0 && disc >= 0.0 { (-qb + disc.sqrt()) / (2.0 * qa) } else { f64::NAN };
            if t.is_finite() && t >= 0.0 && (t <= 1.0 || last_piece) {
                out.push(a + d * t);
                break;
            }
            if last_piece {
                // Degenerate polyline: go on straight.
                out.push(p + d.try_normalize(0.0).unwrap_or_else(Vector3::x) * step_m);
                break;
            }
            piece += 1;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chord points fall exactly a step apart, follow the polyline round its corner and run on past its end.
    #[test]
    fn chord_points_are_a_step_apart_and_turn_corners() {
        let l = vec![Vector3::zeros(), Vector3::new(0.1, 0.0, 0.0), Vector3::new(0.1, 0.1, 0.0)];
        let pts = chord_points(&l, 0.01, 25);
        assert_eq!(pts.len(), 25);
        for w in pts.windows(2) {
            assert!(((w[1] - w[0]).norm() - 0.01).abs() < 1e-12);
        }
        // Past the corner the points follow the second piece.
        assert!((pts[15].x - 0.1).abs() < 1e-12, "{:?}", pts[15]);
        assert!(pts[24].y > 0.12, "extended past the end: {:?}", pts[24]);
    }
}
