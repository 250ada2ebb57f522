//! The rope's bending solved directly: the joints of each strand at once, as one linear system.
//!
//! Each joint's constraint `C = (x_c - x_b)/l2 - (x_b - x_a)/l1` is linear in the positions, so a
//! substep's implicit (XPBD) projection of all of a strand's joints together is the linear system
//! `(G W Gᵀ + α̃) λ = -C` with `Δx = W Gᵀ λ`, the same for each of the three coordinates. Neighbouring
//! joints share two particles and joints two apart share one, so the matrix is symmetric
//! pentadiagonal: an LDLᵀ factorisation solves it in time linear in the joints. A Gauss-Seidel pass
//! (one joint after another) reaches the same projection only when each joint's compliance
//! outweighs its particles' inverse masses; a stiff, finely divided rope (a 3-0 suture's EI over
//! particles a third of a millimetre apart) is several times too soft after one pass.

use nalgebra::Vector3;

use super::Bend;

/// The direct bending solve's working space and its factorisation (kept to spare allocating and
/// factoring it anew: the matrix depends on the particles' inverse masses only, the same in every
/// pass over a substep).
#[derive(Clone, Debug, Default)]
pub(super) struct Scratch {
    /// Each run of consecutive joints, as a range of joint indices, and whether its matrix could be
    /// factored.
    runs: Vec<(std::ops::Range<usize>, bool)>,
    /// The factorisation's pivots `D`, one a joint.
    pivot: Vec<f64>,
    /// `L`'s first and second subdiagonals, one entry a joint.
    l1: Vec<f64>,
    l2: Vec<f64>,
    /// The right-hand side, then the solution `λ`, of the run being solved.
    lambda: Vec<Vector3<f64>>,
}

/// Factors the matrix of every run of consecutive joints (a strand's: each joint's first particle
/// one after the previous joint's) of `joints` for the inverse masses `w`, into `scratch`, for
/// [`project`]. Returns false where a run's matrix is singular (a pivot not positive, as when a
/// joint's three particles are all pinned and it has no compliance): [`project`] leaves that run
/// as it is.
pub(super) fn factor(joints: &[Bend], w: &[f64], scratch: &mut Scratch) -> bool {
    let Scratch { runs, pivot, l1, l2, .. } = scratch;
    runs.clear();
    pivot.clear();
    l1.clear();
    l2.clear();
    let mut ok = true;
    let mut start = 0;
    while start < joints.len() {
        let mut end = start + 1;
        while end < joints.len() && joints[end].p[0] == joints[end - 1].p[0] + 1 {
            end += 1;
        }
        let factored = factor_run(&joints[start..end], w, pivot, l1, l2);
        // A run that could not be factored keeps its place in the joint-indexed entries.
        pivot.resize(end, 0.0);
        l1.resize(end, 0.0);
        l2.resize(end, 0.0);
        runs.push((start..end, factored));
        ok &= factored;
        start = end;
    }
    ok
}

/// Factors one run's pentadiagonal matrix `LDLᵀ`, pushing its pivots and subdiagonals. False where
/// a pivot is not positive.
fn factor_run(run: &[Bend], w: &[f64], pivot: &mut Vec<f64>, l1: &mut Vec<f64>, l2: &mut Vec<f64>) -> bool {
    let n = run.len();
    let first = pivot.len();
    // The matrix's diagonal, first and second off-diagonals: joints j and j+1 share particles
    // p[1], p[2] of j (p[0], p[1] of j+1); j and j+2 share p[2] of j (p[0] of j+2).
    let diag = |j: usize| {
        let b = &run[j];
        (0..3).map(|k| w[b.p[k]] * b.g[k] * b.g[k]).sum::<f64>() + b.compliance
    };
    let off1 = |j: usize| {
        let (a, b) = (&run[j], &run[j + 1]);
        w[a.p[1]] * a.g[1] * b.g[0] + w[a.p[2]] * a.g[2] * b.g[1]
    };
    let off2 = |j: usize| {
        let (a, b) = (&run[j], &run[j + 2]);
        w[a.p[2]] * a.g[2] * b.g[0]
    };
    for j in 0..n {
        let at = first + j;
        let mut d = diag(j);
        if j >= 1 {
            d -= l1[at - 1] * l1[at - 1] * pivot[at - 1];
        }
        if j >= 2 {
            d -= l2[at - 2] * l2[at - 2] * pivot[at - 2];
        }
        if !(d > 0.0 && d.is_finite()) {
            return false;
        }
        pivot.push(d);
        let e = if j + 1 < n { off1(j) } else { 0.0 };
        let coupled = if j >= 1 { l2[at - 1] * l1[at - 1] * pivot[at - 1] } else { 0.0 };
        l1.push((e - coupled) / d);
        l2.push(if j + 2 < n { off2(j) / d } else { 0.0 });
    }
    true
}

