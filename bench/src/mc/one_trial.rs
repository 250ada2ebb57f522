//! One trial of a run directory set up again, to run it alone (its grasp events, its JSON report, a
//! Rerun recording): the same draw, the same scene and skill, checked against the run's fingerprints so
//! that what runs is the trial the run judged.

use std::path::Path;

use knotlab_learner::synthesis::Method;
use knotlab_scenarios::trial::{Learned, TrialSetup};
use knotlab_sim::scene::SceneConfig;

use super::run_info::{RunInfo, scene_fingerprint, skill_fingerprint};
use super::{Draw, McError, drawn_trial};

/// Trial `trial` of the run in `dir` by `method`: its set-up, what it drew, and the time its skill was
/// stopped at (the run's `--until`). `scene` is the scene file the run was made from (its preset not
/// applied): the preset is the run's, and the scene with it must be the one the run drew from, as must
/// `learned`.
pub fn trial_of_run(
    dir: &Path,
    scene: &SceneConfig,
    learned: &Learned,
    trial: u64,
    method: Method,
) -> Result<(TrialSetup, Draw, Option<f64>), McError> {
    let file = RunInfo::path(dir).display().to_string();
    let bad = |reason: String| McError::Results { file: file.clone(), reason };
    let info = RunInfo::read(dir)?.ok_or_else(|| bad("no such file: not a Monte Carlo run".to_owned()))?;
    if trial >= info.trials {
        return Err(bad(format!("trial {trial}: the run has trials 0 to {}", info.trials - 1)));
    }
    if !info.methods.iter().any(|m| *m == method.to_string()) {
        return Err(bad(format!("method {method}: the run ran {}", info.methods.join(", "))));
    }
    let scene = match &info.preset {
        Some(preset) => scene.with_preset(preset).map_err(|e| bad(format!("preset {preset}: {e}")))?,
        None => scene.clone(),
    };
    let now = scene_fingerprint(&scene);
    if now != info.scene_fingerprint {
        return Err(bad(format!(
            "scene_fingerprint {}: the scene given ({} with preset {}) reads {now}; give the scene file the run drew from",
            info.scene_fingerprint,
            info.scene,
            info.preset.as_deref().unwrap_or("none")
        )));
    }
    let now = skill_fingerprint(learned);
    if now != info.skill_fingerprint {
        return Err(bad(format!(
            "skill_fingerprint {}: the skill given reads {now}; give the skill and demonstration the run played",
            info.skill_fingerprint
        )));
    }
    let (setup, drawn) = drawn_trial(&scene, &info.scene, info.seed, trial, method);
    Ok((setup, drawn, info.until_s))
}
