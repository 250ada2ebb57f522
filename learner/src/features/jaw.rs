//! Jaw events: the jaws opening (the angle rising from below the closed threshold to above the open
//! one) and closing (the reverse), timed where the angle left its resting value.

use super::params::DetectorParams;

/// One jaw movement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JawEvent {
    /// `true` for opening, `false` for closing.
    pub opening: bool,
    /// When the angle left its resting value, s.
    pub time_s: f64,
    /// The sample nearest that time.
    pub index: usize,
    /// When the movement ended: after entering the open (or closed) band, the angle changed by less than
    /// half `jaw_departure_rad` over the next 0.1 s, s.
    pub ended_s: f64,
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
                let floor = out.last().map_or(0, |e| e.index);
                let (time_s, index) = departure(times_s, jaw_rad, (last_in_state, floor), t, params);
                out.push(JawEvent {
                    opening: t,
                    time_s,
                    index,
                    ended_s: ended(times_s, jaw_rad, k, params),
                    magnitude_rad: 0.0,
                });
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

/// When the jaw movement that entered a band at sample `k` came to rest.
fn ended(times_s: &[f64], jaw: &[f64], mut k: usize, params: &DetectorParams) -> f64 {
    let n = jaw.len();
    loop {
        let mut j = k;
        while j + 1 < n && times_s[j + 1] - times_s[k] <= 0.1 {
            j += 1;
        }
        let still = (k..=j).all(|i| (jaw[i] - jaw[k]).abs() < 0.5 * params.jaw_departure_rad);
        if still || j + 1 >= n {
            return times_s[k];
        }
        k += 1;
    }
}

/// Where the angle left its resting value before leaving the band at `last` (the last sample inside
/// it), not before sample `floor` (the previous event): walking back from `last` while the angle keeps
/// moving away from the new band finds the resting plateau (0.1 s without further change beyond half
/// `jaw_departure_rad`); its median is the rest; the movement starts where the angle passes the rest by
/// `jaw_departure_rad`.
fn departure(
    times_s: &[f64],
    jaw: &[f64],
    (last, floor): (usize, usize),
    opening: bool,
    params: &DetectorParams,
) -> (f64, usize) {
    // In `v` the movement always goes up.
    let sign = if opening { 1.0 } else { -1.0 };
    let v = |k: usize| sign * jaw[k];
    let (mut k, mut lowest) = (last, last);
    while k > floor {
        k -= 1;
        if v(k) < v(lowest) - 0.5 * params.jaw_departure_rad {
            lowest = k;
        } else if times_s[lowest] - times_s[k] > 0.1 {
            break;
        }
    }
    let mut plateau: Vec<f64> = (k..=lowest).map(v).collect();
    plateau.sort_by(f64::total_cmp);
    let level = plateau[plateau.len() / 2] + params.jaw_departure_rad;
    let mut j = lowest;
    while j + 1 < jaw.len() && v(j + 1) <= level {
        j += 1;
    }
    if j + 1 >= jaw.len() {
        return (times_s[j], j);
    }
    let (a, b) = (v(j), v(j + 1));
    let f = if b > a { ((level - a) / (b - a)).clamp(0.0, 1.0) } else { 0.0 };
    (times_s[j] + f * (times_s[j + 1] - times_s[j]), j + 1)
}