/// Projects every run of `joints` onto its constraints at once, with the matrices [`factor`] left
/// in `scratch` (for these joints and `w`), moving `x` by the inverse masses `w`; each joint's
/// multiplier is carried on in `lambda`. What a pinned particle (`w` 0) would have been moved by,
/// times its mass, is added to its entry of `pinned_pull` (as `x`). A run whose matrix could not be
/// factored is left as it was.
pub(super) fn project(
    joints: &[Bend],
    lambda: &mut [Vector3<f64>],
    x: &mut [Vector3<f64>],
    w: &[f64],
    scratch: &mut Scratch,
    pinned_pull: &mut [Vector3<f64>],
) {
    let Scratch { runs, pivot, l1, l2, lambda: solution } = scratch;
    debug_assert_eq!(pivot.len(), joints.len(), "the joints' matrices factored for other joints");
    for (range, factored) in runs.iter() {
        if *factored {
            let r = range.clone();
            let factors = (&pivot[r.clone()], &l1[r.clone()], &l2[r.clone()]);
            project_run(&joints[r.clone()], &mut lambda[r], factors, x, w, solution, pinned_pull);
        }
    }
}

/// Projects one run of consecutive joints with its factorisation `(D, L's first subdiagonal, its
/// second)`.
fn project_run(
    run: &[Bend],
    total: &mut [Vector3<f64>],
    (pivot, l1, l2): (&[f64], &[f64], &[f64]),
    x: &mut [Vector3<f64>],
    w: &[f64],
    lambda: &mut Vec<Vector3<f64>>,
    pinned_pull: &mut [Vector3<f64>],
) {
    let n = run.len();
    lambda.clear();
    // Forward: L y = -(C + α̃ λ); then z = y / D; back: Lᵀ Δλ = z.
    for j in 0..n {
        let b = &run[j];
        let [pa, pb, pc] = b.p;
        let turn = (x[pc] - x[pb]) / b.l2 - (x[pb] - x[pa]) / b.l1;
        let mut y = -(turn + total[j] * b.compliance);
        if j >= 1 {
            y -= lambda[j - 1] * l1[j - 1];
        }
        if j >= 2 {
            y -= lambda[j - 2] * l2[j - 2];
        }
        lambda.push(y);
    }
    for j in 0..n {
        lambda[j] /= pivot[j];
    }
    for j in (0..n).rev() {
        let mut z = lambda[j];
        if j + 1 < n {
            z -= lambda[j + 1] * l1[j];
        }
        if j + 2 < n {
            z -= lambda[j + 2] * l2[j];
        }
        lambda[j] = z;
    }
    for ((b, l), total) in run.iter().zip(lambda.iter()).zip(total.iter_mut()) {
        *total += l;
        for (p, g) in b.p.into_iter().zip(b.g) {
            if w[p] == 0.0 {
                pinned_pull[p] += l * g;
            }
            x[p] += l * (w[p] * g);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rope::{RopeParams, Ropes};

    /// A rope whose joints are stiff against its particles' inverse masses.
    fn stiff_rope(direct: bool) -> Ropes {
        let params = RopeParams {
            bending_stiffness_n_m2: 5e-7,
            mass_per_m_kg: 0.67,
            substeps: 1,
            direct_bending: direct,
            ..RopeParams::default()
        };
        let mut ropes = Ropes::new(params);
        let points: Vec<_> = (0..30).map(|k| Vector3::new(3.4e-4 * k as f64, 0.0, 0.0)).collect();
        ropes.add_strand(&points);
        ropes
    }

    /// Guards the solve: after one direct projection of a bent strand, every joint's constraint
    /// holds its implicit balance `C + α̃ λ = 0`, checked by solving again from the result (a second
    /// projection moves the particles by no more than rounding), where one Gauss-Seidel pass leaves
    /// the joints far from it.
    #[test]
    fn one_direct_projection_is_the_fixed_point_a_gauss_seidel_pass_is_not() {
        for (direct, settled) in [(true, true), (false, false)] {
            let mut ropes = stiff_rope(direct);
            for (k, x) in ropes.x.iter_mut().enumerate() {
                x.z = 1e-4 * ((k as f64) * 0.7).sin();
            }
            // No compliance: the fixed point is the straight strand, so a second projection moves
            // nothing once the first has straightened it.
            ropes.params.bending_stiffness_n_m2 = f64::INFINITY;
            ropes.start_bending(1e-3);
            ropes.solve_bending();
            let once = ropes.x.clone();
            ropes.start_bending(1e-3);
            ropes.solve_bending();
            let moved = ropes.x.iter().zip(&once).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
            assert_eq!(moved < 1e-12, settled, "direct {direct}: moved {moved:e} m");
        }
    }

    /// Guards the pentadiagonal solve against a dense one: the λ it applies are the dense system's.
    #[test]
    fn the_direct_projection_matches_a_dense_solve() {
        let mut ropes = stiff_rope(true);
        for (k, x) in ropes.x.iter_mut().enumerate() {
            x.y = 2e-4 * ((k as f64) * 1.3).cos();
        }
        ropes.w[0] = 0.0;
        ropes.w[1] = 0.0;
        let h = 1e-3 / 3.0;
        ropes.bends = super::super::Bends::new(&ropes, h, (0, 0, 0));
        let joints = ropes.bends.joints.clone();
        let before = ropes.x.clone();
        let n = joints.len();
        let mut a = nalgebra::DMatrix::<f64>::zeros(n, n);
        let mut rhs = nalgebra::DMatrix::<f64>::zeros(n, 3);
        for (i, bi) in joints.iter().enumerate() {
            for (j, bj) in joints.iter().enumerate() {
                for (ki, pi) in bi.p.iter().enumerate() {
                    for (kj, pj) in bj.p.iter().enumerate() {
                        if pi == pj {
                            a[(i, j)] += ropes.w[*pi] * bi.g[ki] * bj.g[kj];
                        }
                    }
                }
            }
            a[(i, i)] += bi.compliance;
            let [pa, pb, pc] = bi.p;
            let turn = (before[pc] - before[pb]) / bi.l2 - (before[pb] - before[pa]) / bi.l1;
            for c in 0..3 {
                rhs[(i, c)] = -turn[c];
            }
        }
        let lambda = a.lu().solve(&rhs).expect("the dense system");
        let mut expected = before.clone();
        for (i, b) in joints.iter().enumerate() {
            for (p, g) in b.p.into_iter().zip(b.g) {
                for c in 0..3 {
                    expected[p][c] += lambda[(i, c)] * ropes.w[p] * g;
                }
            }
        }
        let mut scratch = Scratch::default();
        let mut lambda = vec![Vector3::zeros(); n];
        let mut pull = vec![Vector3::zeros(); ropes.x.len()];
        assert!(factor(&joints, &ropes.w, &mut scratch));
        project(&joints, &mut lambda, &mut ropes.x, &ropes.w, &mut scratch, &mut pull);
        let worst = ropes.x.iter().zip(&expected).map(|(a, b)| (a - b).norm()).fold(0.0, f64::max);
        assert!(worst < 1e-12, "differs from the dense solve by {worst:e} m");
    }
}
