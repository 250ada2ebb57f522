//! The rope's inextensibility solved directly along each strand: the segments' length constraints,
//! linearised, make a tridiagonal system in their multipliers (each constraint shares one particle
//! with each neighbour), solved exactly in one sweep each way (Thomas's algorithm) instead of by
//! Gauss-Seidel, whose error along a chain grows with its length and with the pull on a light
//! particle (Goldenthal et al. 2007, fast projection).

use nalgebra::Vector3;

/// Working space for [`project_strand`], kept between calls to spare allocating it.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    dir: Vec<Vector3<f64>>,
    lambda: Vec<f64>,
    c_prime: Vec<f64>,
    /// Each particle's move times its mass.
    push: Vec<Vector3<f64>>,
}

/// Projects the strand `x` (its particles, in order; `w` their inverse masses, `rest_m` the rest
/// length of each segment) once towards every segment at its rest length, moving the particles
/// as little as their masses allow; with `compliance_per_m` > 0 each segment is a compliant XPBD
/// constraint of compliance (over the substep) `rest_m * compliance_per_m`, 1/kg, and gives way
/// to a pull as a spring would.
/// `multipliers` (one a segment, as `rest_m`) carries each segment's multiplier over the passes of a substep
/// (XPBD's accumulated `λ`, zero at the substep's start): each projection moves them on, so that
/// passes converge on the substep's implicit step instead of stiffening the compliant lengths
/// pass by pass.
/// What a pinned particle (`w` 0) would have been moved by, times its mass (kg m: the pull on
/// what pins it, times the substep squared), is added to its entry of `pinned_pull` (as `x`).
/// Returns false, moving nothing, where the system is singular (a denominator vanished, a
/// multiplier came out non-finite, or a particle would move ten segments' lengths or more);
/// the caller then falls back to Gauss-Seidel.
///
/// The system, row `k` the segment `k`: `diag_k = w_k + w_k+1` (plus its compliance), the
/// off-diagonal between `k` and `k + 1` `-w_k+1 (dir_k . dir_k+1)`, the right-hand side the
/// segment's stretch. Each row is assembled and eliminated as soon as its successor's direction is
/// known, in one sweep; then one sweep back gives the multipliers.
pub fn project_strand(
    x: &mut [Vector3<f64>],
    w: &[f64],
    rest_m: &[f64],
    compliance_per_m: f64,
    multipliers: &mut [f64],
    scratch: &mut Scratch,
    pinned_pull: &mut [Vector3<f64>],
) -> bool {
    let n = rest_m.len();
    if n == 0 {
        return true;
    }
    let Scratch { dir, lambda, c_prime, push } = scratch;
    dir.clear();
    lambda.clear();
    c_prime.clear();
    push.clear();
    // Row k's diagonal and right-hand side, a row with both ends pinned (nothing can move, its
    // multiplier zero) made the identity.
    let row = |k: usize, len: f64| {
        let compliance = rest_m[k] * compliance_per_m;
        let diag = w[k] + w[k + 1] + compliance;
        if diag == 0.0 { (1.0, 0.0) } else { (diag, -(len - rest_m[k]) - compliance * multipliers[k]) }
    };
    // The row waiting for its successor's direction: its diagonal, right-hand side and the
    // off-diagonal to its predecessor (0 for the first).
    let mut pending = (0.0, 0.0, 0.0);
    // How far the strand's lengths are off, in all, m.
    let mut off_m = 0.0;
    for k in 0..n {
        let d = x[k + 1] - x[k];
        let len = d.norm();
        off_m += (len - rest_m[k]).abs();
        dir.push(if len > 1e-15 { d / len } else { Vector3::x() });
        let (diag, rhs) = row(k, len);
        if k == 0 {
            pending = (diag, rhs, 0.0);
            continue;
        }
        // Row k - 1 is complete: eliminate it (forward elimination, Thomas's algorithm).
        let off = -w[k] * dir[k - 1].dot(&dir[k]);
        let (prev_diag, prev_rhs, lower) = pending;
        eliminate(c_prime, lambda, prev_diag, prev_rhs, lower, Some(off));
        pending = (diag, rhs, off);
    }
    let (last_diag, last_rhs, lower) = pending;
    eliminate(c_prime, lambda, last_diag, last_rhs, lower, None);
    // Back substitution: the multipliers.
    let mut finite = lambda[n - 1].is_finite();
    for k in (0..n - 1).rev() {
        lambda[k] -= c_prime[k] * lambda[k + 1];
        finite &= lambda[k].is_finite();
    }
    if !finite {
        return false;
    }
    // dx_i = w_i (grad_i C_(i-1) lambda_(i-1) + grad_i C_i lambda_i), grad_i C_i = -dir_i,
    // grad_(i+1) C_i = dir_i.
    push.extend((0..=n).map(|i| {
        let mut push = Vector3::zeros();
        if i < n {
            push -= dir[i] * lambda[i];
        }
        if i > 0 {
            push += dir[i - 1] * lambda[i - 1];
        }
        push
    }));
    // Near singular (a straight strand drawn taut between two pinned particles), the multipliers
    // are finite but would throw a particle ten segments' lengths or more beyond what the
    // strand's lengths are off by in all (a light particle flung metres by a pull is put back by
    // that much): refused as singular.
    let most_m = 10.0 * rest_m.iter().copied().fold(0.0, f64::max) + 2.0 * off_m;
    if push.iter().zip(w).any(|(push, w)| (push * *w).norm() > most_m) {
        return false;
    }
    for (i, push) in push.iter().enumerate() {
        if w[i] == 0.0 {
            pinned_pull[i] += push;
        }
        x[i] += push * w[i];
    }
    for (total, step) in multipliers.iter_mut().zip(lambda.iter()) {
        *total += step;
    }
    true
}

