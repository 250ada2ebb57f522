//! Tightness: where the knot sits (the span of its crossings along the thread and in space), and how
//! far it is from the tissue surface and the stitch, for the "knot down" test.

use nalgebra::{Unit, Vector3};

use super::crossings::Crossing;
use super::error::KnotError;

/// Where a knot's crossings sit.
#[derive(Debug, Clone, PartialEq)]
pub struct KnotSpan {
    /// Arc length from the needle end to the first passage through a crossing, m.
    pub start_m: f64,
    /// Arc length from the needle end to the last passage through a crossing, m.
    pub end_m: f64,
    /// The whole thread's length, m.
    pub thread_length_m: f64,
    /// The thread's points where it passes through the crossings (both strands of each), m.
    pub points_m: Vec<Vector3<f64>>,
    /// Mean of `points_m`, m.
    pub centre_m: Vector3<f64>,
    /// Largest distance from `centre_m` to a point of `points_m`, m.
    pub radius_m: f64,
    /// Arc length from the needle end of every passage through a crossing, ascending, m.
    pub passages_m: Vec<f64>,
}

impl KnotSpan {
    /// The span of the given crossings (by index into `crossings`) of a closed picture of `points`
    /// (whose cumulative arc lengths are `arc_m`); passages on the closure are left out. `None` when
    /// no passage lies on the thread.
    pub fn from_crossings(
        points: &[Vector3<f64>],
        arc_m: &[f64],
        crossings: &[Crossing],
        ids: &[u32],
    ) -> Option<Self> {
        let segments = points.len().saturating_sub(1);
        let mut located: Vec<(f64, Vector3<f64>)> = Vec::with_capacity(2 * ids.len());
        for &id in ids {
            let c = crossings.get(id as usize)?;
            for at in [c.over_at, c.under_at] {
                let seg = at.floor() as usize;
                if seg < segments {
                    let t = at - seg as f64;
                    let p = points[seg] + (points[seg + 1] - points[seg]) * t;
                    located.push((arc_m[seg] + t * (arc_m[seg + 1] - arc_m[seg]), p));
                }
            }
        }
        if located.is_empty() {
            return None;
        }
        let mut passages_m: Vec<f64> = located.iter().map(|l| l.0).collect();
        passages_m.sort_by(f64::total_cmp);
        let (start_m, end_m) = (passages_m[0], passages_m[passages_m.len() - 1]);
        let points_m: Vec<Vector3<f64>> = located.into_iter().map(|l| l.1).collect();
        let centre_m = points_m.iter().sum::<Vector3<f64>>() / points_m.len() as f64;
        let radius_m = points_m.iter().map(|p| (p - centre_m).norm()).fold(0.0, f64::max);
        Some(Self {
            start_m,
            end_m,
            thread_length_m: arc_m.last().copied().unwrap_or(0.0),
            points_m,
            centre_m,
            radius_m,
            passages_m,
        })
    }

    /// The thread outside the tissue between the stitch and the knot, both sides together, m: from
    /// the last passage through a crossing before the exit point (arc length `exit_m` from the needle
    /// end) to the exit, plus from the entry (`entry_m`, further along) to the first passage after it.
    /// A knot cinched down on the wound leaves about the two bites; one cinched in the air above it
    /// leaves a loop twice its height, which falls slack once the ends are let go (and, lying over
    /// itself, adds crossings that shorten this). `None` when the knot's crossings do not enclose the
    /// stitch.
    pub fn loop_outside_m(&self, exit_m: f64, entry_m: f64) -> Option<f64> {
        let before = self.passages_m.iter().copied().filter(|&a| a < exit_m).fold(None, |_, a| Some(a))?;
        let after = self.passages_m.iter().copied().find(|&a| a > entry_m)?;
        Some((exit_m - before) + (after - entry_m))
    }

    /// Thread length taken up between the first and last crossing, m: small for a tight knot.
    pub fn length_m(&self) -> f64 {
        self.end_m - self.start_m
    }
}

/// The tissue's surface near the stitch, as a plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TissueSurface {
    /// A point on the surface, m.
    pub point_m: Vector3<f64>,
    /// Unit normal pointing out of the tissue (towards where the knot is tied).
    pub normal: Unit<Vector3<f64>>,
}

impl TissueSurface {
    /// A surface through `point_m` with outward normal `normal` (any length but zero).
    pub fn new(point_m: Vector3<f64>, normal: Vector3<f64>) -> Result<Self, KnotError> {
        let bad = KnotError::BadNormal { normal: [normal.x, normal.y, normal.z] };
        if !normal.iter().all(|c| c.is_finite()) || !point_m.iter().all(|c| c.is_finite()) {
            return Err(bad);
        }
        let normal = Unit::try_new(normal, 1e-12).ok_or(bad)?;
        Ok(Self { point_m, normal })
    }

