//! Watches a thread's centreline (the rope's particles, the chain's joints) for a strand passing
//! through another, from one look to the next (the rope looks after each of its substeps, the
//! chain after each step). Knots are made of strands that block each other; a strand that goes
//! through another (a solver failure under load, or a move faster than the contacts can hold) can
//! tie or untie a knot that real thread could not.
//!
//! Between one look and the next, each point is taken to move on a straight line. Two segments `a b` and `c d` can only pass through each other where the four
//! points are coplanar, where the signed volume `((b - a) x (d - c)) . (c - a)` is zero. A pass is a
//! change of that volume's sign over the substep whose coplanar instant (found by bisection) has
//! the two segments within [`CROSSING_DISTANCE_RADII`] radii of each other: four points also become
//! coplanar when two segments turn through parallel beside each other, or when the lines' crossing
//! point lies beyond a segment's end, and then the segments stay apart.
//!
//! A pair that passed is not counted again until its segments have come apart (two radii, as
//! strands touching): two strands left lying through each other flip the sign back and forth with
//! every substep, one pass.
//!
//! Most candidate pairs lie far from each other: a pair whose distance when last measured, less
//! how far its two segments have moved since, stays above that threshold cannot pass, and is not
//! measured (a segment's points move no farther than its farther end, so the distance between two
//! segments changes by no more than the sum of their moves).

use knotlab_hw::geometry::segment_closest_parameters;
use nalgebra::Vector3;

/// A pass counts when the segments' axes come this many radii of each other at the coplanar
/// instant (two strands touching lie two radii apart; passing through each other, zero).
pub const CROSSING_DISTANCE_RADII: f64 = 0.5;

/// Bisection steps on the coplanar instant within a substep (2^-30 of it).
const BISECTIONS: usize = 30;

/// The watch's state between looks.
#[derive(Clone, Debug, Default)]
pub struct CrossingWatch {
    /// The particles' positions at the end of the last substep watched.
    x_last: Vec<Vector3<f64>>,
    /// Per candidate pair, the signed volume at `x_last` (NaN: not measured then).
    volume: Vec<f64>,
    /// Per candidate pair, its segments' distance when last measured, m (-inf: never).
    clear_m: Vec<f64>,
    /// Per candidate pair, its two segments' travel when it was last measured, m.
    travel_at_measure_m: Vec<f64>,
    /// Per segment, how far it moved at the last look (the farther of its ends), m.
    moved_m: Vec<f64>,
    /// Per segment, how far it has moved in all, m (the sum of its moves).
    travel_m: Vec<f64>,
    /// The segment pairs that passed through each other in the current step, in order (smaller
    /// segment first).
    crossed: Vec<(usize, usize)>,
    /// Pairs measured in all.
    pairs_measured: u64,
    /// Pairs that passed and have not come apart since (their segments not yet two radii apart):
    /// a pair left lying through each other flips back and forth, one pass.
    passed: Vec<(usize, usize)>,
}

/// The signed volume of the four points: zero where they are coplanar.
fn volume(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>, d: &Vector3<f64>) -> f64 {
    (b - a).cross(&(d - c)).dot(&(c - a))
}

/// The distance between segments `a b` and `c d`, m.
fn distance(a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>, d: &Vector3<f64>) -> f64 {
    let (d1, d2) = (b - a, d - c);
    let (s, t) = segment_closest_parameters(a, &d1, c, &d2);
    ((a + d1 * s) - (c + d2 * t)).norm()
}

impl CrossingWatch {
    /// The segment pairs that passed through each other in the current step (smaller segment
    /// first; a pass near a joint, flipping the pairs either side of it, counts once).
    pub fn crossed(&self) -> &[(usize, usize)] {
        &self.crossed
    }

    /// How many pairs' distances were measured so far (the rest were certainly apart).
    pub fn pairs_measured(&self) -> u64 {
        self.pairs_measured
    }

    /// Starts a step: forgets the last step's passes; a centreline of another size, or the first
    /// step, starts the watch where it stands.
    pub fn start_step(&mut self, x: &[Vector3<f64>]) {
        self.crossed.clear();
        if self.x_last.len() != x.len() {
            self.x_last = x.to_vec();
            self.volume.clear();
            self.clear_m.clear();
            self.travel_m.clear();
        }
    }

    /// The candidate pairs (of segments that may come near each other) are new: nothing is known
    /// of them.
    pub fn candidates_changed(&mut self, count: usize) {
        self.volume = vec![f64::NAN; count];
        self.clear_m = vec![f64::NEG_INFINITY; count];
        self.travel_at_measure_m = vec![0.0; count];
    }

