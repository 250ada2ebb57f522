//! Rapid speed changes: where the tip starts and stops moving (speed thresholds with hysteresis, short
//! rests merged, the start and end extrapolated to where the speed left zero), and peaks of the
//! tangential acceleration.

use nalgebra::Vector3;

use super::params::DetectorParams;
use super::signal::{crossing_time, derivative, derivative_scalar, gaussian_smooth};

/// One motion of the tip between two rests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MotionSegment {
    /// When the motion starts (extrapolated to where the speed leaves zero), s.
    pub start_s: f64,
    /// When it ends, s.
    pub end_s: f64,
    /// First sample inside the motion.
    pub start_index: usize,
    /// Last sample inside the motion.
    pub end_index: usize,
    /// Largest smoothed speed, m/s.
    pub peak_speed_mps: f64,
    /// Length of the smoothed path, m.
    pub path_length_m: f64,
}

/// The motions of a tip: `raw_m` are its recorded positions, `speed_mps` the speed of the positions
/// smoothed by `params.smoothing_s`, `path_step_m[k]` the smoothed path's length between samples `k`
/// and `k + 1`. A slow motion's start and end are found on a speed smoothed more (a twenty-fifth of
/// its duration), where its slow rise stands clear of the tremor.
pub fn motion_segments(
    times_s: &[f64],
    raw_m: &[Vector3<f64>],
    speed_mps: &[f64],
    path_step_m: &[f64],
    params: &DetectorParams,
) -> Vec<MotionSegment> {
    let n = times_s.len();
    // 1. Hysteresis: [first sample above on, first sample below off).
    let mut raw: Vec<(usize, usize)> = Vec::new();
    let mut start: Option<usize> = None;
    for (k, &speed) in speed_mps.iter().enumerate() {
        match start {
            None if speed > params.motion_on_mps => start = Some(k),
            Some(s) if speed < params.motion_off_mps => {
                raw.push((s, k));
                start = None;
            }
            _ => {}
        }
    }
    if let Some(s) = start {
        raw.push((s, n));
    }
    // 2. Rests shorter than min_pause_s are no rests.
    let mut merged: Vec<(usize, usize)> = Vec::new();
    for (s, e) in raw {
        if let Some(last) = merged.last_mut()
            && times_s[s] - times_s[last.1.min(n - 1)] < params.min_pause_s
        {
            last.1 = e;
            continue;
        }
        merged.push((s, e));
    }
    // 3. Drop motions too short in time or in space.
    let length = |s: usize, e: usize| path_step_m[s.saturating_sub(1)..e.min(n - 1)].iter().sum::<f64>();
    let kept: Vec<(usize, usize)> = merged
        .into_iter()
        .filter(|&(s, e)| {
            let end_t = times_s[e.min(n - 1)];
            end_t - times_s[s] >= params.min_motion_s && length(s, e) >= params.min_travel_m
        })
        .collect();
    // 4. Extrapolate each start and end to where the speed left zero, within the rests around it.
    let base_floor = (4.0 * rest_speed(speed_mps)).max(0.001);
    let mut resmoothed: Vec<(f64, Vec<f64>, f64)> = Vec::new();
    let mut out = Vec::with_capacity(kept.len());
    for (j, &(s, e)) in kept.iter().enumerate() {
        let lower = if j == 0 { 0 } else { kept[j - 1].1.min(n - 1) };
        let upper = if j + 1 < kept.len() { kept[j + 1].0 } else { n - 1 };
        let peak = speed_mps[s..e].iter().copied().fold(0.0f64, f64::max);
        // A slow motion: its speed smoothed more, in steps of 10 ms (computed once per step).
        let duration = times_s[e.min(n - 1)] - times_s[s];
        let sigma = ((duration / 25.0 / 0.01).round() * 0.01).min(0.3);
        let (speed, floor, sigma) = if sigma > 1.25 * params.smoothing_s {
            if !resmoothed.iter().any(|(x, _, _)| *x == sigma) {
                let positions = gaussian_smooth(times_s, raw_m, sigma);
                let speed: Vec<f64> = derivative(times_s, &positions).iter().map(|v| v.norm()).collect();
                let floor = (4.0 * rest_speed(&speed)).max(0.001);
                resmoothed.push((sigma, speed, floor));
            }
            let (_, speed, floor) = resmoothed
                .iter()
                .find(|(x, _, _)| *x == sigma)
                .expect("the speed for this smoothing was just made");
            (speed.as_slice(), *floor, sigma)
        } else {
            (speed_mps, base_floor, params.smoothing_s)
        };
        let fit = Fit {
            floor,
            sigma_s: sigma,
            peak: speed[s..e.min(n - 1).max(s + 1)].iter().copied().fold(0.0, f64::max),
        };
        let start_s = refine_start(times_s, speed, s, lower, &fit, params);
        let end_s = refine_end(times_s, speed, e.min(n - 1), upper, &fit, params);
        out.push(MotionSegment {
            start_s,
            end_s,
            start_index: s,
            end_index: e.min(n - 1),
            peak_speed_mps: peak,
            path_length_m: length(s, e),
        });
    }
    out
}

