//! One trial, as `knotlab run --json` reports it: the learned skill synthesized at the (moved)
//! stitch by a method, run on the simulated rig, the knot evaluated.

use std::path::PathBuf;

use nalgebra::Vector3;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use knotlab_learner::synthesis::{Method, PrimitiveOffset};
use knotlab_scenarios::expert::RecordOptions;
use knotlab_scenarios::trial::report::{Execution, TrialReport};
use knotlab_scenarios::trial::{StitchMove, TrialError, TrialSetup, run_trial as run_one};
use knotlab_sim::scene::MAX_TILT_RAD;

use crate::error::{Failure, knotlab_error, to_python};
use crate::skill::{Skill, or_shipped};

/// `until_s`, if given, as a trial's stop: a positive number of seconds, else a `ValueError`.
pub fn check_until(until_s: Option<f64>) -> PyResult<()> {
    match until_s {
        Some(t) if !(t.is_finite() && t > 0.0) => {
            Err(PyValueError::new_err(format!("until_s {t}: must be a positive number of seconds")))
        }
        _ => Ok(()),
    }
}

/// `name` as a method, or a `ValueError` naming the ones there are.
pub fn method(name: &str) -> PyResult<Method> {
    name.parse().map_err(|e| PyValueError::new_err(format!("method {name:?}: {e}")))
}

/// Runs one trial and returns its report as a dict (the fields of `knotlab run --json`): the skill
/// (the shipped demonstration learned with the shipped pattern when none is given) synthesized by
/// `method` at the scene's stitch moved by `stitch_offset_m` (world frame, m), turned by
/// `stitch_rotate_deg` about the tissue's normal and tilted by `stitch_tilt_deg` about the wound;
/// `seed` seeds the sensor noise; `until_s` stops the skill early (a short trial, to debug). The
/// interpreter's lock is released while it simulates.
#[pyfunction]
#[pyo3(signature = (
    skill=None, scene=None, seed=0, method="fluid", stitch_offset_m=(0.0, 0.0, 0.0),
    stitch_rotate_deg=0.0, stitch_tilt_deg=0.0, until_s=None
))]
#[allow(clippy::too_many_arguments)]
pub fn run_trial(
    py: Python<'_>,
    skill: Option<&Skill>,
    scene: Option<PathBuf>,
    seed: u64,
    method: &str,
    stitch_offset_m: (f64, f64, f64),
    stitch_rotate_deg: f64,
    stitch_tilt_deg: f64,
    until_s: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let method = self::method(method)?;
    let offset = Vector3::new(stitch_offset_m.0, stitch_offset_m.1, stitch_offset_m.2);
    if !offset.iter().all(|x| x.is_finite()) {
        return Err(PyValueError::new_err(format!("stitch_offset_m {stitch_offset_m:?}: not finite")));
    }
    if !stitch_rotate_deg.is_finite() {
        return Err(PyValueError::new_err(format!("stitch_rotate_deg {stitch_rotate_deg}: not a number")));
    }
    check_until(until_s)?;
    let (scene, scene_name) = crate::scene::load(scene.as_deref(), None).map_err(knotlab_error)?;
    let tilt_deg = scene.tissue.tilt_rad.to_degrees() + stitch_tilt_deg;
    let most_deg = MAX_TILT_RAD.to_degrees();
    if !(tilt_deg.is_finite() && tilt_deg.abs() <= most_deg) {
        return Err(PyValueError::new_err(format!(
            "stitch_tilt_deg {stitch_tilt_deg}: with the scene's tilt ({} degrees) the tissue would tilt \
             {tilt_deg} degrees; at most {most_deg} either way",
            scene.tissue.tilt_rad.to_degrees()
        )));
    }
    let setup = TrialSetup {
        scene,
        scene_name,
        seed,
        stitch: StitchMove {
            offset_m: offset,
            rotate_rad: stitch_rotate_deg.to_radians(),
            tilt_rad: stitch_tilt_deg.to_radians(),
        },
        method,
        offsets: Vec::new(),
    };
    let options = RecordOptions { cycles_per_sample: 10, stop_after_s: until_s, ..RecordOptions::default() };
    let report = py
        .detach(|| -> Result<TrialReport, String> {
            let learned = or_shipped(skill)?;
            let trial = run_one(&learned, &setup, &options, None).map_err(|e| e.to_string())?;
            Ok(TrialReport::new(&setup, &trial, Execution::simulated()))
        })
        .map_err(knotlab_error)?;
    Ok(to_python(py, &report)?.unbind())
}

/// What trial `trial` of a Monte Carlo run seeded `seed` draws on the scene at `scene` (the shipped
/// one when None) with `preset` applied: the fields of a run line's `draw`.
#[pyfunction]
#[pyo3(signature = (scene=None, preset=None, seed=0, trial=0))]
pub fn draw_trial(
    py: Python<'_>,
    scene: Option<PathBuf>,
    preset: Option<String>,
    seed: u64,
    trial: u64,
) -> PyResult<Py<PyAny>> {
    let (scene, _) = crate::scene::load(scene.as_deref(), preset.as_deref()).map_err(knotlab_error)?;
    let (_, _, drawn) = knotlab_bench::mc::draw(&scene, seed, trial);
    Ok(to_python(py, &drawn)?.unbind())
}

/// Runs trial `trial` of a Monte Carlo run seeded `seed` (the scene it draws, as `knotlab mc` runs it)
/// by `method`, each primitive named in `offsets` moved by its offset (`{name: (x, y, z)}`, stitch
/// frame, m), and returns its report as `run_trial` does.
#[pyfunction]
#[pyo3(signature = (skill=None, scene=None, preset=None, seed=0, trial=0, method="fluid", offsets=None, until_s=None))]
#[allow(clippy::too_many_arguments)]
pub fn run_drawn_trial(
    py: Python<'_>,
    skill: Option<&Skill>,
    scene: Option<PathBuf>,
    preset: Option<String>,
    seed: u64,
    trial: u64,
    method: &str,
    offsets: Option<std::collections::BTreeMap<String, (f64, f64, f64)>>,
    until_s: Option<f64>,
) -> PyResult<Py<PyAny>> {
    let method = self::method(method)?;
    check_until(until_s)?;
    let (scene, name) = crate::scene::load(scene.as_deref(), preset.as_deref()).map_err(knotlab_error)?;
    let (mut setup, _) = knotlab_bench::mc::drawn_trial(&scene, &name, seed, trial, method);
    setup.offsets = offsets
        .unwrap_or_default()
        .into_iter()
        .map(|(name, (x, y, z))| PrimitiveOffset { name, stitch_offset_m: Vector3::new(x, y, z) })
        .collect();
    let options = RecordOptions { cycles_per_sample: 10, stop_after_s: until_s, ..RecordOptions::default() };
    let report = py
        .detach(|| -> Result<TrialReport, Failure> {
            let learned = or_shipped(skill).map_err(Failure::Knotlab)?;
            let trial = run_one(&learned, &setup, &options, None).map_err(|e| match e {
                TrialError::Offsets(_) => Failure::Value(e.to_string()),
                other => Failure::Knotlab(other.to_string()),
            })?;
            Ok(TrialReport::new(&setup, &trial, Execution::simulated()))
        })
        .map_err(Failure::into_py)?;
    Ok(to_python(py, &report)?.unbind())
}
