//! The laid-knot trial of [`crate::laid_knot`] in the rope: a surgeon's knot laid over a stitch
//! through two tissue flaps, snugged by its free ends, then the evaluator's holding test (each flap
//! pulled open for a while with the free ends let go) — the yardstick for the rope as the scene's
//! thread. The flaps are as [`knotlab_sim::tissue`] makes them (each a box sliding across the wound on a
//! spring that pulls it back to the rest gap), here integrated beside the rope instead of in Rapier;
//! the tissue frame is the world frame (x along the wound, y across it towards flap A, z up, the
//! surface at z = 0). The stitch is four points (exit, its deep point, the entry's deep point,
//! entry), each moving with its flap: the rope passes through each, free to slide along itself
//! through it (no slide friction), and pulls the flap with the push it takes.

use nalgebra::{Isometry3, Vector3};

use crate::laid_knot::{LaidKnotKind, LaidKnotParams, surgeons_knot_through, surgeons_throw_through};
use knotlab_sim::knot::legs::free_ends;
use knotlab_sim::knot::{KnotPlacement, KnotType, TissueSurface, classify};
use knotlab_sim::rope::rigid::{nearest_on_rope, thread_through};
use knotlab_sim::rope::{RopeParams, Ropes, Surroundings};
use knotlab_sim::scene::{StitchParams, TissueParams};

/// Particle spacing of the trial's rope, m.
pub const SPACING_M: f64 = 0.0003;
/// Step of the trial, s.
pub const DT_S: f64 = 0.001;
/// Deep points lie this far in from a flap's inner face (as [`knotlab_sim::tissue`] lays them), m.
const DEEP_INSET_M: f64 = 0.001;

/// How the trial loads the knot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WoundTrialParams {
    /// The rope's weight per metre, N/m (gravity on the suture's real mass; the rope's mass per
    /// metre is inflated for its solver and would weigh far more).
    pub weight_per_m_n: f64,
    /// Friction of the rope on the tissue.
    pub tissue_friction: f64,
    /// Each flap pulled open with this force in the holding test, N ...
    pub holding_load_n: f64,
    /// ... for this long, s.
    pub settle_s: f64,
}

impl Default for WoundTrialParams {
    /// The nominal scene's: a 10 g, 0.2 m thread's weight, 0.3 N a flap for 1 s.
    fn default() -> Self {
        Self { weight_per_m_n: 0.05 * 9.81, tissue_friction: 0.3, holding_load_n: 0.3, settle_s: 1.0 }
    }
}

/// What the trial measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WoundOutcome {
    /// The knot as laid, snugged and after the holding test (none: the classifier failed).
    pub knot_laid: Option<KnotType>,
    /// ...
    pub knot_snug: Option<KnotType>,
    /// ...
    pub knot_after: Option<KnotType>,
    /// The wound's gap as snugged, m ...
    pub gap_snug_m: f64,
    /// ... and after the holding test, m.
    pub gap_after_m: f64,
    /// The thread in the tissue, from the exit to the entry, as snugged, m ...
    pub inside_snug_m: f64,
    /// ... and after the holding test, m (more: the knot gave thread to the loop).
    pub inside_after_m: f64,
    /// Where the rope passes the exit and the entry, along it from the long end, as snugged, m ...
    pub through_snug_m: [f64; 2],
    /// ... and after the holding test, m.
    pub through_after_m: [f64; 2],
    /// The long end's and the tail's free ends (from each end to where it first touches the other
    /// side's strand, [`knotlab_sim::knot::legs::free_ends`]) as snugged, m (none: they do not touch) ...
    pub free_ends_snug_m: Option<(f64, f64)>,
    /// ... and after the holding test, m.
    pub free_ends_after_m: Option<(f64, f64)>,
    /// The rope's length as laid, snugged and after the holding test, m (an inextensible rope keeps
    /// it; the solver's stretch under load shows as more).
    pub length_m: [f64; 3],
    /// The knot's lowest crossing above the tissue as snugged and after the holding test, m (none:
    /// no knot) ...
    pub height_m: [Option<f64>; 2],
    /// ... and the thread outside the tissue between the stitch and the knot, both sides, m
    /// ([`knotlab_sim::knot::KnotSpan::loop_outside_m`]).
    pub loop_outside_m: [Option<f64>; 2],
    /// Particles in the rope.
    pub particles: usize,
}

