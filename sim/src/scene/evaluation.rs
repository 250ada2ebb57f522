//! How a knot is judged: the scene file's `[evaluation]`.

use serde::{Deserialize, Serialize};

use crate::knot::{DownLimits, KnotType};

/// How a knot is judged (the scene file's `[evaluation]`).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EvaluationParams {
    /// Knots the task accepts.
    pub accepted: Vec<KnotType>,
    /// Largest height of the knot's lowest crossing above the tissue, m.
    pub max_knot_height_m: f64,
    /// Largest distance from the stitch to the knot's nearest crossing, m.
    pub max_stitch_distance_m: f64,
    /// How long the released knot must hold against the elastic load, s.
    pub settle_s: f64,
    /// The wound gap a holding knot keeps below, m.
    pub max_wound_gap_m: f64,
    /// During the settle, each flap is also pulled away from the wound with this force, N (0: the
    /// tissue's elastic load alone). A load below the stitch's friction cannot draw the thread through
    /// the tissue, so the wound cannot open whether or not a knot holds it (see
    /// `sim/tests/integration/holding_test_passed_an_untied_stitch.rs`).
    #[serde(default = "default_holding_load_n")]
    pub holding_load_n: f64,
}

/// Six times the default friction of the stitch in a flap (0.05 N): an untied stitch opens under it,
/// and it is a fifth of the force the scripted expert cinches with (1.5 N).
fn default_holding_load_n() -> f64 {
    0.3
}

impl Default for EvaluationParams {
    /// A surgeon's knot (or the square knot the surgeon's knot is often taken for), down within
    /// [`DownLimits::default`], holding the wound below 1.5 mm for one second against 0.3 N a flap.
    fn default() -> Self {
        let down = DownLimits::default();
        Self {
            accepted: vec![KnotType::SurgeonsKnot, KnotType::Surgeons],
            max_knot_height_m: down.max_height_m,
            max_stitch_distance_m: down.max_stitch_distance_m,
            settle_s: 1.0,
            max_wound_gap_m: 0.0015,
            holding_load_n: default_holding_load_n(),
        }
    }
}