/// One row of the forward elimination: the row `diag`, `rhs`, its off-diagonal to the row before,
/// `lower` (the first row has none; it is not used there), and to the row after, `upper` (`None`
/// for the last row). Pushes the row's `c'` and `d'`.
fn eliminate(
    c_prime: &mut Vec<f64>,
    d_prime: &mut Vec<f64>,
    diag: f64,
    rhs: f64,
    lower: f64,
    upper: Option<f64>,
) {
    let (denom, rhs) = match (c_prime.last(), d_prime.last()) {
        (Some(&c_before), Some(&d_before)) => (diag - lower * c_before, rhs - lower * d_before),
        _ => (diag, rhs),
    };
    c_prime.push(upper.map_or(0.0, |upper| upper / denom));
    d_prime.push(rhs / denom);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A stretched chain with its first particle pinned comes back to its rest lengths within 1e-12 in five
    /// projections, the pinned particle unmoved.
    #[test]
    fn a_stretched_chain_is_put_back_to_its_lengths() {
        // Five particles along x, every segment stretched from 1 to 1.2; the first pinned.
        let mut x: Vec<Vector3<f64>> =
            (0..5).map(|i| Vector3::new(1.2 * i as f64, 0.1 * (i % 2) as f64, 0.0)).collect();
        let w = [0.0, 1.0, 1.0, 1.0, 1.0];
        let rest = [1.0; 4];
        // Newton's method: the error falls 0.11, 0.021, 6e-4, 4e-7, 2e-13.
        for _ in 0..5 {
            assert!(project_strand(
                &mut x,
                &w,
                &rest,
                0.0,
                &mut [0.0; 4],
                &mut Scratch::default(),
                &mut [Vector3::zeros(); 5]
            ));
        }
        assert_eq!(x[0], Vector3::zeros());
        for k in 0..4 {
            let len = (x[k + 1] - x[k]).norm();
            assert!((len - 1.0).abs() < 1e-12, "segment {k} is {len} long");
        }
    }

    /// A single free segment is put back in one projection, its two ends sharing the move, and a segment with
    /// both ends pinned stays put while the free ones after it are restored.
    #[test]
    fn one_segment_is_put_back_at_once_and_a_pinned_one_stays() {
        // One segment (the first row is also the last): its two ends share the correction.
        let mut x = vec![Vector3::zeros(), Vector3::new(1.5, 0.0, 0.0)];
        assert!(project_strand(
            &mut x,
            &[1.0, 1.0],
            &[1.0],
            0.0,
            &mut [0.0; 1],
            &mut Scratch::default(),
            &mut [Vector3::zeros(); 2]
        ));
        assert!((x[0].x - 0.25).abs() < 1e-12 && (x[1].x - 1.25).abs() < 1e-12, "{x:?}");
        // The first segment's both ends pinned (its row the identity), the rest free.
        let mut x: Vec<Vector3<f64>> = (0..4).map(|i| Vector3::new(1.2 * i as f64, 0.0, 0.0)).collect();
        let pinned = [x[0], x[1]];
        let mut scratch = Scratch::default();
        for _ in 0..3 {
            assert!(project_strand(
                &mut x,
                &[0.0, 0.0, 1.0, 1.0],
                &[1.0; 3],
                0.0,
                &mut [0.0; 3],
                &mut scratch,
                &mut [Vector3::zeros(); 4]
            ));
        }
        assert_eq!([x[0], x[1]], pinned);
        for k in 1..3 {
            let len = (x[k + 1] - x[k]).norm();
            assert!((len - 1.0).abs() < 1e-12, "segment {k} is {len} long");
        }
    }

    /// A strand whose system is singular (both ends pinned, all in line, too long) is refused, nothing moved.
    #[test]
    fn a_singular_strand_is_refused_and_left_where_it_is() {
        // Both ends pinned, the middle free, all on one line and too long: no move of the middle
        // shortens both segments (the second row's pivot vanishes); the projection refuses, moving
        // nothing, and the caller falls back to Gauss-Seidel.
        let mut x: Vec<Vector3<f64>> = (0..3).map(|i| Vector3::new(1.2 * i as f64, 0.0, 0.0)).collect();
        let before = x.clone();
        let ok = project_strand(
            &mut x,
            &[0.0, 1.0, 0.0],
            &[1.0, 1.0],
            0.0,
            &mut [0.0; 2],
            &mut Scratch::default(),
            &mut [Vector3::zeros(); 3],
        );
        assert!(!ok, "a singular system was projected: {x:?}");
        assert_eq!(x, before, "a refused projection moved the strand");
    }

    /// A pinned particle does not move, and the pull on it is what the projection would have moved it
    /// by times its mass: for one segment stretched by 0.5 from a pin to a particle of unit mass, 0.5
    /// along the segment, towards the particle.
    #[test]
    fn the_pull_on_a_pinned_particle_is_the_correction_it_was_spared() {
        let mut x = vec![Vector3::zeros(), Vector3::new(1.5, 0.0, 0.0)];
        let mut pull = [Vector3::zeros(); 2];
        assert!(project_strand(
            &mut x,
            &[0.0, 1.0],
            &[1.0],
            0.0,
            &mut [0.0; 2],
            &mut Scratch::default(),
            &mut pull
        ));
        assert_eq!(x[0], Vector3::zeros());
        assert!((x[1].x - 1.0).abs() < 1e-12, "{x:?}");
        assert!((pull[0] - Vector3::new(0.5, 0.0, 0.0)).norm() < 1e-12, "{pull:?}");
        assert_eq!(pull[1], Vector3::zeros(), "a free particle has no pull");
    }

    /// A strand drawn taut between two pins, its middle 0.1 mm off their line, is so near singular that
    /// the projection would throw the middle 2.4 km across it: refused, nothing moved.
    #[test]
    fn a_nearly_singular_strand_is_refused_rather_than_thrown() {
        let mut x = vec![Vector3::zeros(), Vector3::new(1.2, 1e-4, 0.0), Vector3::new(2.4, 0.0, 0.0)];
        let before = x.clone();
        let mut pull = [Vector3::zeros(); 3];
        let ok = project_strand(
            &mut x,
            &[0.0, 1.0, 0.0],
            &[1.0, 1.0],
            0.0,
            &mut [0.0; 2],
            &mut Scratch::default(),
            &mut pull,
        );
        assert!(!ok, "a nearly singular system was projected: {x:?}");
        assert_eq!(x, before, "a refused projection moved the strand");
        assert_eq!(pull, [Vector3::zeros(); 3], "a refused projection summed a pull");
    }
}