/// The two flaps beside the rope.
struct Flaps {
    tissue: TissueParams,
    friction: f64,
    /// Outward displacement of [B, A] from rest, m, and its rate, m/s.
    u_m: [f64; 2],
    v_m_s: [f64; 2],
    /// Outward force on [B, A] besides the spring and the rope, N.
    load_n: [f64; 2],
    /// Where the rope passes each stitch point [exit, exit deep, entry deep, entry]: a particle
    /// index plus the fraction of the way to the next; and where each point sits at rest.
    guides: [(f64, Vector3<f64>); 4],
    /// Whether the last substep's contacts or stitch points moved particles of the rope.
    pushed: bool,
}

/// +1 for flap A (index 1), -1 for B.
fn side(flap: usize) -> f64 {
    if flap == 1 { 1.0 } else { -1.0 }
}

impl Flaps {
    fn inner_y(&self, flap: usize) -> f64 {
        side(flap) * (0.5 * self.tissue.rest_gap_m + self.u_m[flap])
    }

    /// Where the rope passes the exit and the entry, along it from its first particle, m.
    fn through_m(&self, spacing_m: f64) -> [f64; 2] {
        [self.guides[0].0 * spacing_m, self.guides[3].0 * spacing_m]
    }

    fn gap_m(&self) -> f64 {
        self.tissue.rest_gap_m + self.u_m[0] + self.u_m[1]
    }

    /// The thread between the exit and the entry, m.
    fn inside_m(&self, ropes: &Ropes) -> f64 {
        thread_between_m(ropes, self.guides[0].0, self.guides[3].0)
    }

    /// Guide `k` where its flap holds it now.
    fn guide_m(&self, k: usize) -> Vector3<f64> {
        let flap = if k < 2 { 0 } else { 1 };
        self.guides[k].1 + Vector3::y() * (side(flap) * self.u_m[flap])
    }
}

impl Flaps {
    /// Particles in the tissue, between the exit's and the entry's points: no contact with the
    /// flaps.
    fn inside(&self) -> std::ops::RangeInclusive<usize> {
        (self.guides[0].0.floor() as usize)..=(self.guides[3].0.ceil() as usize)
    }

    /// Puts the rope through each stitch point: the point of the rope there moved onto it across
    /// the rope (not along it: the rope slides through), then the point's place on the rope
    /// updated. Returns the outward pull of the rope on each flap, N.
    fn thread_through(&mut self, ropes: &mut Ropes, h_s: f64) -> [f64; 2] {
        let mut outward_n = [0.0; 2];
        for k in 0..4 {
            let flap = if k < 2 { 0 } else { 1 };
            let target = self.guide_m(k);
            let Some((moves, at)) = thread_through(ropes, self.guides[k].0, &target) else { continue };
            for (p, dx) in moves {
                self.pushed |= dx != Vector3::zeros();
                if ropes.w[p] > 0.0 {
                    outward_n[flap] -= side(flap) * dx.y / (ropes.w[p] * h_s * h_s);
                }
            }
            self.guides[k].0 = at;
        }
        outward_n
    }
}

impl Surroundings for Flaps {
    fn pushed_the_rope(&self) -> bool {
        self.pushed
    }

