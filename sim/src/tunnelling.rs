//! Detects one capsule passing through another: for every watched pair of segments, the sign of their
//! separation along the common normal (`dA x dB`). A flip between two steps, while the closest points
//! lie inside both segments, means one went through the other.

use std::collections::HashMap;

use nalgebra::Vector3;

/// A capsule: the segment from `a_m` to `b_m` swept by `radius_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Capsule {
    /// One end of the axis, m.
    pub a_m: Vector3<f64>,
    /// The other end, m.
    pub b_m: Vector3<f64>,
    /// Radius, m.
    pub radius_m: f64,
}

pub use knotlab_hw::geometry::segment_closest_parameters as closest_parameters;

/// The side of `b` relative to `a` along their common normal (0 when the separation along it is
/// within a tenth of the two radii: too close to call, as for two strands lying side by side on one
/// surface); whether the lines' closest points lie inside both segments; and whether the segments'
/// axes come within a quarter of the touching distance. `None` when the pair is out of watch range or
/// nearly parallel.
fn side(a: &Capsule, b: &Capsule, watch_m: f64) -> Option<Side> {
    let (d1, d2) = (a.b_m - a.a_m, b.b_m - b.a_m);
    let (s, t) = closest_parameters(&a.a_m, &d1, &b.a_m, &d2);
    let gap = (b.a_m + d2 * t) - (a.a_m + d1 * s);
    if gap.norm() > watch_m + a.radius_m + b.radius_m {
        return None;
    }
    // Nearly parallel strands lying side by side have no meaningful side: the common normal flips
    // with every small change of their angle. Below about 6 degrees the pair is not judged.
    let normal = d1.cross(&d2);
    if normal.norm() < 0.1 * d1.norm() * d2.norm() {
        return None;
    }
    // Where the infinite lines come closest: inside both segments, or the pair is merely going round
    // an end. A strand going round a chain's bent joint flips the sign of its separation from both
    // segments' lines while it stays clear of the chain (nearly every flip after a knot's release,
    // the segments' axes 0.3-0.8 mm apart throughout); so does a pair whose closest
    // points move from inside onto an end. A strand passing through the chain at a joint comes closer
    // than a quarter of the touching distance to one of its segments.
    let r = a.a_m - b.a_m;
    let (aa, bb, ee, c, f) = (d1.dot(&d1), d1.dot(&d2), d2.dot(&d2), d1.dot(&r), d2.dot(&r));
    let denom = aa * ee - bb * bb;
    let (s_line, t_line) = ((bb * f - c * ee) / denom, (aa * f - bb * c) / denom);
    let reach = a.radius_m + b.radius_m;
    let inside = |x: f64| (0.0..=1.0).contains(&x);
    let _ = (s, t);
    let separation = gap.dot(&normal) / normal.norm();
    let sign = if separation.abs() < 0.1 * reach { 0.0 } else { separation.signum() };
    Some(Side { sign, interior: inside(s_line) && inside(t_line), close: gap.norm() < 0.25 * reach })
}

/// What [`side`] found for a pair.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Side {
    /// -1, 0 (too close to call) or +1.
    sign: f64,
    /// The lines' closest points lie inside both segments.
    interior: bool,
    /// The segments' axes are within a quarter of the touching distance.
    close: bool,
}

/// Watches pairs of capsules from step to step and counts tunnelling events (a strand passing through
/// a chain exactly at a joint flips two pairs, and counts twice).
#[derive(Clone, Debug, Default)]
pub struct TunnellingMonitor {
    last: HashMap<(usize, usize), Side>,
    /// Events counted so far.
    pub events: usize,
    /// The pairs that flipped in the last update.
    pub flipped: Vec<(usize, usize)>,
    /// Extra distance beyond touching within which a pair is watched, m.
    pub watch_m: f64,
}

impl TunnellingMonitor {
    /// A monitor watching pairs closer than `watch_m` beyond touching.
    pub fn new(watch_m: f64) -> Self {
        Self { last: HashMap::new(), events: 0, flipped: Vec::new(), watch_m }
    }