/// What the fit of one motion's start and end works with.
struct Fit {
    /// The lowest level that stands clear of the tremor at rest, m/s.
    floor: f64,
    /// The smoothing of the speed, s.
    sigma_s: f64,
    /// The motion's peak speed, m/s.
    peak: f64,
}

/// The two speed levels of the fit: the onset fractions of the peak, the lower one at least `floor`
/// (above the tremor left at rest), the higher one at least twice the lower; `None` when the motion is
/// too slow for two levels below 70 % of its peak (then the threshold crossing is used).
fn levels(peak: f64, floor: f64, params: &DetectorParams) -> Option<(f64, f64)> {
    let [f1, f2] = params.onset_fractions;
    let low = (f1 * peak).max(floor);
    let high = (f2 * peak).max(2.0 * low);
    (high <= 0.7 * peak).then_some((low, high))
}

/// The speed the smoothed tip shows at rest (tremor, sensor noise): the 20th percentile of the speed,
/// as an instrument rests much of the time.
fn rest_speed(speed_mps: &[f64]) -> f64 {
    let mut sorted = speed_mps.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted[sorted.len() / 5]
}

/// A minimum-jerk movement of unit duration: its speed relative to the peak, `16 x^2 (1 - x)^2`.
fn bell(x: f64) -> f64 {
    if (0.0..=1.0).contains(&x) { 16.0 * x * x * (1.0 - x) * (1.0 - x) } else { 0.0 }
}