    fn after(&mut self, ropes: &mut Ropes, x_prev: &[Vector3<f64>], h_s: f64) {
        self.pushed = false;
        let r = ropes.params.radius_m;
        let [along, _, thickness] = self.tissue.flap_size_m;
        let mut outward_n = self.thread_through(ropes, h_s);
        let inside = self.inside();
        for (p, x_before) in x_prev.iter().enumerate() {
            if inside.contains(&p) || ropes.w[p] == 0.0 {
                continue;
            }
            let x = ropes.x[p];
            if x.x.abs() > 0.5 * along + r || x.z < -thickness - r {
                continue;
            }
            let flap = if x.y >= 0.0 { 1 } else { 0 };
            let s = side(flap);
            let depth_top = r - x.z;
            let depth_inner = s * (x.y - self.inner_y(flap)) + r;
            if depth_top <= 0.0 || depth_inner <= 0.0 {
                continue;
            }
            let (normal, depth) = if depth_top <= depth_inner {
                (Vector3::z(), depth_top)
            } else {
                (-Vector3::y() * s, depth_inner)
            };
            let mut dx = normal * depth;
            // Friction against the flap's own motion over the substep.
            let moved = (x + dx - x_before) - Vector3::y() * (s * self.v_m_s[flap] * h_s);
            let tangential = moved - normal * moved.dot(&normal);
            let slip = tangential.norm();
            if slip > 0.0 {
                dx -= tangential * (self.friction * depth / slip).min(1.0);
            }
            ropes.x[p] += dx;
            self.pushed = true;
            // The flap takes the opposite of the push, along its slide.
            let mass_kg = 1.0 / ropes.w[p];
            outward_n[flap] -= s * mass_kg * dx.y / (h_s * h_s);
        }
        for (flap, rope_n) in outward_n.into_iter().enumerate() {
            let spring_n = -self.tissue.opening_stiffness_n_per_m * self.u_m[flap]
                - self.tissue.opening_damping_n_s_per_m * self.v_m_s[flap];
            let a = (rope_n + spring_n + self.load_n[flap]) / self.tissue.flap_mass_kg;
            self.v_m_s[flap] += a * h_s;
            self.u_m[flap] += self.v_m_s[flap] * h_s;
            let closed = -0.5 * self.tissue.rest_gap_m;
            if self.u_m[flap] < closed {
                self.u_m[flap] = closed;
                self.v_m_s[flap] = self.v_m_s[flap].max(0.0);
            }
        }
    }
}

/// The rope's length between two places on it (particle index plus fraction), m.
pub(super) fn thread_between_m(ropes: &Ropes, from: f64, to: f64) -> f64 {
    let at = |sigma: f64| {
        let i = (sigma.floor() as usize).min(ropes.x.len() - 2);
        let t = sigma - i as f64;
        (i, ropes.x[i] * (1.0 - t) + ropes.x[i + 1] * t)
    };
    let ((i, from), (j, to)) = (at(from), at(to));
    if j <= i {
        return (to - from).norm();
    }
    let mut length = (ropes.x[i + 1] - from).norm() + (to - ropes.x[j]).norm();
    for k in i + 1..j {
        length += (ropes.x[k + 1] - ropes.x[k]).norm();
    }
    length
}

/// The knot in the rope, its lowest crossing over the tissue and the loop outside it, m (none:
/// unclassified, or no knot), the rope passing the exit and the entry at `through_m`, the tissue's
/// surface and stitch where `world_from_tissue` puts the tissue frame's origin.
pub(super) fn observe(
    ropes: &Ropes,
    through_m: [f64; 2],
    world_from_tissue: &Isometry3<f64>,
) -> (Option<KnotType>, Option<f64>, Option<f64>) {
    let Ok(c) = classify(&ropes.polyline(0)) else { return (None, None, None) };
    let origin = world_from_tissue.translation.vector;
    let surface = TissueSurface::new(origin, world_from_tissue.rotation * Vector3::z());
    let (Some(span), Ok(surface)) = (&c.span, surface) else {
        return (Some(c.knot), None, None);
    };
    let height_m = KnotPlacement::measure(span, &surface, &origin).height_m;
    (Some(c.knot), Some(height_m), span.loop_outside_m(through_m[0], through_m[1]))
}

