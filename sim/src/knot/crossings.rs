//! Crossings of a closed picture: every pair of non-adjacent segments whose projections intersect, with
//! which one passes over (the higher along the view direction) and the crossing's sign.

use super::closure::ClosedPicture;

/// Where a crossing's strand passes, as a position along the closed curve: segment index plus the
/// fraction along it (`3.25` is a quarter of the way along segment 3).
pub type CurvePosition = f64;

/// One crossing of a picture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Where the over strand passes.
    pub over_at: CurvePosition,
    /// Where the under strand passes.
    pub under_at: CurvePosition,
    /// +1 for a right-handed crossing, -1 for a left-handed one: the sign of
    /// `cross(over direction, under direction)` in the picture plane, viewed from the viewer's side.
    pub sign: i8,
}

/// Relative size below which two projected segments count as parallel (no crossing).
const PARALLEL_EPS: f64 = 1e-14;

/// All crossings of a closed picture, found by a sweep over the segments' x extents.
pub fn find_crossings(picture: &ClosedPicture) -> Vec<Crossing> {
    let m = picture.segments();
    let xy = &picture.xy;
    let end = |i: usize| if i + 1 == m { 0 } else { i + 1 };
    // Bounding boxes, segments ordered by their smallest x.
    let boxes: Vec<[f64; 4]> = (0..m)
        .map(|i| {
            let (a, b) = (xy[i], xy[end(i)]);
            [a[0].min(b[0]), a[0].max(b[0]), a[1].min(b[1]), a[1].max(b[1])]
        })
        .collect();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_unstable_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]));
    let mut crossings = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        let bi = boxes[i];
        for &j in &order[k + 1..] {
            let bj = boxes[j];
            if bj[0] > bi[1] {
                break;
            }
            if bj[2] > bi[3] || bj[3] < bi[2] {
                continue;
            }
            let adjacent = end(i) == j || end(j) == i;
            if adjacent {
                continue;
            }
            if let Some(c) = intersect(picture, i, end(i), j, end(j)) {
                crossings.push(c);
            }
        }
    }
    crossings
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The crossing of segments `i -> i1` and `j -> j1`, if their projections meet. Both parameters are
/// taken half-open, `[0, 1)`, so a strand through a shared vertex is counted once.
fn intersect(picture: &ClosedPicture, i: usize, i1: usize, j: usize, j1: usize) -> Option<Crossing> {
    let (p, q) = (picture.xy[i], picture.xy[j]);
    let r = [picture.xy[i1][0] - p[0], picture.xy[i1][1] - p[1]];
    let s = [picture.xy[j1][0] - q[0], picture.xy[j1][1] - q[1]];
    let denom = cross(r, s);
    let scale = (r[0].abs() + r[1].abs()) * (s[0].abs() + s[1].abs());
    if denom.abs() <= PARALLEL_EPS * scale || scale == 0.0 {
        return None;
    }
    let qp = [q[0] - p[0], q[1] - p[1]];
    let t_i = cross(qp, s) / denom;
    let t_j = cross(qp, r) / denom;
    if !(0.0..1.0).contains(&t_i) || !(0.0..1.0).contains(&t_j) {
        return None;
    }
    let h = &picture.height;
    let h_i = h[i] + t_i * (h[i1] - h[i]);
    let h_j = h[j] + t_j * (h[j1] - h[j]);
    let (at_i, at_j) = (i as f64 + t_i, j as f64 + t_j);
    Some(if h_i >= h_j {
        Crossing { over_at: at_i, under_at: at_j, sign: if cross(r, s) > 0.0 { 1 } else { -1 } }
    } else {
        Crossing { over_at: at_j, under_at: at_i, sign: if cross(s, r) > 0.0 { 1 } else { -1 } }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square drawn with one segment pair crossing: 0(0,0) 1(2,2) 2(2,0) 3(0,2), closed.
    fn bow_tie(h: [f64; 4]) -> ClosedPicture {
        ClosedPicture {
            xy: vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]],
            height: h.to_vec(),
            thread_points: 4,
        }
    }

    /// A single crossing is found with the right strand over and a right-handed sign; raising the other
    /// strand swaps over and under and makes it left-handed.
    #[test]
    fn one_crossing_with_over_under_and_sign() {
        // Segment 0 goes up-right, segment 2 goes up-left (from (2,0) to (0,2)).
        let c = find_crossings(&bow_tie([1.0, 1.0, 0.0, 0.0]));
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].over_at, c[0].under_at, c[0].sign), (0.5, 2.5, 1));
        // Swap which strand is higher: over/under swap and the crossing turns left-handed.
        let c = find_crossings(&bow_tie([0.0, 0.0, 1.0, 1.0]));
        assert_eq!((c[0].over_at, c[0].under_at, c[0].sign), (2.5, 0.5, -1));
    }
}
