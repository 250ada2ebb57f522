//! Grid geometry shared by the stirring and the particle tracing: the cells a segment passes through and
//! distances from points to cells.

use nalgebra::Vector2;

/// Visits, in order, every cell `(i, j)` (cell `(i, j)` covers `[i h, (i + 1) h) x [j h, (j + 1) h)` in
/// grid coordinates) that the segment from `a` to `b` passes through; where it passes exactly through a
/// cell corner both side cells are visited too. Stops and returns `false` as soon as `visit` does;
/// returns `true` when every cell was visited. Non-finite input visits nothing and returns `false`.
pub fn cells_on_segment(
    a: Vector2<f64>,
    b: Vector2<f64>,
    h_m: f64,
    mut visit: impl FnMut(isize, isize) -> bool,
) -> bool {
    let (a, b) = (a / h_m, b / h_m);
    if !(a.iter().chain(b.iter()).all(|x| x.is_finite())) {
        return false;
    }
    let (mut i, mut j) = (a.x.floor() as isize, a.y.floor() as isize);
    let (end_i, end_j) = (b.x.floor() as isize, b.y.floor() as isize);
    let d = b - a;
    let step_i: isize = if d.x > 0.0 { 1 } else { -1 };
    let step_j: isize = if d.y > 0.0 { 1 } else { -1 };
    let t_delta_x = if d.x != 0.0 { (1.0 / d.x).abs() } else { f64::INFINITY };
    let t_delta_y = if d.y != 0.0 { (1.0 / d.y).abs() } else { f64::INFINITY };
    let next_x = if d.x > 0.0 { (i + 1) as f64 } else { i as f64 };
    let next_y = if d.y > 0.0 { (j + 1) as f64 } else { j as f64 };
    let mut t_max_x = if d.x != 0.0 { (next_x - a.x) / d.x } else { f64::INFINITY };
    let mut t_max_y = if d.y != 0.0 { (next_y - a.y) / d.y } else { f64::INFINITY };
    let limit = (end_i - i).abs() + (end_j - j).abs() + 2;
    if !visit(i, j) {
        return false;
    }
    for _ in 0..limit {
        if i == end_i && j == end_j {
            return true;
        }
        let tie = (t_max_x - t_max_y).abs() <= 1e-12;
        if tie {
            if t_max_x > 1.0 {
                return true;
            }
            if !visit(i + step_i, j) || !visit(i, j + step_j) {
                return false;
            }
            i += step_i;
            j += step_j;
            t_max_x += t_delta_x;
            t_max_y += t_delta_y;
        } else if t_max_x < t_max_y {
            if t_max_x > 1.0 {
                return true;
            }
            i += step_i;
            t_max_x += t_delta_x;
        } else {
            if t_max_y > 1.0 {
                return true;
            }
            j += step_j;
            t_max_y += t_delta_y;
        }
        if !visit(i, j) {
            return false;
        }
    }
    true
}

/// Distance from `p` to the closed cell `(i, j)` of side `h_m` (0 inside), m.
pub fn distance_to_cell(p: Vector2<f64>, i: isize, j: isize, h_m: f64) -> f64 {
    let (x0, y0) = (i as f64 * h_m, j as f64 * h_m);
    let dx = (x0 - p.x).max(p.x - (x0 + h_m)).max(0.0);
    let dy = (y0 - p.y).max(p.y - (y0 + h_m)).max(0.0);
    dx.hypot(dy)
}

/// The point of the cell `(i, j)` nearest to `p`, kept `inset` cell sides inside its edges, m.
pub fn nearest_in_cell(p: Vector2<f64>, i: isize, j: isize, h_m: f64, inset: f64) -> Vector2<f64> {
    let lo = Vector2::new(i as f64 + inset, j as f64 + inset) * h_m;
    let hi = Vector2::new((i + 1) as f64 - inset, (j + 1) as f64 - inset) * h_m;
    Vector2::new(p.x.clamp(lo.x, hi.x), p.y.clamp(lo.y, hi.y))
}
