//! Contacts between rope segments: capsules of the rope's radius round each segment, pushed apart
//! on positions, with Coulomb friction on the substep's relative tangential displacement (Macklin
//! et al. 2014: below `static_friction` times the push, the slip is undone entirely). The contacts
//! are solved in each of the substep's passes over the rope's lengths and joints, and a pair's
//! pushes and its friction's moves are summed over the passes: the friction is bounded by the
//! whole push, and the passes converge on the substep's joint solution of rope and contacts (the
//! lengths and joints solved alone first spread a press along the strand, and the friction a strand
//! drawn over another showed fell short of its coefficient by the substep squared over the
//! particles' mass: 0.446 for 0.5 at 0.15 kg/m in 6 substeps, 0.488 in two passes, 0.499 in four). A pair that
//! lay within a diameter of touching when the substep began is pushed apart to the side it lay on
//! then: whatever moved one strand past the other's axis within the substep (a body's push, the
//! lengths' pull), the contact takes it back rather than on through.
//!
//! Of the candidate pairs ([`super::broad_phase`], sought again once a particle has moved half the
//! contact margin) only a few touch; the rest are passed over without their closest points while it
//! is certain they cannot touch ([`Watch`]): a pair's gap shrinks by no more than its segments' moves
//! since it was measured. The contacts solved, and so every bit of the result, are those of solving
//! every candidate.

use knotlab_hw::geometry::segment_closest_parameters;
use nalgebra::Vector3;

use super::Ropes;

/// Rounding allowance on the gaps and moves below, m: far above the arithmetic's error on
/// millimetre lengths (about 1e-19 m), far below any gap that matters.
const ROUNDING_M: f64 = 1e-9;

/// How far a segment may move from the reference positions before they are taken anew, m.
const REFERENCE_MOVE_M: f64 = 5e-5;

/// The candidate pairs, their gaps when last measured, and bounds on how far the segments have
/// moved since: a pair is solved only where its gap could have closed.
///
/// Moves are counted from reference positions, taken anew when a segment has moved
/// [`REFERENCE_MOVE_M`] from them. A pair measured when its segments lay `m_i`, `m_j` from the
/// reference carries that as its credit: its particles have since moved at most the credit plus
/// their segments' moves from the reference now (the triangle inequality), and its gap shrinks by
/// no more than that sum.
#[derive(Clone, Debug, Default)]
pub(super) struct Watch {
    /// The particles' positions when the candidates were found.
    x_found: Vec<Vector3<f64>>,
    /// The reference positions.
    x_ref: Vec<Vector3<f64>>,
    /// The segments each particle ends (an index past the last segment where it ends one only).
    particle_segments: Vec<[usize; 2]>,
    /// How far each segment's particles lie from the reference, at most, m (one more entry than
    /// segments, always 0, for particles that end one segment only).
    segment_moved_m: Vec<f64>,
    /// Each candidate's gap beyond touching (distance less two radii) when last measured, m.
    gap_m: Vec<f64>,
    /// Each candidate's credit, m.
    credit_m: Vec<f64>,
    /// How far each candidate's pair has been pushed apart over the substep's passes so far, m:
    /// the normal impulse (times the pair's inverse mass and the substep) that bounds its friction.
    pushed_m: Vec<f64>,
    /// How far each candidate's friction has moved its points back along each other over the
    /// substep's passes so far, m: the friction's impulse, as [`Self::pushed_m`] the normal one.
    rubbed_m: Vec<Vector3<f64>>,
    /// How many pairs' closest points were computed.
    pairs_measured: u64,
    /// Solve every candidate, culling none (to check that the culling changes nothing).
    exhaustive: bool,
}

/// The farthest any particle of `x` lies from where `since` has it, m.
fn farthest_move(x: &[Vector3<f64>], since: &[Vector3<f64>]) -> f64 {
    // Four running maxima, independent of each other, so that the loop need not wait on one.
    let mut farthest_sq = [0.0f64; 4];
    for (x, since) in x.chunks(4).zip(since.chunks(4)) {
        for k in 0..x.len().min(since.len()) {
            let d = (x[k] - since[k]).norm_squared();
            if d > farthest_sq[k] {
                farthest_sq[k] = d;
            }
        }
    }
    farthest_sq.into_iter().fold(0.0, f64::max).sqrt()
}

impl Watch {
    /// Whether the candidates found last still hold every pair that can touch: the rope is the
    /// same, and no particle has moved half the contact margin since. (Two segments that were no
    /// candidates lay more than two radii and the margin apart.)
    pub(super) fn still_covers(&self, ropes: &Ropes) -> bool {
        self.x_found.len() == ropes.x.len()
            && self.gap_m.len() == ropes.candidates.len()
            && 2.0 * farthest_move(&ropes.x, &self.x_found) + ROUNDING_M < ropes.params.contact_margin_m
    }

