//! Which rope segments may touch within a step: sweep and prune along x over the segments' boxes,
//! grown by the contact reach, skipping neighbours in one strand.

use nalgebra::Vector3;

/// The pairs `(i, j)`, `i < j`, of `segments` whose boxes, grown by `reach_m`, overlap, except
/// pairs `skip` rules out. Sorted, so the contacts are solved in the same order whatever the
/// positions' history.
pub fn candidate_pairs(
    x: &[Vector3<f64>],
    segments: &[[usize; 2]],
    reach_m: f64,
    skip: impl Fn(usize, usize) -> bool,
) -> Vec<(usize, usize)> {
    let boxes: Vec<(Vector3<f64>, Vector3<f64>)> = segments
        .iter()
        .map(|[a, b]| (x[*a].inf(&x[*b]).add_scalar(-reach_m), x[*a].sup(&x[*b]).add_scalar(reach_m)))
        .collect();
    let mut order: Vec<usize> = (0..segments.len()).collect();
    order.sort_by(|i, j| boxes[*i].0.x.total_cmp(&boxes[*j].0.x).then(i.cmp(j)));
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        let (lo, hi) = boxes[i];
        for &j in &order[k + 1..] {
            let (lo2, hi2) = boxes[j];
            if lo2.x > hi.x {
                break;
            }
            if lo2.y > hi.y || lo2.z > hi.z || hi2.y < lo.y || hi2.z < lo.z {
                continue;
            }
            let (i, j) = (i.min(j), i.max(j));
            if !skip(i, j) {
                pairs.push((i, j));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}
