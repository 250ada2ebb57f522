//! The thread's centreline: validation, arc length, and the region the knot occupies.

use nalgebra::Vector3;

use super::error::KnotError;

/// Fewest points a centreline may have: three segments are the least that can cross themselves.
pub const MIN_POINTS: usize = 4;

/// Most points a centreline may have: a simulated thread has a few hundred, a measured one a few
/// thousand; a million classify in seconds and a few hundred megabytes.
pub const MAX_POINTS: usize = 1_000_000;

/// Checks that a centreline can be classified: [`MIN_POINTS`] to [`MAX_POINTS`] points, all finite,
/// no two consecutive points equal.
pub fn validate(points: &[Vector3<f64>]) -> Result<(), KnotError> {
    if points.len() < MIN_POINTS {
        return Err(KnotError::TooFewPoints { count: points.len() });
    }
    if points.len() > MAX_POINTS {
        return Err(KnotError::TooManyPoints { count: points.len(), max: MAX_POINTS });
    }
    for (index, p) in points.iter().enumerate() {
        for (axis, value) in ['x', 'y', 'z'].into_iter().zip(p.iter().copied()) {
            if !value.is_finite() {
                return Err(KnotError::NotFinite { index, axis, value });
            }
        }
        if index > 0 && points[index - 1] == *p {
            return Err(KnotError::DuplicatePoint { index, previous: index - 1 });
        }
    }
    Ok(())
}

/// Cumulative arc length at each point, m: `0` at the needle end, the thread's length at the tail end.
pub fn arc_lengths_m(points: &[Vector3<f64>]) -> Vec<f64> {
    let mut total = 0.0;
    let mut lengths = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            total += (p - points[i - 1]).norm();
        }
        lengths.push(total);
    }
    lengths
}

/// A ball holding the whole thread: the closure at infinity leaves it before joining the ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnotRegion {
    /// The thread's centre of mass (segments weighted by length), m.
    pub centre_m: Vector3<f64>,
    /// Distance from the centre to the farthest point of the thread, m.
    pub radius_m: f64,
}

impl KnotRegion {
    /// The region of a validated centreline.
    pub fn of(points: &[Vector3<f64>]) -> Self {
        let mut weighted = Vector3::zeros();
        let mut length = 0.0;
        for w in points.windows(2) {
            let l = (w[1] - w[0]).norm();
            weighted += (w[0] + w[1]) * (0.5 * l);
            length += l;
        }
        let centre_m = if length > 0.0 { weighted / length } else { points[0] };
        let radius_m = points.iter().map(|p| (p - centre_m).norm()).fold(0.0, f64::max);
        Self { centre_m, radius_m }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize) -> Vec<Vector3<f64>> {
        (0..n).map(|i| Vector3::new(i as f64, 0.0, 0.0)).collect()
    }

    /// A centreline with too few points, a non-finite coordinate or a repeated point is refused, naming it.
    #[test]
    fn refuses_short_non_finite_and_repeated_centrelines() {
        assert_eq!(validate(&line(3)), Err(KnotError::TooFewPoints { count: 3 }));
        assert_eq!(validate(&line(4)), Ok(()));
        let mut nan = line(5);
        nan[2].y = f64::NAN;
        assert!(matches!(validate(&nan), Err(KnotError::NotFinite { index: 2, axis: 'y', .. })));
        let mut inf = line(5);
        inf[4].z = f64::INFINITY;
        assert!(matches!(validate(&inf), Err(KnotError::NotFinite { index: 4, axis: 'z', .. })));
        let mut dup = line(5);
        dup[3] = dup[2];
        assert_eq!(validate(&dup), Err(KnotError::DuplicatePoint { index: 3, previous: 2 }));
    }

    /// A straight thread's knot region is centred on it, half its length in radius; its arc lengths add up.
    #[test]
    fn region_holds_the_thread_and_arc_length_adds_up() {
        let points = line(11);
        let region = KnotRegion::of(&points);
        assert!((region.centre_m - Vector3::new(5.0, 0.0, 0.0)).norm() < 1e-12);
        assert!((region.radius_m - 5.0).abs() < 1e-12);
        let s = arc_lengths_m(&points);
        assert_eq!((s[0], s[10]), (0.0, 10.0));
    }
}
