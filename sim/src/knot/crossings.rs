//! Crossings of a closed picture: every pair of non-adjacent segments whose projections intersect, with
//! which one passes over (the higher along the view direction) and the crossing's sign.
//!
//! Pairs are sought in a uniform grid of cells about one segment long, so the work grows with the
//! segments and the crossings, not with their square; a picture with more than [`MAX_CROSSINGS`]
//! crossings, or that needs more than [`MAX_PAIR_TESTS`] pairs looked at, is given up rather than let take
//! memory and time without bound.

use super::closure::ClosedPicture;

/// Where a crossing's strand passes, as a position along the closed curve: segment index plus the
/// fraction along it (`3.25` is a quarter of the way along segment 3).
pub type CurvePosition = f64;

/// Most crossings one picture may have; a picture with more is not classified (its vote is
/// `unknown`). A thread tied in a trial draws a few dozen.
pub const MAX_CROSSINGS: usize = 100_000;

/// Most pairs of segments one picture's search may look at (about a second's work).
pub const MAX_PAIR_TESTS: usize = 20_000_000;

/// Most cells a segment is filed under; a longer one (the closure's rays, its far arc) is tested
/// against every segment whose box it meets.
const MAX_CELLS_PER_SEGMENT: usize = 16;

/// Most cells along one side of the grid.
const MAX_CELLS_PER_SIDE: usize = 4096;

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

/// A picture too tangled to classify: it has more crossings than [`MAX_CROSSINGS`], or its search
/// would look at more than [`MAX_PAIR_TESTS`] pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooTangled {
    /// Crossings found before the search stopped.
    pub crossings_found: usize,
}

/// Relative size below which two projected segments count as parallel (no crossing).
const PARALLEL_EPS: f64 = 1e-14;

/// All crossings of a closed picture, in the order of a sweep over the segments' smallest x (each
/// pair's strand of smaller x first), or [`TooTangled`].
pub fn find_crossings(picture: &ClosedPicture) -> Result<Vec<Crossing>, TooTangled> {
    let m = picture.segments();
    let xy = &picture.xy;
    let end = |i: usize| if i + 1 == m { 0 } else { i + 1 };
    // Bounding boxes [x min, x max, y min, y max].
    let boxes: Vec<[f64; 4]> = (0..m)
        .map(|i| {
            let (a, b) = (xy[i], xy[end(i)]);
            [a[0].min(b[0]), a[0].max(b[0]), a[1].min(b[1]), a[1].max(b[1])]
        })
        .collect();
    // The sweep's order: a pair is tested with its segment of smaller x first, ties as the sort
    // leaves them, so that a crossing at equal heights always goes the same way.
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_unstable_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]));
    let mut rank = vec![0usize; m];
    for (k, &i) in order.iter().enumerate() {
        rank[i] = k;
    }
    let grid = Grid::over(&boxes, picture.thread_points);
    let (filed, long) = grid.file(&boxes);
    let mut long_rank = vec![usize::MAX; m];
    for (k, &s) in long.iter().enumerate() {
        long_rank[s] = k;
    }
    let mut found: Vec<(usize, usize, Crossing)> = Vec::new();
    let mut looked = 0usize;
    let mut look = |found: &Vec<(usize, usize, Crossing)>| {
        looked += 1;
        if looked > MAX_PAIR_TESTS { Err(TooTangled { crossings_found: found.len() }) } else { Ok(()) }
    };
    let test = |a: usize, b: usize, found: &mut Vec<(usize, usize, Crossing)>| -> Result<(), TooTangled> {
        let (i, j) = if rank[a] < rank[b] { (a, b) } else { (b, a) };
        if end(i) == j || end(j) == i {
            return Ok(());
        }
        if let Some(c) = intersect(picture, i, end(i), j, end(j)) {
            if found.len() == MAX_CROSSINGS {
                return Err(TooTangled { crossings_found: found.len() + 1 });
            }
            found.push((rank[i], rank[j], c));
        }
        Ok(())
    };
    let overlap = |a: &[f64; 4], b: &[f64; 4]| a[0] <= b[1] && b[0] <= a[1] && a[2] <= b[3] && b[2] <= a[3];
    // Segments filed in cells: a pair sharing cells is tested once, in the cell holding the lower
    // corner of their boxes' overlap.
    let mut start = 0;
    while start < filed.len() {
        let cell = filed[start].0;
        let stop = start + filed[start..].iter().take_while(|f| f.0 == cell).count();
        for x in start..stop {
            for y in x + 1..stop {
                look(&found)?;
                let (a, b) = (filed[x].1, filed[y].1);
                let (ba, bb) = (&boxes[a], &boxes[b]);
                if !overlap(ba, bb) || grid.cell_of(ba[0].max(bb[0]), ba[2].max(bb[2])) != cell {
                    continue;
                }
                test(a, b, &mut found)?;
            }
        }
        start = stop;
    }
    // The long segments against every other segment (each long pair once).
    for (k, &a) in long.iter().enumerate() {
        for b in 0..m {
            look(&found)?;
            if b == a || long_rank[b] < k || !overlap(&boxes[a], &boxes[b]) {
                continue;
            }
            test(a, b, &mut found)?;
        }
    }
    found.sort_unstable_by_key(|f| (f.0, f.1));
    Ok(found.into_iter().map(|f| f.2).collect())
}

