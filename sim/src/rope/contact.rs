//! Contacts between rope segments: capsules of the rope's radius round each segment, pushed apart
//! on positions, with Coulomb friction on the substep's relative tangential displacement (Macklin
//! et al. 2014: below `static_friction` times the push, the slip is undone entirely).

use nalgebra::Vector3;

use super::Ropes;

/// The closest points of segments `p0 p1` and `q0 q1`: their parameters (0 at the first end).
pub fn closest_on_segments(
    p0: &Vector3<f64>,
    p1: &Vector3<f64>,
    q0: &Vector3<f64>,
    q1: &Vector3<f64>,
) -> (f64, f64) {
    let d1 = p1 - p0;
    let d2 = q1 - q0;
    let r = p0 - q0;
    let a = d1.dot(&d1);
    let e = d2.dot(&d2);
    let f = d2.dot(&r);
    if a <= 1e-18 && e <= 1e-18 {
        return (0.0, 0.0);
    }
    if a <= 1e-18 {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = d1.dot(&r);
    if e <= 1e-18 {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = d1.dot(&d2);
    let denom = a * e - b * b;
    let mut s = if denom > 1e-18 * a * e { ((b * f - c * e) / denom).clamp(0.0, 1.0) } else { 0.0 };
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

/// Solves every candidate contact once; returns how many touched.
pub(super) fn solve_contacts(ropes: &mut Ropes, x_prev: &[Vector3<f64>]) -> usize {
    let two_r = 2.0 * ropes.params.radius_m;
    let (mu_s, mu_k) = (ropes.params.static_friction, ropes.params.kinetic_friction);
    let mut touching = 0;
    for k in 0..ropes.candidates.len() {
        let (i, j) = ropes.candidates[k];
        let ([a, b], _) = ropes.segments[i];
        let ([c, d], _) = ropes.segments[j];
        let (s, t) = closest_on_segments(&ropes.x[a], &ropes.x[b], &ropes.x[c], &ropes.x[d]);
        let p = ropes.x[a] * (1.0 - s) + ropes.x[b] * s;
        let q = ropes.x[c] * (1.0 - t) + ropes.x[d] * t;
        let delta = p - q;
        let dist = delta.norm();
        if dist >= two_r || dist < 1e-12 {
            continue;
        }
        touching += 1;
        let n = delta / dist;
        let weights = [(a, 1.0 - s), (b, s), (c, -(1.0 - t)), (d, -t)];
        let wsum: f64 = weights.iter().map(|(p, k)| ropes.w[*p] * k * k).sum();
        if wsum == 0.0 {
            continue;
        }
        let depth = two_r - dist;
        for (p, k) in weights {
            ropes.x[p] += n * (ropes.w[p] * k * depth / wsum);
        }
        // Friction: the contact points' relative displacement over the substep, across the normal.
        let moved = |p: usize| ropes.x[p] - x_prev[p];
        let rel = (moved(a) * (1.0 - s) + moved(b) * s) - (moved(c) * (1.0 - t) + moved(d) * t);
        let tangential = rel - n * rel.dot(&n);
        let slip = tangential.norm();
        if slip < 1e-15 {
            continue;
        }
        let undo = if slip < mu_s * depth { tangential } else { tangential * (mu_k * depth / slip).min(1.0) };
        for (p, k) in weights {
            ropes.x[p] -= undo * (ropes.w[p] * k / wsum);
        }
    }
    touching
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_segments_meet_at_their_crossing() {
        let (s, t) = closest_on_segments(
            &Vector3::new(-1.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(0.5, -1.0, 1.0),
            &Vector3::new(0.5, 3.0, 1.0),
        );
        assert!((s - 0.75).abs() < 1e-12, "s {s}");
        assert!((t - 0.25).abs() < 1e-12, "t {t}");
    }

    #[test]
    fn segments_apart_along_their_line_meet_at_their_near_ends() {
        let (s, t) = closest_on_segments(
            &Vector3::new(0.0, 0.0, 0.0),
            &Vector3::new(1.0, 0.0, 0.0),
            &Vector3::new(3.0, 0.0, 0.0),
            &Vector3::new(2.0, 0.0, 0.0),
        );
        assert_eq!((s, t), (1.0, 1.0));
    }

    #[test]
    fn parallel_segments_give_a_pair_of_points_a_common_normal_apart() {
        let (p0, p1) = (Vector3::new(0.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0));
        let (q0, q1) = (Vector3::new(1.0, 1.0, 0.0), Vector3::new(3.0, 1.0, 0.0));
        let (s, t) = closest_on_segments(&p0, &p1, &q0, &q1);
        let gap = (p0 + (p1 - p0) * s) - (q0 + (q1 - q0) * t);
        assert!((gap.norm() - 1.0).abs() < 1e-12, "closest points {gap:?} apart");
    }
}