    /// The centreline is now at `x`: judges every candidate pair of `segments` (pairs of points of
    /// `x`) that may have passed since the last look, for a thread of radius `radius_m`.
    pub fn look(
        &mut self,
        x: &[Vector3<f64>],
        segments: &[[usize; 2]],
        candidates: &[(usize, usize)],
        radius_m: f64,
    ) {
        if self.travel_m.len() != segments.len() {
            self.travel_m = vec![0.0; segments.len()];
            self.moved_m = vec![0.0; segments.len()];
            self.candidates_changed(candidates.len());
        }
        if self.volume.len() != candidates.len() {
            self.candidates_changed(candidates.len());
        }
        // How far each segment moved since the last look, and in all.
        for (s, [a, b]) in segments.iter().enumerate() {
            let moved_sq =
                (x[*a] - self.x_last[*a]).norm_squared().max((x[*b] - self.x_last[*b]).norm_squared());
            self.moved_m[s] = moved_sq.sqrt();
            self.travel_m[s] += self.moved_m[s];
        }
        let threshold_m = CROSSING_DISTANCE_RADII * radius_m;
        let first = self.crossed.len();
        let apart_m = 2.0 * radius_m;
        for (k, &(i, j)) in candidates.iter().enumerate() {
            // The pair's distance now is at least its distance when measured less how far its
            // segments have moved since.
            let since_m = self.travel_m[i] + self.travel_m[j] - self.travel_at_measure_m[k];
            let counted = !self.passed.is_empty() && self.passed.contains(&(i, j));
            if self.clear_m[k] - since_m > threshold_m {
                self.volume[k] = f64::NAN;
                if counted && self.clear_m[k] - since_m >= apart_m {
                    self.passed.retain(|p| *p != (i, j));
                }
                continue;
            }
            self.pairs_measured += 1;
            let ([a, b], [c, d]) = (segments[i], segments[j]);
            let last = &self.x_last;
            let before = if self.volume[k].is_nan() {
                volume(&last[a], &last[b], &last[c], &last[d])
            } else {
                self.volume[k]
            };
            let pair_moved_m = self.moved_m[i] + self.moved_m[j];
            let clear_before_m = self.clear_m[k] - (since_m - pair_moved_m);
            let now = volume(&x[a], &x[b], &x[c], &x[d]);
            self.volume[k] = now;
            self.clear_m[k] = distance(&x[a], &x[b], &x[c], &x[d]);
            self.travel_at_measure_m[k] = self.travel_m[i] + self.travel_m[j];
            if counted && self.clear_m[k] >= apart_m {
                // Apart again (a flip on the way out ends the pass counted already).
                self.passed.retain(|p| *p != (i, j));
            }
            if counted || before == 0.0 || now == 0.0 || before.signum() == now.signum() {
                continue;
            }
            // Over the look the distance falls no faster than the pair moves: from both ends, it
            // stays above half their sum less the move. Most flips are of pairs lying apart in
            // one plane (neighbours along a straight strand).
            if 0.5 * (clear_before_m + self.clear_m[k] - pair_moved_m) > threshold_m {
                continue;
            }
            // The coplanar instant, s in 0..1 of the look, on the straight moves.
            let at = |s: f64, p: usize| last[p] + (x[p] - last[p]) * s;
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (lo + hi);
                let v = volume(&at(mid, a), &at(mid, b), &at(mid, c), &at(mid, d));
                if v.signum() == before.signum() {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let s = 0.5 * (lo + hi);
            if distance(&at(s, a), &at(s, b), &at(s, c), &at(s, d)) < threshold_m {
                self.crossed.push((i.min(j), i.max(j)));
                self.passed.push((i, j));
            }
        }
        // One strand passing through another near a joint flips the pairs on both sides of it:
        // one pass.
        let mut passes: Vec<(usize, usize)> = self.crossed.split_off(first);
        passes.sort_unstable();
        for (i, j) in passes {
            let near = |&(p, q): &(usize, usize)| p.abs_diff(i) <= 1 && q.abs_diff(j) <= 1;
            if !self.crossed[first..].iter().any(near) {
                self.crossed.push((i, j));
            }
        }
        self.x_last.clear();
        self.x_last.extend_from_slice(x);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Segment 0 along x at z = 0, segment 2 along y at height `z` (segment 1 joins them, far off).
    fn at(z: f64) -> Vec<Vector3<f64>> {
        vec![
            Vector3::new(-0.002, 0.0, 0.0),
            Vector3::new(0.002, 0.0, 0.0),
            Vector3::new(0.0, -0.002, z),
            Vector3::new(0.0, 0.002, z),
        ]
    }

    /// Guards the count: a segment moved through another is one pass; left lying through it,
    /// jittering across, still one; drawn clear and pushed through again, a second; moved past it
    /// beyond its end, none.
    #[test]
    fn a_pass_counts_once_until_the_segments_come_apart() {
        let (r, segments, pairs) = (0.0002, [[0, 1], [1, 2], [2, 3]], [(0, 2)]);
        let mut watch = CrossingWatch::default();
        let mut passes = Vec::new();
        for z in [0.001, 0.0005, -0.00001, 0.00001, -0.00001, 0.00001, -0.001, -0.002, 0.001] {
            let x = at(z);
            watch.start_step(&x);
            watch.look(&x, &segments, &pairs, r);
            passes.extend_from_slice(watch.crossed());
        }
        assert_eq!(passes, [(0, 2), (0, 2)]);
        // Beside its end: the four points become coplanar 3 mm off, no pass.
        let mut watch = CrossingWatch::default();
        let beside = |z: f64| {
            at(z)
                .into_iter()
                .enumerate()
                .map(|(k, p)| if k >= 2 { p + Vector3::x() * 0.005 } else { p })
                .collect::<Vec<_>>()
        };
        for z in [0.001, -0.001] {
            let x = beside(z);
            watch.start_step(&x);
            watch.look(&x, &segments, &pairs, r);
            assert!(watch.crossed().is_empty(), "at {z}: {:?}", watch.crossed());
        }
    }
}