/// [`bell`] smoothed by a Gaussian of standard deviation `s` (in units of the duration), by Simpson's
/// rule over five standard deviations either side.
fn smoothed_bell(x: f64, s: f64) -> f64 {
    if s < 1e-4 {
        return bell(x);
    }
    let (a, b) = ((x - 5.0 * s).max(0.0), (x + 5.0 * s).min(1.0));
    if b <= a {
        return 0.0;
    }
    let n = 200;
    let h = (b - a) / n as f64;
    let f = |y: f64| bell(y) * (-0.5 * ((x - y) / s).powi(2)).exp();
    let mut sum = f(a) + f(b);
    for k in 1..n {
        sum += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0 / (s * (std::f64::consts::TAU).sqrt())
}

/// Where the smoothed bell rises through `fraction` of its (smoothed) peak, by bisection.
fn bell_crossing(fraction: f64, s: f64) -> f64 {
    let target = fraction * smoothed_bell(0.5, s);
    let (mut lo, mut hi) = (-5.0 * s, 0.5);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if smoothed_bell(mid, s) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Fits a minimum-jerk start, as seen through the Gaussian smoothing of standard deviation `sigma_s`, to
/// the times `ta` < `tb` where the speed rose through the fractions `fa` < `fb` of its peak: returns the
/// start time, or `None` when the fit has no solution. (Human reaching movements have close to
/// minimum-jerk speed profiles, Flash and Hogan 1985; the start is where the fitted profile leaves zero.)
pub fn fit_minimum_jerk_start(ta: f64, tb: f64, fa: f64, fb: f64, sigma_s: f64) -> Option<f64> {
    if !(tb > ta && 0.0 < fa && fa < fb && fb < 1.0) {
        return None;
    }
    let (mut xa, mut xb) = (bell_crossing(fa, 0.0), bell_crossing(fb, 0.0));
    let mut duration = (tb - ta) / (xb - xa);
    for _ in 0..4 {
        let s = sigma_s / duration;
        xa = bell_crossing(fa, s);
        xb = bell_crossing(fb, s);
        if xb <= xa {
            return None;
        }
        duration = (tb - ta) / (xb - xa);
    }
    Some(ta - xa * duration)
}

/// The start of a motion: where the speed crosses the two levels near the threshold crossing `on`, and
/// a minimum-jerk start fitted to them (see [`fit_minimum_jerk_start`]), not before `lower`.
fn refine_start(
    times_s: &[f64],
    speed: &[f64],
    on: usize,
    lower: usize,
    fit: &Fit,
    params: &DetectorParams,
) -> f64 {
    let fallback =
        if on > lower { crossing_time(times_s, speed, on - 1, params.motion_on_mps) } else { times_s[on] };
    let Some((low, high)) = levels(fit.peak, fit.floor, params) else { return fallback };
    // The high crossing: forward from `on` (or back, if `on` is already above it).
    let mut kb = on;
    while kb > lower && speed[kb - 1] >= high {
        kb -= 1;
    }
    while kb + 1 < speed.len() && speed[kb] < high {
        kb += 1;
    }
    let mut ka = kb;
    while ka > lower && speed[ka] >= low {
        ka -= 1;
    }
    if ka == kb || speed[ka] >= low || kb == 0 {
        return fallback;
    }
    let ta = crossing_time(times_s, speed, ka, low);
    let tb = crossing_time(times_s, speed, kb - 1, high);
    fit_minimum_jerk_start(ta, tb, low / fit.peak, high / fit.peak, fit.sigma_s)
        .map_or(fallback, |t0| t0.clamp(times_s[lower], ta))
}

/// The mirror image of [`refine_start`] at the end of a motion.
fn refine_end(
    times_s: &[f64],
    speed: &[f64],
    off: usize,
    upper: usize,
    fit: &Fit,
    params: &DetectorParams,
) -> f64 {
    let fallback =
        if off > 0 { crossing_time(times_s, speed, off - 1, params.motion_off_mps) } else { times_s[off] };
    let Some((low, high)) = levels(fit.peak, fit.floor, params) else { return fallback };
    let mut kb = off;
    while kb < upper && speed[kb + 1] >= high {
        kb += 1;
    }
    while kb > 0 && speed[kb] < high {
        kb -= 1;
    }
    let mut ka = kb;
    while ka < upper && speed[ka] >= low {
        ka += 1;
    }
    if ka == kb || speed[ka] >= low {
        return fallback;
    }
    let ta = crossing_time(times_s, speed, ka - 1, low);
    let tb = crossing_time(times_s, speed, kb, high);
    // Time reversed, the end is a start.
    fit_minimum_jerk_start(-ta, -tb, low / fit.peak, high / fit.peak, fit.sigma_s)
        .map_or(fallback, |t| (-t).clamp(ta, times_s[upper]))
}

/// Peaks of the tangential acceleration (`+1`) or deceleration (`-1`) above the threshold inside the
/// motions: `(sample, magnitude in m/s^2)`.
pub fn acceleration_peaks(
    times_s: &[f64],
    speed_mps: &[f64],
    motions: &[MotionSegment],
    params: &DetectorParams,
    sign: f64,
) -> Vec<(usize, f64)> {
    let accel = derivative_scalar(times_s, speed_mps);
    let mut out = Vec::new();
    for m in motions {
        let mut best: Option<(usize, f64)> = None;
        for (k, a) in accel.iter().enumerate().take(m.end_index + 1).skip(m.start_index) {
            let a = sign * a;
            if a > params.acceleration_mps2 {
                if best.is_none_or(|(_, b)| a > b) {
                    best = Some((k, a));
                }
            } else if let Some(b) = best.take() {
                out.push(b);
            }
        }
        if let Some(b) = best {
            out.push(b);
        }
    }
    out
}
