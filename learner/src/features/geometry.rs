//! The shape of the tip's path inside each motion: a plane fitted locally (principal components over a
//! sliding window), the signed curvature in it, inflection points where the curvature changes sign, and
//! loops, each a full turn of the tip's direction in its plane.

use nalgebra::{Matrix3, SymmetricEigen, Vector3};

use super::motion::MotionSegment;
use super::params::DetectorParams;

/// A curvature feature: the sample, its kind and its magnitude.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ShapeFeature {
    /// The curvature changed sign at this sample; magnitude 1/m.
    Inflection {
        /// The sample.
        index: usize,
        /// The smaller of the peak curvatures either side, 1/m.
        magnitude_per_m: f64,
    },
    /// A full turn completed at this sample.
    Loop {
        /// The sample.
        index: usize,
        /// The loop's diameter (twice its median radius of curvature), m.
        diameter_m: f64,
    },
}

/// Normals of planes fitted to the points within `half_window_s` of each sample of `[start, end]`,
/// oriented consistently along the motion; a window whose points lie on a line keeps the previous
/// normal. `None` when no window of the motion spans a plane.
pub fn local_normals(
    times_s: &[f64],
    points: &[Vector3<f64>],
    start: usize,
    end: usize,
    half_window_s: f64,
) -> Option<Vec<Vector3<f64>>> {
    // Prefix sums of the points and their outer products: each window's covariance in O(1).
    let m = end - start + 1;
    let mut sum = vec![Vector3::zeros(); m + 1];
    let mut outer = vec![Matrix3::zeros(); m + 1];
    // Centre on the first point for numerical comfort.
    let origin = points[start];
    for k in 0..m {
        let p = points[start + k] - origin;
        sum[k + 1] = sum[k] + p;
        outer[k + 1] = outer[k] + p * p.transpose();
    }
    let mut normals: Vec<Option<Vector3<f64>>> = Vec::with_capacity(m);
    let (mut lo, mut hi) = (0usize, 0usize);
    for k in 0..m {
        let t = times_s[start + k];
        while times_s[start + lo] < t - half_window_s {
            lo += 1;
        }
        while hi + 1 < m && times_s[start + hi + 1] <= t + half_window_s {
            hi += 1;
        }
        let count = (hi - lo + 1) as f64;
        let mean = (sum[hi + 1] - sum[lo]) / count;
        let cov = (outer[hi + 1] - outer[lo]) / count - mean * mean.transpose();
        let eig = SymmetricEigen::new(cov);
        let mut order = [0usize, 1, 2];
        order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
        let (small, middle) = (eig.eigenvalues[order[0]], eig.eigenvalues[order[1]]);
        // A plane needs spread in two directions: the middle spread at least (0.2 mm)^2 and clearly
        // above the spread out of the plane.
        let planar = middle > 4e-8 && middle > 4.0 * small.max(0.0);
        normals.push(planar.then(|| eig.eigenvectors.column(order[0]).into_owned()));
    }
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

/// Inflections and loops inside one motion, from smoothed positions, velocities and accelerations.
pub fn shape_features(
    times_s: &[f64],
    points: &[Vector3<f64>],
    velocity: &[Vector3<f64>],
    acceleration: &[Vector3<f64>],
    motion: &MotionSegment,
    params: &DetectorParams,
) -> Vec<ShapeFeature> {
    let (start, end) = (motion.start_index, motion.end_index);
    let Some(normals) = local_normals(times_s, points, start, end, params.plane_window_s) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    // Curvature sign state with hysteresis, the peak of the current run, the last zero crossing, an
    // inflection waiting for the peak of the run after it.
    let mut sign = 0.0f64;
    let mut run_peak = 0.0f64;
    let mut previous_sign = 0.0f64;
    let mut zero_at = start;
    let mut pending: Option<(usize, f64)> = None;
    let mut turned = 0.0f64;
    // The direction's total turning at each sample since the motion's start (never reset), rad.
    let mut total_turn = vec![0.0f64; end - start + 1];
    // The curvature at each sample (NaN where the tip is too slow), 1/m.
    let mut curvatures = vec![f64::NAN; end - start + 1];
    let mut total = 0.0f64;
    let min_speed =
        params.turning_min_speed_mps.max(params.turning_min_speed_fraction * motion.peak_speed_mps);
    let full = std::f64::consts::TAU * params.loop_turns;
    for k in start..=end {
        let v = velocity[k];
        let speed = v.norm();
        if speed < min_speed {
            total_turn[k - start] = total;
            continue;
        }
        let n = normals[k - start];
        let cross = v.cross(&acceleration[k]).dot(&n);
        let curvature = cross / (speed * speed * speed);
        curvatures[k - start] = curvature;
        let dt = if k > start { times_s[k] - times_s[k - 1] } else { 0.0 };
        // Signed turning rate of the direction in the plane (rad/s), integrated.
        turned += cross / (speed * speed) * dt;
        total += cross / (speed * speed) * dt;
        total_turn[k - start] = total;
        if previous_sign != 0.0 && curvature.signum() != previous_sign {
            zero_at = k;
        }
        previous_sign = curvature.signum();
        if curvature.abs() >= params.inflection_curvature_per_m {
            let s = curvature.signum();
            if sign != 0.0 && s != sign {
                // A sign change between two runs above the threshold: an inflection at the zero.
                if let Some((index, before)) = pending.take() {
                    out.push(ShapeFeature::Inflection { index, magnitude_per_m: before.min(run_peak) });
                }
                pending = Some((zero_at, run_peak));
                run_peak = 0.0;
                turned = 0.0;
            }
            sign = s;
            run_peak = run_peak.max(curvature.abs());
        }
        if turned.abs() >= full {
            // The loop's points: back from here to where the direction pointed the same way.
            let mut first = k;
            while first > start && (total - total_turn[first - 1 - start]).abs() < full {
                first -= 1;
            }
            let diameter_m =
                loop_diameter(&curvatures[first - start..=k - start], params.inflection_curvature_per_m);
            out.push(ShapeFeature::Loop { index: k, diameter_m });
            turned -= turned.signum() * full;
        }
    }
    if let Some((index, before)) = pending {
        out.push(ShapeFeature::Inflection { index, magnitude_per_m: before.min(run_peak) });
    }
    out.sort_by_key(|f| match f {
        ShapeFeature::Inflection { index, .. } | ShapeFeature::Loop { index, .. } => *index,
    });
    out
}

/// A loop's diameter: twice the median radius of curvature over its samples that curve at least
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
