//! Force events: episodes where the smoothed magnitude of the measured force rises above the onset
//! threshold until it falls below the release threshold (hysteresis), with their onset, peak and
//! release.

use super::params::DetectorParams;
use super::signal::crossing_time;

/// One force episode.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ForceEpisode {
    /// When the force rose above the onset threshold, s.
    pub onset_s: f64,
    /// Sample of the onset.
    pub onset_index: usize,
    /// Sample of the largest force.
    pub peak_index: usize,
    /// The largest smoothed force, N.
    pub peak_n: f64,
    /// When it fell below the release threshold and the sample (`None` if the recording ends first).
    pub release: Option<(f64, usize)>,
}

/// The force episodes of a smoothed force magnitude.
pub fn force_episodes(times_s: &[f64], force_n: &[f64], params: &DetectorParams) -> Vec<ForceEpisode> {
    let mut out: Vec<ForceEpisode> = Vec::new();
    let mut current: Option<ForceEpisode> = None;
    for k in 0..force_n.len() {
        let f = force_n[k];
        match current.as_mut() {
            None if f > params.force_onset_n => {
                let onset_s = if k > 0 {
                    crossing_time(times_s, force_n, k - 1, params.force_onset_n)
                } else {
                    times_s[0]
                };
                current =
                    Some(ForceEpisode { onset_s, onset_index: k, peak_index: k, peak_n: f, release: None });
            }
            Some(e) => {
                if f > e.peak_n {
                    e.peak_n = f;
                    e.peak_index = k;
                }
                if f < params.force_release_n {
                    let t = crossing_time(times_s, force_n, k - 1, params.force_release_n);
                    e.release = Some((t, k));
                    if t - e.onset_s >= params.min_force_s {
                        out.push(*e);
                    }
                    current = None;
                }
            }
            None => {}
        }
    }
    if let Some(e) = current
        && times_s[times_s.len() - 1] - e.onset_s >= params.min_force_s
    {
        out.push(e);
    }
    out
}
