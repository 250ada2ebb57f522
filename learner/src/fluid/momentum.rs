//! The momentum step (Griebel et al., sections 3.1.3 to 3.2.4): the intermediate velocities F and G with
//! donor-cell convection, the right-hand side of the pressure equation, the pressure correction of the
//! velocities, and the discrete divergence.

use super::flags::Flags;

/// How the convective terms mix central differences and donor cell (eq. 3.19 and 3.20).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mixing {
    /// One gamma for every flux.
    Global(f64),
    /// Per flux, `gamma = min(1, factor |w| dt / h)` with `w` the velocity carrying the flux: the book's
    /// stability condition applied where it arises. With factor 1 the upwind diffusion is `w^2 dt / 2`,
    /// which cancels the anti-diffusion of the explicit Euler step (as in Lax-Wendroff), instead of
    /// `gamma |w| h / 2`.
    Local {
        /// `factor dt / h`, s/m.
        factor_dt_per_h: f64,
    },
}

impl Mixing {
    /// The upwind weight of a flux carried by `twice_w` (twice the velocity at the flux point): `gamma`
    /// times `|twice_w|`.
    #[inline]
    fn upwind(self, twice_w: f64) -> f64 {
        match self {
            Mixing::Global(gamma) => gamma * twice_w.abs(),
            Mixing::Local { factor_dt_per_h } => {
                (0.5 * factor_dt_per_h * twice_w.abs()).min(1.0) * twice_w.abs()
            }
        }
    }
}

/// The intermediate velocities `F = u + dt (nu lap(u) - d(u^2)/dx - d(uv)/dy)` and the like `G`, on every
/// face between two fluid cells; elsewhere `F = u`, `G = v` (so walls and obstacles pass no fluid).
/// Convection mixes central differences and donor cell as `mixing` says (eq. 3.19 and 3.20).
///
/// Rows are computed whole on equal-length slices (which the compiler vectorizes), then the faces that
/// are not between two fluid cells get `F = u`, `G = v` back.
#[allow(clippy::too_many_arguments)]
pub fn compute_fg(
    flags: &Flags,
    u: &[f64],
    v: &[f64],
    nu: f64,
    mixing: Mixing,
    dt: f64,
    f: &mut [f64],
    g: &mut [f64],
) {
    let grid = flags.grid;
    let (n, h, s) = (grid.n, grid.h_m, grid.stride());
    let c = Coefficients { nu_inv_h2: nu / (h * h), q: 0.25 / h, dt, mixing };
    f.copy_from_slice(u);
    g.copy_from_slice(v);
    for j in 1..=n {
        let row = j * s;
        // u faces i = 1..n-1 of row j: centre, east, west, north, south; v at k, k+1, k-s, k-s+1.
        let r = |offset: isize| {
            let start = (row as isize + 1 + offset) as usize;
            &u[start..start + n - 1]
        };
        let w = |offset: isize| {
            let start = (row as isize + 1 + offset) as usize;
            &v[start..start + n - 1]
        };
        let s_ = s as isize;
        f_row(
            &mut f[row + 1..row + n],
            [r(0), r(1), r(-1), r(s_), r(-s_)],
            [w(0), w(1), w(-s_), w(-s_ + 1)],
            &c,
        );
    }
    for j in 1..n {
        let row = j * s;
        let r = |offset: isize| {
            let start = (row as isize + 1 + offset) as usize;
            &v[start..start + n]
        };
        let w = |offset: isize| {
            let start = (row as isize + 1 + offset) as usize;
            &u[start..start + n]
        };
        let s_ = s as isize;
        // v faces i = 1..n of row j: centre, north, south, east, west (the roles of x and y swapped);
        // u at k, k+s, k-1, k-1+s.
        f_row(
            &mut g[row + 1..row + n + 1],
            [r(0), r(s_), r(-s_), r(1), r(-1)],
            [w(0), w(s_), w(-1), w(s_ - 1)],
            &c,
        );
    }
    for &k in &flags.u_solid {
        f[k] = u[k];
    }
    for &k in &flags.v_solid {
        g[k] = v[k];
    }
}

/// Constants of one momentum step.
struct Coefficients {
    nu_inv_h2: f64,
    q: f64,
    dt: f64,
    mixing: Mixing,
}