/// A uniform grid over the picture, its cells about as wide as the thread's segments are long.
struct Grid {
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
}

impl Grid {
    fn over(boxes: &[[f64; 4]], thread_points: usize) -> Self {
        let (mut x0, mut x1, mut y0, mut y1) =
            (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for b in boxes {
            (x0, x1, y0, y1) = (x0.min(b[0]), x1.max(b[1]), y0.min(b[2]), y1.max(b[3]));
        }
        let thread = &boxes[..thread_points.saturating_sub(1).min(boxes.len())];
        let mean =
            thread.iter().map(|b| (b[1] - b[0]).max(b[3] - b[2])).sum::<f64>() / thread.len().max(1) as f64;
        let side = (x1 - x0).max(y1 - y0);
        let cell = mean.max(side / MAX_CELLS_PER_SIDE as f64).max(f64::MIN_POSITIVE);
        let count = |extent: f64| ((extent / cell).floor() as usize + 1).min(MAX_CELLS_PER_SIDE);
        Self { x0, y0, cell, nx: count(x1 - x0), ny: count(y1 - y0) }
    }

    fn column(&self, x: f64) -> usize {
        (((x - self.x0) / self.cell).floor().max(0.0) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.y0) / self.cell).floor().max(0.0) as usize).min(self.ny - 1)
    }

    fn cell_of(&self, x: f64, y: f64) -> usize {
        self.row(y) * self.nx + self.column(x)
    }

    /// (cell, segment) for every short segment, sorted by cell, and the long segments.
    fn file(&self, boxes: &[[f64; 4]]) -> (Vec<(usize, usize)>, Vec<usize>) {
        let mut filed = Vec::with_capacity(2 * boxes.len());
        let mut long = Vec::new();
        for (s, b) in boxes.iter().enumerate() {
            let (c0, c1, r0, r1) = (self.column(b[0]), self.column(b[1]), self.row(b[2]), self.row(b[3]));
            if (c1 - c0 + 1) * (r1 - r0 + 1) > MAX_CELLS_PER_SEGMENT {
                long.push(s);
                continue;
            }
            for r in r0..=r1 {
                for c in c0..=c1 {
                    filed.push((r * self.nx + c, s));
                }
            }
        }
        filed.sort_unstable();
        (filed, long)
    }
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
        let c = find_crossings(&bow_tie([1.0, 1.0, 0.0, 0.0])).unwrap();
        assert_eq!(c.len(), 1);
        assert_eq!((c[0].over_at, c[0].under_at, c[0].sign), (0.5, 2.5, 1));
        // Swap which strand is higher: over/under swap and the crossing turns left-handed.
        let c = find_crossings(&bow_tie([0.0, 0.0, 1.0, 1.0])).unwrap();
        assert_eq!((c[0].over_at, c[0].under_at, c[0].sign), (2.5, 0.5, -1));
    }

    /// Every pair tested, in the sweep's order: what the grid must find.
    fn every_pair(picture: &ClosedPicture) -> Vec<Crossing> {
        let m = picture.segments();
        let end = |i: usize| if i + 1 == m { 0 } else { i + 1 };
        let xmin = |i: usize| picture.xy[i][0].min(picture.xy[end(i)][0]);
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_unstable_by(|&a, &b| xmin(a).total_cmp(&xmin(b)));
        let mut found = Vec::new();
        for (k, &i) in order.iter().enumerate() {
            for &j in &order[k + 1..] {
                if end(i) != j && end(j) != i {
                    found.extend(intersect(picture, i, end(i), j, end(j)));
                }
            }
        }
        found
    }

    /// The grid finds the crossings testing every pair finds, in the same order, for random walks
    /// (many crossings, short and long segments, the closure's rays among them) and a tight coil
    /// seen along its axis (every turn over every other).
    #[test]
    fn the_grid_finds_what_testing_every_pair_finds() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut total = 0;
        for case in 0..40 {
            let n = 20 + 30 * case;
            let mut xy = vec![[0.0, 0.0]];
            for _ in 1..n {
                let [x, y] = xy[xy.len() - 1];
                let step = if rng.random_bool(0.05) { 20.0 } else { 1.0 };
                xy.push([x + step * rng.random_range(-1.0..1.0), y + step * rng.random_range(-1.0..1.0)]);
            }
            let height = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
            let picture = ClosedPicture { xy, height, thread_points: n - 3 };
            let want = every_pair(&picture);
            total += want.len();
            assert_eq!(find_crossings(&picture).unwrap(), want, "walk of {n} points");
        }
        assert!(total > 10_000, "{total} crossings: too few to compare");
        let coil: Vec<[f64; 2]> = (0..2000)
            .map(|k| {
                let t = k as f64 * 0.5;
                [(1.0 + 5e-4 * t) * t.cos(), (1.0 + 5e-4 * t) * t.sin()]
            })
            .collect();
        let picture =
            ClosedPicture { height: (0..2000).map(|k| k as f64).collect(), xy: coil, thread_points: 2000 };
        let want = every_pair(&picture);
        assert!(want.len() > 20_000, "{}", want.len());
        assert_eq!(find_crossings(&picture).unwrap(), want);
    }
}