/// The rope as it lies at one moment of a wound trial (snugged, or after the holding test).
pub(super) struct Moment {
    knot: Option<KnotType>,
    height_m: Option<f64>,
    loop_outside_m: Option<f64>,
    gap_m: f64,
    inside_m: f64,
    through_m: [f64; 2],
    free_ends_m: Option<(f64, f64)>,
    length_m: f64,
}

impl Moment {
    /// Takes it: the rope passing the exit and the entry at `through_m`, `inside_m` of it in the
    /// tissue, the wound `gap_m` open, the tissue frame where `world_from_tissue` puts it.
    pub(super) fn take(
        ropes: &Ropes,
        through_m: [f64; 2],
        world_from_tissue: &Isometry3<f64>,
        inside_m: f64,
        gap_m: f64,
    ) -> Self {
        let (knot, height_m, loop_outside_m) = observe(ropes, through_m, world_from_tissue);
        let touch_m = 2.5 * ropes.params.radius_m;
        Self {
            knot,
            height_m,
            loop_outside_m,
            gap_m,
            inside_m,
            through_m,
            free_ends_m: free_ends(&ropes.polyline(0), through_m[0], through_m[1], touch_m),
            length_m: length_m(ropes),
        }
    }
}

impl WoundOutcome {
    /// The outcome from the knot and the rope's length as laid and the two moments.
    pub(super) fn from_moments(
        knot_laid: Option<KnotType>,
        length_laid_m: f64,
        snug: Moment,
        after: Moment,
        particles: usize,
    ) -> Self {
        Self {
            knot_laid,
            knot_snug: snug.knot,
            knot_after: after.knot,
            gap_snug_m: snug.gap_m,
            gap_after_m: after.gap_m,
            inside_snug_m: snug.inside_m,
            inside_after_m: after.inside_m,
            through_snug_m: snug.through_m,
            through_after_m: after.through_m,
            free_ends_snug_m: snug.free_ends_m,
            free_ends_after_m: after.free_ends_m,
            height_m: [snug.height_m, after.height_m],
            loop_outside_m: [snug.loop_outside_m, after.loop_outside_m],
            length_m: [length_laid_m, snug.length_m, after.length_m],
            particles,
        }
    }
}