/// One row of `F` (or of `G` with x and y swapped): `w` is the component itself at the face and its
/// neighbours along (`a`, `b`) and across (`c`, `d`) its direction; `t` the other component at the four
/// faces around (`t0 + t1` carries the flux on the `c` side, `t2 + t3` on the `d` side).
fn f_row(out: &mut [f64], w: [&[f64]; 5], t: [&[f64]; 4], c: &Coefficients) {
    let len = out.len();
    let [wc, wa, wb, wn, ws] = w.map(|x| &x[..len]);
    let [t0, t1, t2, t3] = t.map(|x| &x[..len]);
    let q = c.q;
    for i in 0..len {
        let (uc, ue, uw, un, us) = (wc[i], wa[i], wb[i], wn[i], ws[i]);
        let lap = ue + uw + un + us - 4.0 * uc;
        let (a, b) = (uc + ue, uw + uc);
        let along =
            q * (a * a - b * b) + q * (c.mixing.upwind(a) * (uc - ue) - c.mixing.upwind(b) * (uw - uc));
        let (vn, vs) = (t0[i] + t1[i], t2[i] + t3[i]);
        let across = q * (vn * (uc + un) - vs * (us + uc))
            + q * (c.mixing.upwind(vn) * (uc - un) - c.mixing.upwind(vs) * (us - uc));
        out[i] = uc + c.dt * (c.nu_inv_h2 * lap - along - across);
    }
}

/// The right-hand side of the pressure equation in every fluid cell, `div(F, G) / dt` (eq. 3.38), 1/s^2;
/// zero elsewhere.
pub fn compute_rhs(flags: &Flags, f: &[f64], g: &[f64], dt: f64, rhs: &mut [f64]) {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let c = 1.0 / (grid.h_m * dt);
    rhs.fill(0.0);
    for j in 1..=n {
        let k = j * s + 1;
        let out = &mut rhs[k..k + n];
        let (fe, fw, gn, gs, w) = (
            &f[k..k + n],
            &f[k - 1..k - 1 + n],
            &g[k..k + n],
            &g[k - s..k - s + n],
            &flags.fluid_weight[k..k + n],
        );
        for i in 0..n {
            out[i] = w[i] * c * ((fe[i] - fw[i]) + (gn[i] - gs[i]));
        }
    }
}

/// The pressure correction (eq. 3.34 and 3.35): `u = F - dt dp/dx`, `v = G - dt dp/dy` on every face
/// between two fluid cells (the other faces keep their velocity, which `F` and `G` hold).
pub fn correct_velocities(
    flags: &Flags,
    f: &[f64],
    g: &[f64],
    p: &[f64],
    dt: f64,
    u: &mut [f64],
    v: &mut [f64],
) {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let c = dt / grid.h_m;
    for j in 1..=n {
        let k = j * s + 1;
        let (out, fk, pe, pc) = (&mut u[k..k + n - 1], &f[k..k + n - 1], &p[k + 1..k + n], &p[k..k + n - 1]);
        for i in 0..n - 1 {
            out[i] = fk[i] - c * (pe[i] - pc[i]);
        }
    }
    for j in 1..n {
        let k = j * s + 1;
        let (out, gk, pn, pc) = (&mut v[k..k + n], &g[k..k + n], &p[k + s..k + s + n], &p[k..k + n]);
        for i in 0..n {
            out[i] = gk[i] - c * (pn[i] - pc[i]);
        }
    }
    for &k in &flags.u_solid {
        u[k] = f[k];
    }
    for &k in &flags.v_solid {
        v[k] = g[k];
    }
}

/// The largest change between `old` and `new` velocities over the interior faces, m/s.
pub fn max_change(flags: &Flags, u_old: &[f64], v_old: &[f64], u: &[f64], v: &[f64]) -> f64 {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let mut change = 0.0f64;
    for j in 1..=n {
        let k = j * s + 1;
        for (a, b) in u[k..k + n - 1].iter().zip(&u_old[k..k + n - 1]) {
            change = change.max((a - b).abs());
        }
        if j < n {
            for (a, b) in v[k..k + n].iter().zip(&v_old[k..k + n]) {
                change = change.max((a - b).abs());
            }
        }
    }
    change
}

/// The largest discrete divergence `|du/dx + dv/dy|` over the fluid cells, 1/s (NaN if a velocity
/// next to a fluid cell is not finite).
pub fn max_divergence(flags: &Flags, u: &[f64], v: &[f64]) -> f64 {
    let grid = flags.grid;
    let (n, s) = (grid.n, grid.stride());
    let inv_h = 1.0 / grid.h_m;
    let mut worst = 0.0f64;
    for j in 1..=n {
        let k = j * s + 1;
        let (ue, uw, vn, vs, w) = (
            &u[k..k + n],
            &u[k - 1..k - 1 + n],
            &v[k..k + n],
            &v[k - s..k - s + n],
            &flags.fluid_weight[k..k + n],
        );
        for i in 0..n {
            let div = w[i] * inv_h * ((ue[i] - uw[i]) + (vn[i] - vs[i]));
            if div.is_nan() {
                return f64::NAN;
            }
            worst = worst.max(div.abs());
        }
    }
    worst
}