    /// Signed height of a point above the surface, m (negative inside the tissue).
    pub fn height_m(&self, p: &Vector3<f64>) -> f64 {
        (p - self.point_m).dot(&self.normal)
    }
}

/// Where the knot is, relative to the tissue and the stitch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KnotPlacement {
    /// Height of the knot's lowest crossing point above the tissue, m.
    pub height_m: f64,
    /// Height of its highest crossing point, m.
    pub top_height_m: f64,
    /// Distance from the stitch to the nearest crossing point of the knot, m.
    pub stitch_distance_m: f64,
    /// Distance from the stitch to the knot's centre, m.
    pub centre_stitch_distance_m: f64,
}

/// A knot's crossing point this far under the tissue's surface is the suture inside the tissue, m.
pub const INSIDE_TISSUE_M: f64 = 0.001;

/// How close "down" is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DownLimits {
    /// Largest height of the knot's lowest crossing above the tissue, m.
    pub max_height_m: f64,
    /// Largest distance from the stitch to the knot's nearest crossing, m.
    pub max_stitch_distance_m: f64,
}

impl Default for DownLimits {
    /// 2 mm above the tissue (a few thread diameters of a 3-0 suture), within 6 mm of the stitch
    /// (a bite's width); scenes with other sutures set their own.
    fn default() -> Self {
        Self { max_height_m: 0.002, max_stitch_distance_m: 0.006 }
    }
}

impl KnotPlacement {
    /// Measures a knot's span against the tissue surface and the stitch point. Crossing points more
    /// than [`INSIDE_TISSUE_M`] under the surface are left out (unless every point is): they are the
    /// suture running under the wound, crossed by the knot above it in the picture, not the knot.
    pub fn measure(span: &KnotSpan, surface: &TissueSurface, stitch_m: &Vector3<f64>) -> Self {
        let above: Vec<&Vector3<f64>> =
            span.points_m.iter().filter(|p| surface.height_m(p) >= -INSIDE_TISSUE_M).collect();
        let points: Vec<&Vector3<f64>> =
            if above.is_empty() { span.points_m.iter().collect() } else { above };
        let heights = points.iter().map(|p| surface.height_m(p));
        let height_m = heights.clone().fold(f64::INFINITY, f64::min);
        let top_height_m = heights.fold(f64::NEG_INFINITY, f64::max);
        let stitch_distance_m = points.iter().map(|p| (*p - stitch_m).norm()).fold(f64::INFINITY, f64::min);
        Self {
            height_m,
            top_height_m,
            stitch_distance_m,
            centre_stitch_distance_m: (span.centre_m - stitch_m).norm(),
        }
    }

