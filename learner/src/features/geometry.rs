//! The shape of the tip's path inside each motion, measured along the path rather than in time (so
//! that a slow hand's tremor does not masquerade as curvature): the motion's smoothed positions are
//! resampled at equal arc-length steps and smoothed again over a millimetre of path; a plane is fitted
//! locally (principal components over a window of path); in it the signed curvature gives inflection
//! points where it changes sign, and the direction's turning gives loops, each a full turn.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use super::motion::MotionSegment;
use super::params::DetectorParams;
use super::signal::gaussian_smooth;

/// A curvature feature: when, and its magnitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeFeature {
    /// The curvature changed sign here.
    Inflection {
        /// When, s.
        time_s: f64,
        /// The smaller of the peak curvatures either side, 1/m.
        magnitude_per_m: f64,
    },
    /// A full turn completed here.
    Loop {
        /// When, s.
        time_s: f64,
        /// The loop's diameter (twice its median radius of curvature), m.
        diameter_m: f64,
    },
}

/// A motion's path at equal arc-length steps: points, smoothed along the path, and the time at each.
pub struct ArcPath {
    /// The points, m.
    pub points: Vec<Vector3<f64>>,
    /// The time the tip passed each, s.
    pub times_s: Vec<f64>,
}

/// Resamples `points` (at `times_s`) every `step_m` of arc length and smooths them with a Gaussian of
/// `smoothing_m` along the arc. `None` when the path is shorter than four steps.
pub fn arc_path(times_s: &[f64], points: &[Vector3<f64>], step_m: f64, smoothing_m: f64) -> Option<ArcPath> {
    let arc = knotlab_hw::geometry::arc_lengths(points);
    let s = arc.last().copied().unwrap_or(0.0);
    let count = (s / step_m).floor() as usize;
    if count < 4 {
        return None;
    }
    let mut resampled = Vec::with_capacity(count + 1);
    let mut times = Vec::with_capacity(count + 1);
    let mut k = 0;
    for i in 0..=count {
        let target = i as f64 * step_m;
        while k + 2 < arc.len() && arc[k + 1] < target {
            k += 1;
        }
        let span = arc[k + 1] - arc[k];
        let f = if span > 0.0 { ((target - arc[k]) / span).clamp(0.0, 1.0) } else { 0.0 };
        resampled.push(points[k] + (points[k + 1] - points[k]) * f);
        times.push(times_s[k] + (times_s[k + 1] - times_s[k]) * f);
    }
    // Smooth over the arc (the "time" axis of the smoother is the arc length here).
    let stations: Vec<f64> = (0..=count).map(|i| i as f64 * step_m).collect();
    Some(ArcPath { points: gaussian_smooth(&stations, &resampled, smoothing_m), times_s: times })
}

/// Normals of planes fitted to the points within `half_window` samples of each point, oriented
/// consistently along the path; a window whose points lie on a line keeps the previous normal. `None`
/// when no window spans a plane.
pub fn local_normals(points: &[Vector3<f64>], half_window: usize) -> Option<Vec<Vector3<f64>>> {
    // Prefix sums of the points and their outer products: each window's covariance in O(1).
    let m = points.len();
    let origin = points[0];
    let mut sum = vec![Vector3::zeros(); m + 1];
    let mut outer = vec![Matrix3::zeros(); m + 1];
    for k in 0..m {
        let p = points[k] - origin;
        sum[k + 1] = sum[k] + p;
        outer[k + 1] = outer[k] + p * p.transpose();
    }
    let normals: Vec<Option<Vector3<f64>>> = (0..m)
        .map(|k| {
            let (lo, hi) = (k.saturating_sub(half_window), (k + half_window).min(m - 1));
            let count = (hi - lo + 1) as f64;
            let mean = (sum[hi + 1] - sum[lo]) / count;
            let cov = (outer[hi + 1] - outer[lo]) / count - mean * mean.transpose();
            let eig = SymmetricEigen::new(cov);
            let mut order = [0usize, 1, 2];
            order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
            let (small, middle) = (eig.eigenvalues[order[0]], eig.eigenvalues[order[1]]);
            // A plane needs spread in two directions: the middle spread at least (0.2 mm)^2 and
            // clearly above the spread out of the plane.
            let planar = middle > 4e-8 && middle > 4.0 * small.max(0.0);
            planar.then(|| eig.eigenvectors.column(order[0]).into_owned())
        })
        .collect();
    let first = normals.iter().flatten().next().copied()?;
    let mut previous = first;
    Some(
        normals
            .into_iter()
            .map(|n| {
                let mut n = n.unwrap_or(previous);
                if n.dot(&previous) < 0.0 {
                    n = -n;
                }
                previous = n;
                n
            })
            .collect(),
    )
}

