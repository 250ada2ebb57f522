//! The fluid solver's rules for obstacle cells, enforced by growing the mask (a virtual obstacle is
//! never removed): every obstacle cell has at least two direct obstacle neighbours, and no obstacle
//! cell has fluid on two opposite sides.
//!
//! Both rules hold exactly when every obstacle cell lies in a fully blocked 2 x 2 square of the grid
//! (such a cell has one blocked neighbour across and one along, so two neighbours and never fluid on
//! both sides of either line), so each blocked cell not yet in one gets the 2 x 2 square around it
//! that holds the most blocked cells already (ties: the square towards +i, +j first). One pass in
//! row-major order suffices: cells only get blocked, and every cell a square adds lies in that square.
//! Neighbours outside the grid do not count either way.

use super::mask::ObstacleMask;

/// Whether the 2 x 2 square with lower corner `(i, j)` lies in the grid and is fully blocked.
fn square_full(mask: &ObstacleMask, i: usize, j: usize) -> bool {
    i + 1 < mask.n && j + 1 < mask.n && (0..2).all(|dj| (0..2).all(|di| mask.get(i + di, j + dj)))
}

/// Lower corners of the in-grid 2 x 2 squares holding cell `(i, j)`, in the tie-breaking order.
fn squares_around(n: usize, i: usize, j: usize) -> impl Iterator<Item = (usize, usize)> {
    let is = [Some(i), i.checked_sub(1)];
    let js = [Some(j), j.checked_sub(1)];
    js.into_iter()
        .flat_map(move |cj| is.into_iter().map(move |ci| (ci, cj)))
        .filter_map(|(ci, cj)| Some((ci?, cj?)))
        .filter(move |(ci, cj)| ci + 1 < n && cj + 1 < n)
}

/// `mask` grown until it obeys the fluid solver's rules. Grids smaller than 2 x 2 come back unchanged.
pub fn apply_fluid_rules(mask: &ObstacleMask) -> ObstacleMask {
    let mut out = mask.clone();
    let n = out.n;
    if n < 2 {
        return out;
    }
    for j in 0..n {
        for i in 0..n {
            if !out.get(i, j) || squares_around(n, i, j).any(|(ci, cj)| square_full(&out, ci, cj)) {
                continue;
            }
            let mut best: Option<((usize, usize), usize)> = None;
            for (ci, cj) in squares_around(n, i, j) {
                let held = (0..2).flat_map(|dj| (0..2).map(move |di| (di, dj)));
                let count = held.filter(|&(di, dj)| out.get(ci + di, cj + dj)).count();
                if best.is_none_or(|(_, c)| count > c) {
                    best = Some(((ci, cj), count));
                }
            }
            if let Some(((ci, cj), _)) = best {
                for dj in 0..2 {
                    for di in 0..2 {
                        out.set(ci + di, cj + dj, true);
                    }
                }
            }
        }
    }
    out
}

/// Obstacle cells breaking the rules: fewer than two direct obstacle neighbours, or fluid on two
/// opposite sides (neighbours outside the grid count as neither).
pub fn fluid_rule_violations(mask: &ObstacleMask) -> Vec<(usize, usize)> {
    let n = mask.n;
    let mut bad = Vec::new();
    for j in 0..n {
        for i in 0..n {
            if !mask.get(i, j) {
                continue;
            }
            let cell = |di: isize, dj: isize| -> Option<bool> {
                let (x, y) = (i.checked_add_signed(di)?, j.checked_add_signed(dj)?);
                (x < n && y < n).then(|| mask.get(x, y))
            };
            let (l, r, d, u) = (cell(-1, 0), cell(1, 0), cell(0, -1), cell(0, 1));
            let blocked = [l, r, d, u].iter().filter(|c| **c == Some(true)).count();
            let fluid_across = l == Some(false) && r == Some(false);
            let fluid_along = d == Some(false) && u == Some(false);
            if blocked < 2 || fluid_across || fluid_along {
                bad.push((i, j));
            }
        }
    }
    bad
}