    /// Starts watching the candidates just found: every gap unknown (to be measured when first
    /// solved), the reference where the rope stands.
    pub(super) fn found(&mut self, ropes: &Ropes) {
        self.x_found.clone_from(&ropes.x);
        self.x_ref.clone_from(&ropes.x);
        let none = ropes.segments.len();
        self.particle_segments = vec![[none; 2]; ropes.x.len()];
        for (k, [a, b]) in ropes.segments.iter().enumerate() {
            self.particle_segments[*a][1] = k;
            self.particle_segments[*b][0] = k;
        }
        self.segment_moved_m = vec![0.0; none + 1];
        self.gap_m = vec![f64::NEG_INFINITY; ropes.candidates.len()];
        self.credit_m = vec![0.0; ropes.candidates.len()];
        self.pushed_m = vec![0.0; ropes.candidates.len()];
        self.rubbed_m = vec![Vector3::zeros(); ropes.candidates.len()];
    }

    /// A new substep's solve: no pair pushed apart or held by its friction yet.
    pub(super) fn start_substep(&mut self) {
        self.pushed_m.iter_mut().for_each(|m| *m = 0.0);
        self.rubbed_m.iter_mut().for_each(|m| *m = Vector3::zeros());
    }

    /// Measures how far every segment has moved from the reference; where one has moved too far,
    /// takes the rope as it stands as the reference, each pair's credit growing by its segments'
    /// moves.
    fn measure_moves(&mut self, ropes: &Ropes) {
        let mut farthest = 0.0f64;
        for (k, [a, b]) in ropes.segments.iter().enumerate() {
            let moved_sq = (ropes.x[*a] - self.x_ref[*a])
                .norm_squared()
                .max((ropes.x[*b] - self.x_ref[*b]).norm_squared());
            self.segment_moved_m[k] = moved_sq.sqrt() + ROUNDING_M;
            farthest = farthest.max(self.segment_moved_m[k]);
        }
        if farthest > REFERENCE_MOVE_M {
            for (k, &(i, j)) in ropes.candidates.iter().enumerate() {
                self.credit_m[k] += self.segment_moved_m[i] + self.segment_moved_m[j];
            }
            self.x_ref.clone_from(&ropes.x);
            self.segment_moved_m.iter_mut().for_each(|m| *m = 0.0);
        }
    }

    /// After particle `p` was moved: the bounds on its segments' moves take its move in.
    fn particle_moved(&mut self, p: usize, x: &Vector3<f64>) {
        let moved = (x - self.x_ref[p]).norm() + ROUNDING_M;
        for k in self.particle_segments[p] {
            if moved > self.segment_moved_m[k] {
                self.segment_moved_m[k] = moved;
            }
        }
        let last = self.segment_moved_m.len() - 1;
        self.segment_moved_m[last] = 0.0;
    }
}

/// The closest points' parameters on segments `a b` and `c d` and the vector between the points.
fn closest(ropes: &Ropes, a: usize, b: usize, c: usize, d: usize) -> (f64, f64, Vector3<f64>) {
    let (s, t) = segment_closest_parameters(
        &ropes.x[a],
        &(ropes.x[b] - ropes.x[a]),
        &ropes.x[c],
        &(ropes.x[d] - ropes.x[c]),
    );
    let p = ropes.x[a] * (1.0 - s) + ropes.x[b] * s;
    let q = ropes.x[c] * (1.0 - t) + ropes.x[d] * t;
    (s, t, p - q)
}

/// What bounds the friction of a pass over the contacts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Friction {
    /// The pair's pushes summed over the substep's passes (the passes over the rope).
    Summed,
    /// This pass's push alone, its moves not summed: the pass after the bodies pushed the rope,
    /// which keeps two strands from being carried through each other. (Bounded by the substep's
    /// pushes, its friction would hold the rope against what the bodies moved it by: a knot
    /// snugged over a stitch stopped 2 mm short of closing the wound.)
    OwnPush,
}