    /// Whether the knot is down: its lowest crossing near the tissue, its nearest crossing near the
    /// stitch.
    pub fn is_down(&self, limits: &DownLimits) -> bool {
        self.height_m <= limits.max_height_m && self.stitch_distance_m <= limits.max_stitch_distance_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn span_at(points: &[Vector3<f64>]) -> KnotSpan {
        let centre_m = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
        KnotSpan {
            start_m: 0.1,
            end_m: 0.12,
            thread_length_m: 0.3,
            points_m: points.to_vec(),
            centre_m,
            radius_m: 0.0,
            passages_m: vec![0.1, 0.12],
        }
    }

    /// Crossings with the suture running under the wound are left out of the knot's height and stitch
    /// distance, while points just under the surface, or all of them under it, still count.
    #[test]
    fn crossings_with_the_suture_under_the_wound_are_not_the_knot() {
        let surface = TissueSurface::new(Vector3::zeros(), Vector3::z()).expect("a surface");
        let stitch = Vector3::zeros();
        // Coils 5 and 7 mm up, crossing the suture's U 3 mm under the wound in the picture.
        let span = span_at(&[
            Vector3::new(0.0, 0.001, 0.005),
            Vector3::new(0.0, 0.0, -0.003),
            Vector3::new(0.0, -0.001, 0.007),
        ]);
        let placement = KnotPlacement::measure(&span, &surface, &stitch);
        assert!((placement.height_m - 0.005).abs() < 1e-12, "{placement:?}");
        assert!((placement.top_height_m - 0.007).abs() < 1e-12);
        assert!((placement.stitch_distance_m - (0.005f64.powi(2) + 0.001f64.powi(2)).sqrt()).abs() < 1e-12);
        // Just under the surface (a thread lying on it, within its radius) still counts.
        let low = span_at(&[Vector3::new(0.0, 0.0, -0.0003), Vector3::new(0.0, 0.0, 0.004)]);
        assert!((KnotPlacement::measure(&low, &surface, &stitch).height_m + 0.0003).abs() < 1e-12);
        // All under the surface: measured as it is.
        let under = span_at(&[Vector3::new(0.0, 0.0, -0.003)]);
        assert!((KnotPlacement::measure(&under, &surface, &stitch).height_m + 0.003).abs() < 1e-12);
    }

    /// The loop outside the tissue runs from the knot's passages to the exit and from the entry back to the
    /// knot, and a knot all on one side of the stitch closes no loop.
    #[test]
    fn the_loop_outside_runs_from_the_knot_to_the_exit_and_from_the_entry_to_the_knot() {
        // Wraps at 100-110 mm, the exit at 150 mm, the entry at 165 mm, the tail through at 210 mm.
        let span =
            KnotSpan { passages_m: vec![0.10, 0.105, 0.11, 0.21, 0.21], ..span_at(&[Vector3::zeros()]) };
        let outside = span.loop_outside_m(0.15, 0.165).expect("the knot encloses the stitch");
        assert!((outside - (0.04 + 0.045)).abs() < 1e-12, "{outside}");
        // Cinched down: the passages close to the points.
        let down = KnotSpan { passages_m: vec![0.145, 0.147, 0.17], ..span.clone() };
        assert!((down.loop_outside_m(0.15, 0.165).unwrap() - 0.008).abs() < 1e-12);
        // A knot all on one side of the stitch does not close a loop through it.
        let aside = KnotSpan { passages_m: vec![0.01, 0.02], ..span };
        assert_eq!(aside.loop_outside_m(0.15, 0.165), None);
    }

    /// A knot 1 mm above an offset surface at the stitch is down; one higher up or 1 cm from the stitch is
    /// not, and a zero or NaN surface normal is refused.
    #[test]
    fn placement_against_a_tilted_surface() {
        let surface =
            TissueSurface::new(Vector3::new(0.0, 0.0, 0.8), Vector3::new(0.0, 0.0, 2.0)).expect("normal");
        let stitch = Vector3::new(0.0, 0.0, 0.8);
        let low = span_at(&[Vector3::new(0.001, 0.0, 0.801), Vector3::new(0.002, 0.0, 0.804)]);
        let p = KnotPlacement::measure(&low, &surface, &stitch);
        assert!((p.height_m - 0.001).abs() < 1e-12 && (p.top_height_m - 0.004).abs() < 1e-12);
        assert!((p.stitch_distance_m - 2f64.sqrt() * 0.001).abs() < 1e-12);
        assert!(p.is_down(&DownLimits::default()));
        // The same knot 5 mm up the thread is not down; nor is one down on the tissue but 1 cm away.
        let high = span_at(&[Vector3::new(0.001, 0.0, 0.806), Vector3::new(0.002, 0.0, 0.809)]);
        assert!(!KnotPlacement::measure(&high, &surface, &stitch).is_down(&DownLimits::default()));
        let aside = span_at(&[Vector3::new(0.01, 0.0, 0.801)]);
        assert!(!KnotPlacement::measure(&aside, &surface, &stitch).is_down(&DownLimits::default()));
        assert!(TissueSurface::new(stitch, Vector3::zeros()).is_err());
        assert!(TissueSurface::new(stitch, Vector3::new(f64::NAN, 0.0, 1.0)).is_err());
    }

    /// A knot's span takes its arc-length range and points from passages on the thread, not on the closure.
    #[test]
    fn span_locates_passages_on_the_thread_only() {
        let points: Vec<Vector3<f64>> = (0..5).map(|i| Vector3::new(i as f64, 0.0, 0.0)).collect();
        let arc: Vec<f64> = (0..5).map(|i| i as f64).collect();
        // Crossing 0 on segments 0.5 and 2.25; crossing 1 between segment 3.5 and the closure (6.0).
        let crossings = [
            Crossing { over_at: 0.5, under_at: 2.25, sign: 1 },
            Crossing { over_at: 6.0, under_at: 3.5, sign: 1 },
        ];
        let span = KnotSpan::from_crossings(&points, &arc, &crossings, &[0, 1]).expect("on the thread");
        assert_eq!((span.start_m, span.end_m, span.length_m()), (0.5, 3.5, 3.0));
        assert_eq!(span.points_m.len(), 3);
        assert!((span.centre_m.x - 2.0833333333333335).abs() < 1e-12);
    }
}