/// The rope's length along its polyline, m.
pub(super) fn length_m(ropes: &Ropes) -> f64 {
    ropes.polyline(0).windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// Lays `knot` (a surgeon's knot, or its first throw alone: [`LaidKnotKind::SurgeonsThrow`]) over the stitch of `tissue` and
/// `stitch`, snugs it by its free ends as [`crate::laid_knot::lay_and_snug`] does, lets go and
/// runs the holding test.
pub fn laid_surgeons_knot_in_wound(
    rope: RopeParams,
    tissue: &TissueParams,
    stitch: &StitchParams,
    knot: &LaidKnotParams,
    trial: &WoundTrialParams,
) -> WoundOutcome {
    let inset = (0.5 * tissue.rest_gap_m + DEEP_INSET_M).min(stitch.bite_m);
    let stitch_points = [
        Vector3::new(stitch.along_m, -stitch.bite_m, 0.0),
        Vector3::new(stitch.along_m, -inset, -stitch.depth_m),
        Vector3::new(stitch.along_m, inset, -stitch.depth_m),
        Vector3::new(stitch.along_m, stitch.bite_m, 0.0),
    ];
    let path = match knot.kind {
        LaidKnotKind::SurgeonsThrow => surgeons_throw_through(&Isometry3::identity(), stitch_points, knot),
        _ => surgeons_knot_through(&Isometry3::identity(), stitch_points, knot),
    };
    let mut ropes = Ropes::new(rope);
    let strand = ropes.add_strand_along(&path, SPACING_M);
    let last = strand.end - 1;
    let nearest = |target: &Vector3<f64>| {
        strand.clone().min_by(|a, b| (ropes.x[*a] - target).norm().total_cmp(&(ropes.x[*b] - target).norm()))
    };
    let guides: Vec<(f64, Vector3<f64>)> = stitch_points
        .iter()
        .map(|q| (nearest_on_rope(&ropes, q, nearest(q).unwrap_or(strand.start), last), *q))
        .collect();
    let mut flaps = Flaps {
        tissue: *tissue,
        friction: trial.tissue_friction,
        u_m: [0.0; 2],
        v_m_s: [0.0; 2],
        load_n: [0.0; 2],
        guides: [guides[0], guides[1], guides[2], guides[3]],
        pushed: false,
    };
    let knot_laid = observe(&ropes, flaps.through_m(SPACING_M), &Isometry3::identity()).0;
    let length_laid_m = length_m(&ropes);
    let (long_end, tail) = (strand.start, strand.end - 1);
    let weight: Vec<Vector3<f64>> = (0..ropes.x.len())
        .map(|p| {
            if ropes.w[p] > 0.0 {
                -Vector3::z() * (trial.weight_per_m_n * SPACING_M)
            } else {
                Vector3::zeros()
            }
        })
        .collect();
    let snug_steps = (knot.snug_s / DT_S).round() as usize;
    for step in 0..snug_steps {
        ropes.force_n.copy_from_slice(&weight);
        let f = knot.snug_n * (2.0 * step as f64 / snug_steps as f64).min(1.0);
        ropes.force_n[tail] += Vector3::y() * f;
        ropes.force_n[long_end] -= Vector3::y() * f;
        flaps.load_n = [-knot.closing_n, -knot.closing_n];
        ropes.step_in(DT_S, &mut flaps);
    }
    let identity = Isometry3::identity();
    let snug =
        Moment::take(&ropes, flaps.through_m(SPACING_M), &identity, flaps.inside_m(&ropes), flaps.gap_m());
    ropes.force_n.copy_from_slice(&weight);
    flaps.load_n = [trial.holding_load_n; 2];
    for _ in 0..(trial.settle_s / DT_S).round() as usize {
        ropes.step_in(DT_S, &mut flaps);
    }
    let after =
        Moment::take(&ropes, flaps.through_m(SPACING_M), &identity, flaps.inside_m(&ropes), flaps.gap_m());
    WoundOutcome::from_moments(knot_laid, length_laid_m, snug, after, ropes.x.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flaps with their four stitch points where the strand's first particle lies (so threading
    /// it moves nothing), at rest.
    fn flaps_at(x0: Vector3<f64>) -> Flaps {
        Flaps {
            tissue: knotlab_bench::shipped_scene().tissue,
            friction: 0.3,
            u_m: [0.0; 2],
            v_m_s: [0.0; 2],
            load_n: [0.0; 2],
            guides: [(0.0, x0); 4],
            pushed: false,
        }
    }

    /// Guards the flaps' report of their pushes, after which the rope solves its contacts with itself
    /// once more: a strand lying half a radius into flap A's top is pushed out and reported, the same
    /// strand lifted clear of the flaps is not.
    #[test]
    fn the_flaps_report_a_push_and_only_a_push() {
        for (depth_radii, pushed) in [(0.5, true), (-5.0, false)] {
            let mut ropes = Ropes::new(RopeParams::default());
            let r = ropes.params.radius_m;
            let z = r * (1.0 - depth_radii);
            ropes.add_strand_along(&[Vector3::new(-0.005, 0.005, z), Vector3::new(0.005, 0.005, z)], 2.0 * r);
            let mut flaps = flaps_at(ropes.x[0]);
            let x_prev = ropes.x.clone();
            flaps.after(&mut ropes, &x_prev, 1e-3);
            assert_eq!(flaps.pushed_the_rope(), pushed, "{depth_radii} radii into the flap");
            // Pushed, every particle but the stitch's first stands on the flap's top.
            let lowest_m = ropes.x.iter().skip(1).map(|x| x.z).fold(f64::INFINITY, f64::min);
            let expected_m = if pushed { r } else { z };
            assert!((lowest_m - expected_m).abs() < 1e-9, "lowest at {lowest_m} m, not {expected_m} m");
        }
    }
}
