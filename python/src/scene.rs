//! A scene file's presets and randomization, to pick a preset by name and to see what a Monte Carlo
//! run draws.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;

use knotlab_scenarios::shipped;
use knotlab_sim::scene::SceneConfig;

use crate::error::{knotlab_error, to_python};

/// The scene at `path` (the shipped one when none) with `preset` applied, and its name.
pub fn load(path: Option<&Path>, preset: Option<&str>) -> Result<(SceneConfig, String), String> {
    let name = shipped::name(path, &shipped::SCENE);
    let scene = shipped::scene(path, &shipped::SCENE).map_err(|e| e.to_string())?;
    let scene = match preset {
        Some(preset) => scene.with_preset(preset).map_err(|e| format!("{name}: {e}"))?,
        None => scene,
    };
    Ok((scene, name))
}

/// A scene file (the shipped `scenarios/default.toml` when none is given): its name, the names of its
/// presets and its randomization (with `preset` applied, if one is given) as a dict.
#[pyfunction]
#[pyo3(signature = (path=None, preset=None))]
pub fn scene_info(py: Python<'_>, path: Option<PathBuf>, preset: Option<String>) -> PyResult<Py<PyAny>> {
    let (scene, name) = load(path.as_deref(), preset.as_deref()).map_err(knotlab_error)?;
    let info = serde_json::json!({
        "name": name,
        "preset": preset,
        "presets": scene.presets.keys().collect::<Vec<_>>(),
        "randomization": scene.randomization,
    });
    Ok(to_python(py, &info)?.unbind())
}
