//! Contacts between rope segments: capsules of the rope's radius round each segment, pushed apart
//! on positions, with Coulomb friction on the substep's relative tangential displacement (Macklin
//! et al. 2014: below `static_friction` times the push, the slip is undone entirely).

use knotlab_hw::geometry::segment_closest_parameters;
use nalgebra::Vector3;

use super::Ropes;

/// Solves every candidate contact once; returns how many touched.
pub(super) fn solve_contacts(ropes: &mut Ropes, x_prev: &[Vector3<f64>]) -> usize {
    let two_r = 2.0 * ropes.params.radius_m;
    let (mu_s, mu_k) = (ropes.params.static_friction, ropes.params.kinetic_friction);
    let mut touching = 0;
    for k in 0..ropes.candidates.len() {
        let (i, j) = ropes.candidates[k];
        let ([a, b], _) = ropes.segments[i];
        let ([c, d], _) = ropes.segments[j];
        let (s, t) = segment_closest_parameters(
            &ropes.x[a],
            &(ropes.x[b] - ropes.x[a]),
            &ropes.x[c],
            &(ropes.x[d] - ropes.x[c]),
        );
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