/// Solves every candidate contact once, in the candidates' order or, on the substeps
/// [`Ropes::contacts_backward`] says, the other way round; returns how many touched.
/// `moved_elsewhere`: whether anything but this solver moved the particles since it last ran.
pub(super) fn solve_contacts(
    ropes: &mut Ropes,
    watch: &mut Watch,
    x_prev: &[Vector3<f64>],
    moved_elsewhere: bool,
    friction: Friction,
) -> usize {
    let two_r = 2.0 * ropes.params.radius_m;
    let (mu_s, mu_k) = (ropes.params.static_friction, ropes.params.kinetic_friction);
    let mut touching = 0;
    if moved_elsewhere {
        watch.measure_moves(ropes);
    }
    let count = ropes.candidates.len();
    let backward = ropes.contacts_backward;
    for step in 0..count {
        let k = if backward { count - 1 - step } else { step };
        let (i, j) = ropes.candidates[k];
        let moved_m = watch.credit_m[k] + watch.segment_moved_m[i] + watch.segment_moved_m[j];
        // A pair pushed apart earlier in the substep keeps its friction though it touch no more.
        let pushed_before = friction == Friction::Summed && watch.pushed_m[k] > 0.0;
        if watch.gap_m[k] - moved_m >= ROUNDING_M && !pushed_before && !watch.exhaustive {
            continue;
        }
        watch.pairs_measured += 1;
        let [a, b] = ropes.segments[i];
        let [c, d] = ropes.segments[j];
        let (s, t, delta) = closest(ropes, a, b, c, d);
        let dist = delta.norm();
        watch.gap_m[k] = dist - two_r;
        watch.credit_m[k] = watch.segment_moved_m[i] + watch.segment_moved_m[j];
        // The same two points where the substep started: a pair that lay within a diameter of
        // touching there and the other way round now was carried through itself within the
        // substep (a body's push, a length's pull), and is pushed back to the side it came from.
        let then = (x_prev[a] * (1.0 - s) + x_prev[b] * s) - (x_prev[c] * (1.0 - t) + x_prev[d] * t);
        let through = then.norm_squared() < 4.0 * two_r * two_r && delta.dot(&then) < 0.0;
        let overlapping = (dist < two_r && dist >= 1e-12) || through;
        let rubbing = pushed_before && dist >= 1e-12;
        if !(overlapping || rubbing) {
            continue;
        }
        let (n, depth) = if through {
            let n = then.normalize();
            (n, two_r - delta.dot(&n))
        } else {
            (delta / dist, (two_r - dist).max(0.0))
        };
        if overlapping {
            touching += 1;
        }
        let weights = [(a, 1.0 - s), (b, s), (c, -(1.0 - t)), (d, -t)];
        let wsum: f64 = weights.iter().map(|(p, k)| ropes.w[*p] * k * k).sum();
        if wsum == 0.0 {
            continue;
        }
        for (p, k) in weights {
            ropes.x[p] += n * (ropes.w[p] * k * depth / wsum);
            if ropes.w[p] == 0.0 && k != 0.0 {
                ropes.held_pull[p] += n * (k * depth / wsum);
            }
        }
        watch.pushed_m[k] += depth;
        let (pushed_m, rubbed_m) = match friction {
            Friction::Summed => (watch.pushed_m[k], watch.rubbed_m[k]),
            Friction::OwnPush => (depth, Vector3::zeros()),
        };
        // Friction: the contact points' relative displacement over the substep, across the normal.
        let moved = |p: usize| ropes.x[p] - x_prev[p];
        let rel = (moved(a) * (1.0 - s) + moved(b) * s) - (moved(c) * (1.0 - t) + moved(d) * t);
        let tangential = rel - n * rel.dot(&n);
        // The friction's whole move over the substep, were this slip undone too: kept if within the
        // static bound on the pair's whole push, else cut to the kinetic one.
        let rubbed = rubbed_m - n * rubbed_m.dot(&n);
        let wanted = rubbed + tangential;
        let wanted_m = wanted.norm();
        if tangential.norm() >= 1e-15 {
            let kept =
                if wanted_m <= mu_s * pushed_m { wanted } else { wanted * (mu_k * pushed_m / wanted_m) };
            let undo = kept - rubbed;
            if friction == Friction::Summed {
                watch.rubbed_m[k] = kept;
            }
            for (p, k) in weights {
                ropes.x[p] -= undo * (ropes.w[p] * k / wsum);
                if ropes.w[p] == 0.0 && k != 0.0 {
                    ropes.held_pull[p] -= undo * (k / wsum);
                }
            }
        }
        // The pair's particles moved: their segments' bounds take it in.
        for (p, _) in weights {
            watch.particle_moved(p, &ropes.x[p]);
        }
    }
    touching
}

#[cfg(test)]
mod tests {
    use super::super::{RopeParams, Surroundings};
    use super::*;

    /// Surroundings that, after one substep's constraints, push the middle of strand `strand`
    /// (its particles within `reach_m` of the z axis) up by `lift_m`, as a jaw pushing a strand out
    /// of itself would.
    struct Shove {
        strand: std::ops::Range<usize>,
        reach_m: f64,
        lift_m: f64,
        at_substep: usize,
        substep: usize,
    }

    impl Surroundings for Shove {
        fn pushed_the_rope(&self) -> bool {
            self.substep == self.at_substep + 1
        }

