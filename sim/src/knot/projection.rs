//! Projection directions: the three axes and a spread of directions over a hemisphere, each turned
//! slightly by a fixed, deterministic jitter so that no direction lines up with an axis-aligned thread.

use nalgebra::{Rotation3, Unit, Vector3};

/// Number of projection directions that vote: 3 axes plus [`SPREAD_DIRECTIONS`].
pub const DIRECTIONS: usize = 3 + SPREAD_DIRECTIONS;

/// Directions spread over a hemisphere (a Fibonacci lattice); `d` and `-d` give mirror-image
/// diagrams of the same knot, so one hemisphere suffices.
pub const SPREAD_DIRECTIONS: usize = 10;

/// Jitter: each direction is turned by about this angle, rad, about an axis of its own.
const JITTER_RAD: f64 = 0.035;

/// A view of the thread: `direction` points at the viewer; `(u, v, direction)` is right-handed, so a
/// point projects to `(p.u, p.v)` and its height is `p.direction` (higher is over).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Towards the viewer (unit).
    pub direction: Unit<Vector3<f64>>,
    /// First axis of the picture plane (unit).
    pub u: Vector3<f64>,
    /// Second axis of the picture plane (unit), `direction x u`.
    pub v: Vector3<f64>,
}

impl Projection {
    /// The projection looking along `-direction`, with a deterministic picture-plane basis.
    pub fn new(direction: Unit<Vector3<f64>>) -> Self {
        let d = direction.into_inner();
        let helper = if d.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
        let u = (helper - d * d.dot(&helper)).normalize();
        let v = d.cross(&u);
        Self { direction, u, v }
    }

    /// Picture-plane coordinates and height of a point.
    pub fn project(&self, p: &Vector3<f64>) -> ([f64; 2], f64) {
        ([p.dot(&self.u), p.dot(&self.v)], p.dot(&self.direction))
    }
}

/// The [`DIRECTIONS`] jittered projection directions, always the same.
pub fn directions() -> [Projection; DIRECTIONS] {
    const GOLDEN_ANGLE_RAD: f64 = 2.399_963_229_728_653;
    std::array::from_fn(|k| {
        let raw = match k {
            0 => Vector3::x(),
            1 => Vector3::y(),
            2 => Vector3::z(),
            _ => {
                // Fibonacci lattice on the upper hemisphere.
                let i = (k - 3) as f64 + 0.5;
                let z = 1.0 - i / SPREAD_DIRECTIONS as f64;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let phi = GOLDEN_ANGLE_RAD * i;
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            }
        };
        // A fixed, irrational-looking axis per direction; the turn is JITTER_RAD about it.
        let t = (k as f64 + 1.0) * 0.754_877_666_246_693;
        let axis = Vector3::new((7.3 * t).sin(), (5.1 * t + 1.0).cos(), (3.7 * t + 2.0).sin());
        let turn = Rotation3::from_scaled_axis(axis.normalize() * JITTER_RAD);
        Projection::new(Unit::new_normalize(turn * raw))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every projection basis is orthonormal and right-handed, no direction lies on an axis, and no two
    /// directions nearly coincide.
    #[test]
    fn bases_are_right_handed_and_directions_distinct() {
        let all = directions();
        for (k, p) in all.iter().enumerate() {
            let d = p.direction.into_inner();
            assert!((p.u.cross(&p.v) - d).norm() < 1e-12, "direction {k}");
            assert!(p.u.dot(&d).abs() < 1e-12 && (p.u.norm() - 1.0).abs() < 1e-12);
            // Jittered: no direction lies on an axis.
            assert!(d.iter().all(|c| c.abs() < 0.9999), "direction {k} is on an axis: {d:?}");
            for q in &all[..k] {
                assert!(d.dot(&q.direction).abs() < 0.99, "directions too close");
            }
        }
    }
}
