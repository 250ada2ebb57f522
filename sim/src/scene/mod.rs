//! A scene file (TOML): where the stitch, the tissue and the trocars are, and how the thread, the
//! servos and the solver behave. Unknown keys and out-of-range values are errors naming the key.

mod config;
mod evaluation;
mod load;

pub use config::{
    MAX_TILT_RAD, NeedleParams, Obstacle, RandomObstacle, Randomization, RandomizationPreset, SceneConfig,
    SensorParams, ServoParams, StartParams, StitchParams, TissueParams, Trocars, UnknownPreset,
};
pub use evaluation::EvaluationParams;
pub use load::{SceneError, load_scene, parse_scene};