        fn after(&mut self, ropes: &mut Ropes, _: &[Vector3<f64>], _: f64) {
            if self.substep == self.at_substep {
                for p in self.strand.clone() {
                    if ropes.x[p].xy().norm() < self.reach_m {
                        ropes.x[p].z += self.lift_m;
                    }
                }
            }
            self.substep += 1;
        }
    }

    /// A strand along x lying under one along y, touching it, shoved up in one substep by
    /// `lift_diameters` of the thread at the crossing (past the upper strand's axis from 1, clear of
    /// it on the far side from 2), then stepped 20 ms: the passes counted, and the lower strand's height
    /// over the upper's at the crossing at the end, in radii.
    fn shoved_up(lift_diameters: f64) -> (usize, f64) {
        let params = RopeParams { substeps: 6, ..RopeParams::default() };
        let r = params.radius_m;
        let mut ropes = Ropes::new(params);
        let lower =
            ropes.add_strand_along(&[Vector3::new(-0.01, 0.0, 0.0), Vector3::new(0.01, 0.0, 0.0)], 3.0 * r);
        let upper = ropes.add_strand_along(
            &[Vector3::new(0.0, -0.01, 2.0 * r), Vector3::new(0.0, 0.01, 2.0 * r)],
            3.0 * r,
        );
        for p in [lower.start, lower.end - 1, upper.start, upper.end - 1] {
            ropes.w[p] = 0.0;
        }
        let mut shove = Shove {
            strand: lower.clone(),
            reach_m: 2.0 * r,
            lift_m: lift_diameters * 2.0 * r,
            at_substep: 13,
            substep: 0,
        };
        let mut passes = 0;
        for _ in 0..20 {
            ropes.step_in(0.001, &mut shove);
            passes += ropes.crossed_last_step().len();
        }
        let nearest = |s: std::ops::Range<usize>| {
            s.map(|p| ropes.x[p]).min_by(|a, b| a.xy().norm().total_cmp(&b.xy().norm())).expect("a strand")
        };
        (passes, (nearest(lower).z - nearest(upper).z) / r)
    }

    /// A strand shoved by a body past the axis of another it touched, or clean past it, within one
    /// substep, is pushed back to the side it came from by the rope's contacts, not on through the other
    /// (pushed apart the way they then lay, it was: a coil caught in the jaws as they shut passed
    /// through another).
    #[test]
    fn a_strand_shoved_past_another_s_axis_in_a_substep_goes_back_the_way_it_came() {
        for lift in [1.1, 1.4, 1.8, 2.5] {
            let (passes, height_radii) = shoved_up(lift);
            println!(
                "shoved {lift} diameters: {passes} passes, the lower strand at {height_radii:.2} radii over the upper"
            );
            assert_eq!(passes, 0, "shoved {lift} diameters, it passed through");
            assert!(
                height_radii < -1.9,
                "shoved {lift} diameters, the lower strand ended {height_radii:.2} radii over the upper"
            );
        }
    }

    /// A 60 mm strand laid as a helix whose coils touch, its first particle pinned and its last
    /// pulled sideways, stepped 300 times with the contacts culled or not: its particles' positions
    /// at the end, and how many pairs' closest points were computed.
    fn coiled_and_pulled(exhaustive: bool) -> (Vec<Vector3<f64>>, u64, usize) {
        let mut ropes = Ropes::new(RopeParams { substeps: 5, ..RopeParams::default() });
        let turns = 6.0;
        let path: Vec<Vector3<f64>> = (0..=600)
            .map(|k| {
                let a = k as f64 / 600.0 * turns * std::f64::consts::TAU;
                Vector3::new(0.0016 * a.cos(), 0.0016 * a.sin(), 0.00041 * a / std::f64::consts::TAU)
            })
            .collect();
        let strand = ropes.add_strand_along(&path, 0.0003);
        ropes.w[strand.start] = 0.0;
        ropes.force_n[strand.end - 1] = Vector3::new(0.5, 0.2, 0.1);
        ropes.watch.exhaustive = exhaustive;
        let mut touched = 0;
        for _ in 0..300 {
            ropes.step(0.001);
            touched += ropes.contacts_last;
        }
        (ropes.x.clone(), ropes.watch.pairs_measured, touched)
    }

    /// Passing over rope pairs that cannot touch leaves a coiled, pulled strand bit for bit as solving every
    /// candidate does, while measuring under a quarter as many pairs.
    #[test]
    fn culling_the_pairs_that_cannot_touch_changes_no_bit() {
        let (culled, culled_measured, touched) = coiled_and_pulled(false);
        let (every, every_measured, _) = coiled_and_pulled(true);
        assert!(touched > 1000, "the coils touched {touched} times: the trial tests nothing");
        assert_eq!(culled, every, "culling changed the result");
        assert!(
            culled_measured * 4 < every_measured,
            "culled {culled_measured} pair measurements, every candidate {every_measured}"
        );
    }
}
