//! Jaw events: the jaws opening (the angle rising from below the closed threshold to above the open
//! one) and closing (the reverse), timed where the angle left its resting value.

use super::params::DetectorParams;
use super::signal::crossing_time;

/// One jaw movement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JawEvent {
    /// `true` for opening, `false` for closing.
    pub opening: bool,
    /// When the angle left its resting value, s.
    pub time_s: f64,
    /// The sample nearest that time.
    pub index: usize,
    /// Opening: the largest angle before the jaws close again; closing: the angle they closed from, rad.
    pub magnitude_rad: f64,
}

/// The jaw movements in a jaw-angle signal.
pub fn jaw_events(times_s: &[f64], jaw_rad: &[f64], params: &DetectorParams) -> Vec<JawEvent> {
    let n = jaw_rad.len();
    // State: Some(true) open, Some(false) closed, None in between at the start.
    let mut state: Option<bool> = None;
    // The last sample inside the band of the current state.
    let mut last_in_state = 0usize;
    let mut out: Vec<JawEvent> = Vec::new();
    for k in 0..n {
        let a = jaw_rad[k];
        let now = if a > params.jaw_open_rad {
            Some(true)
        } else if a < params.jaw_closed_rad {
            Some(false)
        } else {
            None
        };
        match (state, now) {
            (Some(s), Some(t)) if s == t => last_in_state = k,
            (Some(_), Some(t)) => {
                let (time_s, index) = departure(times_s, jaw_rad, last_in_state, t, params);
                out.push(JawEvent { opening: t, time_s, index, magnitude_rad: 0.0 });
                state = Some(t);
                last_in_state = k;
            }
            (None, Some(t)) => {
                state = Some(t);
                last_in_state = k;
            }
            (_, None) => {}
        }
    }
    // Magnitudes: an opening's largest angle until the next event; a closing's angle before it.
    for j in 0..out.len() {
        let from = out[j].index;
        let to = out.get(j + 1).map_or(n, |e| e.index);
        out[j].magnitude_rad = if out[j].opening {
            jaw_rad[from..to].iter().copied().fold(f64::NEG_INFINITY, f64::max)
        } else {
            let before = if j > 0 { out[j - 1].index } else { 0 };
            jaw_rad[before..=from].iter().copied().fold(f64::NEG_INFINITY, f64::max)
        };
    }
    out
}

/// Where the angle left its resting value before leaving the band at `last`: the rest is the median
/// angle over the 0.2 s up to `last`; going back from `last`, the last sample within
/// `jaw_departure_rad` of it.
fn departure(
    times_s: &[f64],
    jaw: &[f64],
    last: usize,
    opening: bool,
    params: &DetectorParams,
) -> (f64, usize) {
    let t_last = times_s[last];
    let first = times_s.partition_point(|t| *t < t_last - 0.2);
    let mut rest: Vec<f64> = jaw[first..=last].to_vec();
    rest.sort_by(f64::total_cmp);
    let rest = rest[rest.len() / 2];
    let level = if opening { rest + params.jaw_departure_rad } else { rest - params.jaw_departure_rad };
    let beyond = |a: f64| if opening { a > level } else { a < level };
    // Forward from the median window to the first sample beyond the level.
    let mut k = first;
    while k + 1 < jaw.len() && !beyond(jaw[k + 1]) {
        k += 1;
    }
    while k > first && beyond(jaw[k]) {
        k -= 1;
    }
    if k + 1 >= jaw.len() {
        return (times_s[k], k);
    }
    (crossing_time(times_s, jaw, k, level), k + 1)
}