/// Inflections and loops inside one motion, from the time-smoothed positions.
pub fn shape_features(
    times_s: &[f64],
    points: &[Vector3<f64>],
    motion: &MotionSegment,
    params: &DetectorParams,
) -> Vec<ShapeFeature> {
    let (start, end) = (motion.start_index, motion.end_index);
    let Some(path) =
        arc_path(&times_s[start..=end], &points[start..=end], params.shape_step_m, params.shape_smoothing_m)
    else {
        return Vec::new();
    };
    let half_window = (params.plane_window_m / params.shape_step_m).round().max(2.0) as usize;
    let Some(normals) = local_normals(&path.points, half_window) else { return Vec::new() };
    let p = &path.points;
    let full = std::f64::consts::TAU * params.loop_turns;
    let mut out = Vec::new();
    // Curvature sign state with hysteresis, the peak of the current run, the last zero crossing, an
    // inflection waiting for the peak of the run after it; turning since the last reset, total
    // turning and curvature per point.
    let mut sign = 0.0f64;
    let mut run_peak = 0.0f64;
    let mut previous_sign = 0.0f64;
    let mut zero_at = 1usize;
    let mut pending: Option<(usize, f64)> = None;
    let mut turned = 0.0f64;
    let mut total = 0.0f64;
    let mut total_turn = vec![0.0f64; p.len()];
    let mut curvatures = vec![0.0f64; p.len()];
    for i in 1..p.len() - 1 {
        let (a, b) = (p[i] - p[i - 1], p[i + 1] - p[i]);
        let n = normals[i];
        // The signed angle from a to b about the plane's normal.
        let angle = a.cross(&b).dot(&n).atan2(a.dot(&b));
        let curvature = angle / params.shape_step_m;
        curvatures[i] = curvature;
        turned += angle;
        total += angle;
        total_turn[i] = total;
        if previous_sign != 0.0 && curvature.signum() != previous_sign {
            zero_at = i;
        }
        previous_sign = curvature.signum();
        if curvature.abs() >= params.inflection_curvature_per_m {
            let s = curvature.signum();
            if sign != 0.0 && s != sign {
                // A sign change between two runs above the threshold: an inflection at the zero.
                if let Some((index, before)) = pending.take() {
                    out.push(ShapeFeature::Inflection {
                        time_s: path.times_s[index],
                        magnitude_per_m: before.min(run_peak),
                    });
                }
                pending = Some((zero_at, run_peak));
                run_peak = 0.0;
                turned = 0.0;
            }
            sign = s;
            run_peak = run_peak.max(curvature.abs());
        }
        if turned.abs() >= full {
            // The loop's points: back from here over the turn it completed.
            let mut first = i;
            while first > 1 && (total - total_turn[first - 1]).abs() < full {
                first -= 1;
            }
            let diameter_m = loop_diameter(&curvatures[first..=i], params.inflection_curvature_per_m);
            out.push(ShapeFeature::Loop { time_s: path.times_s[i], diameter_m });
            turned -= turned.signum() * full;
        }
    }
    if let Some((index, before)) = pending {
        out.push(ShapeFeature::Inflection {
            time_s: path.times_s[index],
            magnitude_per_m: before.min(run_peak),
        });
    }
    let time = |f: &ShapeFeature| match f {
        ShapeFeature::Inflection { time_s, .. } | ShapeFeature::Loop { time_s, .. } => *time_s,
    };
    out.sort_by(|a, b| time(a).total_cmp(&time(b)));
    out
}

/// A loop's diameter: twice the median radius of curvature over its points that curve at least
/// `min_curvature_per_m` (a circle's diameter; straight stretches before the loop do not count).
fn loop_diameter(curvatures: &[f64], min_curvature_per_m: f64) -> f64 {
    let mut radii: Vec<f64> =
        curvatures.iter().filter(|c| c.abs() >= min_curvature_per_m).map(|c| 1.0 / c.abs()).collect();
    if radii.is_empty() {
        return 0.0;
    }
    radii.sort_by(f64::total_cmp);
    2.0 * radii[radii.len() / 2]
}
