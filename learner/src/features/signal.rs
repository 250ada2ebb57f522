//! Signal helpers for the detectors: Gaussian smoothing over sample times (tolerant of jittered
//! spacing), central differences, and level crossings interpolated between samples.

use nalgebra::Vector3;

/// Smooths `values` (sampled at `times_s`) with a Gaussian of standard deviation `sigma_s`, cut at four
/// sigma; near the ends the kernel is renormalised over the samples that exist.
pub fn gaussian_smooth<T>(times_s: &[f64], values: &[T], sigma_s: f64) -> Vec<T>
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    let n = times_s.len();
    let reach = 4.0 * sigma_s;
    let mut out = Vec::with_capacity(n);
    let mut lo = 0;
    let mut hi = 0;
    for k in 0..n {
        let t = times_s[k];
        while times_s[lo] < t - reach {
            lo += 1;
        }
        while hi + 1 < n && times_s[hi + 1] <= t + reach {
            hi += 1;
        }
        let mut total = 0.0;
        let mut acc: Option<T> = None;
        for i in lo..=hi {
            let d = (times_s[i] - t) / sigma_s;
            let w = (-0.5 * d * d).exp();
            total += w;
            acc = Some(match acc {
                None => values[i] * w,
                Some(a) => a + values[i] * w,
            });
        }
        // The sample itself always lies in its window, so `acc` is set and `total` is at least 1.
        out.push(acc.map_or(values[k], |a| a * (1.0 / total)));
    }
    out
}

/// Central differences `d values / d t` (one-sided at the ends).
pub fn derivative(times_s: &[f64], values: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let n = values.len();
    (0..n)
        .map(|k| {
            let a = k.saturating_sub(1);
            let b = (k + 1).min(n - 1);
            if b == a { Vector3::zeros() } else { (values[b] - values[a]) / (times_s[b] - times_s[a]) }
        })
        .collect()
}

/// Central differences of a scalar signal.
pub fn derivative_scalar(times_s: &[f64], values: &[f64]) -> Vec<f64> {
    let n = values.len();
    (0..n)
        .map(|k| {
            let a = k.saturating_sub(1);
            let b = (k + 1).min(n - 1);
            if b == a { 0.0 } else { (values[b] - values[a]) / (times_s[b] - times_s[a]) }
        })
        .collect()
}

/// The time where the signal crosses `level` between samples `k` and `k + 1` (linear interpolation).
pub fn crossing_time(times_s: &[f64], values: &[f64], k: usize, level: f64) -> f64 {
    let (a, b) = (values[k], values[k + 1]);
    let f = if (b - a).abs() > 0.0 { ((level - a) / (b - a)).clamp(0.0, 1.0) } else { 0.0 };
    times_s[k] + f * (times_s[k + 1] - times_s[k])
}

/// Index of the sample nearest to `time_s` (the times are increasing).
pub fn index_at(times_s: &[f64], time_s: f64) -> usize {
    let after = times_s.partition_point(|t| *t < time_s);
    if after == 0 {
        0
    } else if after >= times_s.len() {
        times_s.len() - 1
    } else if time_s - times_s[after - 1] <= times_s[after] - time_s {
        after - 1
    } else {
        after
    }
}

/// The value of a vector signal at `time_s`, linear between samples, held beyond the ends.
pub fn vector_at(times_s: &[f64], values: &[Vector3<f64>], time_s: f64) -> Vector3<f64> {
    let after = times_s.partition_point(|t| *t <= time_s);
    if after == 0 {
        return values[0];
    }
    if after >= times_s.len() {
        return values[values.len() - 1];
    }
    let (ta, tb) = (times_s[after - 1], times_s[after]);
    let f = if tb > ta { (time_s - ta) / (tb - ta) } else { 0.0 };
    values[after - 1] + (values[after] - values[after - 1]) * f
}
