//! The feature detectors' thresholds, with defaults that work on the scripted expert's demonstrations
//! and on synthetic ones with tremor (0.1-0.2 mm at 8-12 Hz) and force noise (0.01-0.02 N per axis).
//! A task pattern may override any of them in its `[detector]` table.

use serde::{Deserialize, Serialize};

/// Thresholds and windows of the feature detectors. SI units.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct DetectorParams {
    /// Standard deviation of the Gaussian that smooths the tip positions before differentiating, s
    /// (40 ms leaves about 4 % of an 8 Hz tremor).
    pub smoothing_s: f64,
    /// A rest ends when the smoothed speed rises above this, m/s.
    pub motion_on_mps: f64,
    /// A motion ends when the smoothed speed falls below this, m/s.
    pub motion_off_mps: f64,
    /// A rest shorter than this inside a motion is no rest: the motions either side are one, s.
    pub min_pause_s: f64,
    /// Motions shorter than this are dropped, s.
    pub min_motion_s: f64,
    /// Motions whose path is shorter than this are dropped, m.
    pub min_travel_m: f64,
    /// The start and end of a motion are found by fitting a minimum-jerk speed profile (as the
    /// smoothing shows it) to where the speed crosses these two fractions of the motion's peak speed
    /// (the lower one at least four times the speed the tip shows at rest, the higher one at least
    /// twice the lower).
    pub onset_fractions: [f64; 2],
    /// Peaks of the tangential acceleration above this are acceleration / deceleration features, m/s^2.
    pub acceleration_mps2: f64,
    /// Curvature below this does not count for inflections, 1/m.
    pub inflection_curvature_per_m: f64,
    /// The path's shape is measured on points this far apart along it, m.
    pub shape_step_m: f64,
    /// ... smoothed along the path with a Gaussian of this standard deviation (a hand's tremor, a
    /// fraction of a millimetre, is gone; a loop of 1 cm keeps its shape), m.
    pub shape_smoothing_m: f64,
    /// Half the length of path the local plane is fitted to, m.
    pub plane_window_m: f64,
    /// A loop is counted each time the direction has turned through this many full turns since the
    /// motion's start, the last inflection or the last loop (a little under one, so that a wrap whose
    /// lead-in and lead-out turn back a little still counts).
    pub loop_turns: f64,
    /// Standard deviation of the Gaussian that smooths the force magnitude, s.
    pub force_smoothing_s: f64,
    /// A force episode starts when the smoothed force rises above this, N.
    pub force_onset_n: f64,
    /// A force episode ends when the smoothed force falls below this, N.
    pub force_release_n: f64,
    /// Force episodes shorter than this are dropped, s.
    pub min_force_s: f64,
    /// The jaws count as open above this angle, rad.
    pub jaw_open_rad: f64,
    /// The jaws count as closed below this angle, rad.
    pub jaw_closed_rad: f64,
    /// A jaw movement starts where the angle leaves its resting value by this much, rad.
    pub jaw_departure_rad: f64,
}

impl Default for DetectorParams {
    fn default() -> Self {
        Self {
            smoothing_s: 0.04,
            motion_on_mps: 0.004,
            motion_off_mps: 0.0025,
            min_pause_s: 0.06,
            min_motion_s: 0.12,
            min_travel_m: 0.001,
            onset_fractions: [0.06, 0.24],
            acceleration_mps2: 0.5,
            inflection_curvature_per_m: 15.0,
            shape_step_m: 0.0002,
            shape_smoothing_m: 0.001,
            plane_window_m: 0.01,
            loop_turns: 0.85,
            force_smoothing_s: 0.01,
            force_onset_n: 0.2,
            force_release_n: 0.1,
            min_force_s: 0.03,
            jaw_open_rad: 0.3,
            jaw_closed_rad: 0.15,
            jaw_departure_rad: 0.02,
        }
    }
}

/// The closest the path's shape may be measured along it, m: with the demonstration's tip speed
/// bounded, this bounds the points the shape is resampled to.
pub const MIN_SHAPE_STEP_M: f64 = 1e-4;

/// The farthest, m: a loop of 1 cm must still show.
pub const MAX_SHAPE_STEP_M: f64 = 0.01;

impl DetectorParams {
    /// Checks every field; `(field, reason)` of the first bad one.
    pub fn check(&self) -> Result<(), (&'static str, String)> {
        let positive = [
            ("smoothing_s", self.smoothing_s),
            ("motion_on_mps", self.motion_on_mps),
            ("motion_off_mps", self.motion_off_mps),
            ("min_pause_s", self.min_pause_s),
            ("min_motion_s", self.min_motion_s),
            ("min_travel_m", self.min_travel_m),
            ("acceleration_mps2", self.acceleration_mps2),
            ("inflection_curvature_per_m", self.inflection_curvature_per_m),
            ("shape_step_m", self.shape_step_m),
            ("shape_smoothing_m", self.shape_smoothing_m),
            ("plane_window_m", self.plane_window_m),
            ("loop_turns", self.loop_turns),
            ("force_smoothing_s", self.force_smoothing_s),
            ("force_onset_n", self.force_onset_n),
            ("force_release_n", self.force_release_n),
            ("min_force_s", self.min_force_s),
            ("jaw_open_rad", self.jaw_open_rad),
            ("jaw_closed_rad", self.jaw_closed_rad),
            ("jaw_departure_rad", self.jaw_departure_rad),
        ];
        for (name, x) in positive {
            if !(x.is_finite() && x > 0.0) {
                return Err((name, format!("must be positive, got {x}")));
            }
        }
        if !(MIN_SHAPE_STEP_M..=MAX_SHAPE_STEP_M).contains(&self.shape_step_m) {
            return Err((
                "shape_step_m",
                format!(
                    "must be within {MIN_SHAPE_STEP_M}-{MAX_SHAPE_STEP_M} m (the path's shape on points 0.1 mm to 1 cm apart), got {}",
                    self.shape_step_m
                ),
            ));
        }
        if self.motion_off_mps > self.motion_on_mps {
            return Err((
                "motion_off_mps",
                format!("must not exceed motion_on_mps ({})", self.motion_on_mps),
            ));
        }
        if self.force_release_n > self.force_onset_n {
            return Err((
                "force_release_n",
                format!("must not exceed force_onset_n ({})", self.force_onset_n),
            ));
        }
        if self.jaw_closed_rad >= self.jaw_open_rad {
            return Err(("jaw_closed_rad", format!("must be below jaw_open_rad ({})", self.jaw_open_rad)));
        }
        let [low, high] = self.onset_fractions;
        if !(low.is_finite() && high.is_finite() && 0.0 < low && low < high && high < 1.0) {
            return Err(("onset_fractions", format!("need 0 < low < high < 1, got [{low}, {high}]")));
        }
        Ok(())
    }
}
