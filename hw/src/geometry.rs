//! Small geometry shared by the simulator and the learner: closest points between line segments
//! (Ericson, Real-Time Collision Detection, 5.1.9).

use nalgebra::Vector3;

/// Closest points of segments `p0 + s d1` and `q0 + t d2`, `s, t` in [0, 1].
pub fn segment_closest_parameters(
    p0: &Vector3<f64>,
    d1: &Vector3<f64>,
    q0: &Vector3<f64>,
    d2: &Vector3<f64>,
) -> (f64, f64) {
    let r = p0 - q0;
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(&r));
    if a < 1e-24 && e < 1e-24 {
        return (0.0, 0.0);
    }
    if a < 1e-24 {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e < 1e-24 {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let mut s = if denom > 1e-24 { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Shortest distance between the segments `p0`-`p1` and `q0`-`q1`.
pub fn segment_distance(p0: &Vector3<f64>, p1: &Vector3<f64>, q0: &Vector3<f64>, q1: &Vector3<f64>) -> f64 {
    let (d1, d2) = (p1 - p0, q1 - q0);
    let (s, t) = segment_closest_parameters(p0, &d1, q0, &d2);
    ((p0 + d1 * s) - (q0 + d2 * t)).norm()
}

/// Cumulative arc length at each point of a polyline, m (0 at the first point).
pub fn arc_lengths(points: &[Vector3<f64>]) -> Vec<f64> {
    let mut arc = Vec::with_capacity(points.len());
    let mut s = 0.0;
    for (k, p) in points.iter().enumerate() {
        if k > 0 {
            s += (p - points[k - 1]).norm();
        }
        arc.push(s);
    }
    arc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Arc lengths sum a polyline's pieces from zero at its first point; an empty polyline has none.
    #[test]
    fn arc_lengths_accumulate_the_pieces() {
        let points = [Vector3::zeros(), Vector3::new(3.0, 4.0, 0.0), Vector3::new(3.0, 4.0, 2.0)];
        assert_eq!(arc_lengths(&points), vec![0.0, 5.0, 7.0]);
        assert!(arc_lengths(&[]).is_empty());
    }

    /// Segment distances are right for crossing segments, parallel ones offset past an end, and a segment
    /// shrunk to a point.
    #[test]
    fn distances_of_crossing_parallel_and_degenerate_segments() {
        let v = Vector3::new;
        // Crossing 1 apart in z.
        assert!(
            (segment_distance(&v(-1.0, 0.0, 0.0), &v(1.0, 0.0, 0.0), &v(0.0, -1.0, 1.0), &v(0.0, 1.0, 1.0))
                - 1.0)
                .abs()
                < 1e-12
        );
        // Parallel, offset beyond the end: end to end.
        let d = segment_distance(&v(0.0, 0.0, 0.0), &v(1.0, 0.0, 0.0), &v(2.0, 1.0, 0.0), &v(3.0, 1.0, 0.0));
        assert!((d - 2f64.sqrt()).abs() < 1e-12, "{d}");
        // A point against a segment.
        let d = segment_distance(&v(0.5, 2.0, 0.0), &v(0.5, 2.0, 0.0), &v(0.0, 0.0, 0.0), &v(1.0, 0.0, 0.0));
        assert!((d - 2.0).abs() < 1e-12, "{d}");
    }
}