    /// Checks the pairs `(i, j)` of `capsules` after a step; returns the new events.
    pub fn update(&mut self, capsules: &[Capsule], pairs: impl Iterator<Item = (usize, usize)>) -> usize {
        let mut next = HashMap::new();
        let mut new_events = 0;
        self.flipped.clear();
        for (i, j) in pairs {
            let Some(now) = side(&capsules[i], &capsules[j], self.watch_m) else {
                continue;
            };
            let last = self.last.get(&(i, j)).copied();
            if now.sign == 0.0 {
                // Too close to call: remember the last side that was clear.
                if let Some(kept) = last {
                    next.insert((i, j), kept);
                }
                continue;
            }
            // Through: the side changed with the crossing inside both segments at both steps, or with
            // the axes meeting (at a joint) at one of them.
            if let Some(last) = last
                && last.sign != now.sign
                && ((last.interior && now.interior) || last.close || now.close)
            {
                new_events += 1;
                self.flipped.push((i, j));
            }
            next.insert((i, j), now);
        }
        self.last = next;
        self.events += new_events;
        new_events
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cap(a: [f64; 3], b: [f64; 3]) -> Capsule {
        Capsule { a_m: Vector3::from(a), b_m: Vector3::from(b), radius_m: 0.001 }
    }

    /// A segment moved through another over several steps counts as one tunnelling event.
    #[test]
    fn a_segment_moving_through_another_is_one_event() {
        let mut monitor = TunnellingMonitor::new(0.01);
        let fixed = cap([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        for z in [0.004, 0.002, -0.002] {
            let moving = cap([0.0, -1.0, z], [0.0, 1.0, z]);
            monitor.update(&[fixed, moving], [(0, 1)].into_iter());
        }
        assert_eq!(monitor.events, 1);
    }

    /// Regression: strands lying flat on one surface, one's end against the other's side, jitter by a
    /// micrometre in height; their lines cross inside both within the ends' tolerance, and the sign of
    /// a zero separation flipped at every step (89 false events in `knotlab sim`).
    #[test]
    fn strands_side_by_side_on_a_surface_are_not_events() {
        let mut monitor = TunnellingMonitor::new(0.002);
        let r = 0.0004;
        let lying =
            Capsule { a_m: Vector3::new(-0.003, 0.0, 0.0), b_m: Vector3::new(0.003, 0.0, 0.0), radius_m: r };
        for k in 0..100 {
            let z = if k % 2 == 0 { 1e-6 } else { -1e-6 };
            let end_on = Capsule {
                a_m: Vector3::new(0.0, 2.0 * r, z),
                b_m: Vector3::new(0.0, 0.0065, z),
                radius_m: r,
            };
            monitor.update(&[lying, end_on], [(0, 1)].into_iter());
        }
        assert_eq!(monitor.events, 0);
    }

    /// Guards against false events: a strand going round the end of a segment (a chain's bent
    /// joint), 0.5 mm beyond it and never nearer its axis than that, flips the sign of its
    /// separation from the segment's line without passing through (counted as passing within two
    /// radii of the end, such flips make 9-23 false events per knot as the instruments let go).
    #[test]
    fn a_strand_going_round_an_end_clear_of_it_is_not_an_event() {
        let mut monitor = TunnellingMonitor::new(0.002);
        let r = 0.0004;
        let ending = Capsule { a_m: Vector3::new(-0.003, 0.0, 0.0), b_m: Vector3::zeros(), radius_m: r };
        for z in [0.0003, 0.0001, -0.0001, -0.0003] {
            let round = Capsule {
                a_m: Vector3::new(0.0005, -0.003, z),
                b_m: Vector3::new(0.0005, 0.003, z),
                radius_m: r,
            };
            monitor.update(&[ending, round], [(0, 1)].into_iter());
        }
        assert_eq!(monitor.events, 0);
        // The same motion through the end itself (the axes meet) is one.
        let mut monitor = TunnellingMonitor::new(0.002);
        for z in [0.0003, 0.0001, -0.0001, -0.0003] {
            let through =
                Capsule { a_m: Vector3::new(0.0, -0.003, z), b_m: Vector3::new(0.0, 0.003, z), radius_m: r };
            monitor.update(&[ending, through], [(0, 1)].into_iter());
        }
        assert_eq!(monitor.events, 1);
    }

    /// A segment that goes round past the end of another, changing sides beyond it, is no tunnelling event.
    #[test]
    fn a_segment_sliding_off_the_end_is_not_an_event() {
        let mut monitor = TunnellingMonitor::new(0.01);
        let fixed = cap([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        // Passes beyond the end of the fixed segment, then below it.
        for (x, z) in [(0.9, 0.003), (1.1, 0.003), (1.1, -0.003), (0.9, -0.003)] {
            let moving = cap([x, -1.0, z], [x, 1.0, z]);
            monitor.update(&[fixed, moving], [(0, 1)].into_iter());
        }
        assert_eq!(monitor.events, 0);
    }
}
