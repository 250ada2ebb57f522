//! The engine of the Gymnasium environment `knotlab/KnotTying-v0`: a scene drawn from its
//! randomization (trial `trial` of a Monte Carlo run seeded `seed`, the same draw as `knotlab mc`'s)
//! and stepped by tip velocities, turn rates and jaw openings (`knotlab_scenarios::episode`).

use std::path::PathBuf;
use std::sync::Mutex;

use nalgebra::Vector3;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use knotlab_bench::mc::draw;
use knotlab_hw::rig::Rig;
use knotlab_scenarios::episode::{
    ARMS, Episode as StepWise, EpisodeError, EpisodeSettings, TipCommand, demonstration_commands,
};
use knotlab_scenarios::shipped;
use knotlab_sim::snapshot::{View, render_rgb};
use knotlab_sim::world::SimWorld;

use crate::error::{Failure, knotlab_error, to_python};

/// Values per instrument in a command: velocity (3, m/s), turn rate (3, rad/s), jaw opening (rad).
const PER_ARM: usize = 7;

fn settings(
    control_hz: f64,
    time_limit_s: f64,
    max_speed_mps: f64,
    max_turn_rad_s: f64,
    max_jaw_rad: f64,
    thread_points: usize,
) -> EpisodeSettings {
    EpisodeSettings { control_hz, time_limit_s, max_speed_mps, max_turn_rad_s, max_jaw_rad, thread_points }
}

/// One episode: made by `reset`, stepped until it ends.
#[pyclass(module = "knotlab._knotlab")]
pub struct Episode {
    // The controller's devices are Send, not Sync: one step at a time.
    inner: Mutex<StepWise>,
    drawn: serde_json::Value,
}

impl Episode {
    fn lock(&self) -> PyResult<std::sync::MutexGuard<'_, StepWise>> {
        self.inner.lock().map_err(|_| knotlab_error("the episode failed in an earlier step; reset it"))
    }
}

#[pymethods]
impl Episode {
    /// An episode of the scene at `scene` (the shipped one when None) with `preset` applied: with
    /// `randomize`, the draw of trial `trial` of a Monte Carlo run seeded `seed` (the stitch moved,
    /// the hardware and the thread varied, sensor noise seeded as that trial's); without, the scene
    /// as it is, its sensor noise seeded by `seed`.
    #[new]
    #[pyo3(signature = (
        scene=None, preset=None, seed=0, trial=0, randomize=true, control_hz=20.0, time_limit_s=60.0,
        max_speed_mps=0.15, max_turn_rad_s=4.0, max_jaw_rad=0.8, thread_points=32
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        scene: Option<PathBuf>,
        preset: Option<String>,
        seed: u64,
        trial: u64,
        randomize: bool,
        control_hz: f64,
        time_limit_s: f64,
        max_speed_mps: f64,
        max_turn_rad_s: f64,
        max_jaw_rad: f64,
        thread_points: usize,
    ) -> PyResult<Self> {
        let (scene, name) = crate::scene::load(scene.as_deref(), preset.as_deref()).map_err(knotlab_error)?;
        let settings =
            settings(control_hz, time_limit_s, max_speed_mps, max_turn_rad_s, max_jaw_rad, thread_points);
        let made = py.detach(|| -> Result<(StepWise, serde_json::Value), Failure> {
            let knotlab = |e: &dyn std::fmt::Display| Failure::Knotlab(e.to_string());
            let (scene, sim_seed, drawn) = if randomize {
                let (mut drawn_scene, stitch, drawn) = draw(&scene, seed, trial);
                stitch.apply(&mut drawn_scene);
                let value = serde_json::to_value(&drawn).map_err(|e| knotlab(&e))?;
                (drawn_scene, drawn.sim_seed, value)
            } else {
                (scene, seed, serde_json::Value::Null)
            };
            let rig = Rig::shipped().map_err(|e| knotlab(&e))?;
            let mut world = SimWorld::new(scene, rig).map_err(|e| knotlab(&format!("{name}: {e}")))?;
            world.reseed(sim_seed);
            let episode = StepWise::new(world, settings).map_err(|e| match e {
                EpisodeError::Settings { .. } => Failure::Value(e.to_string()),
                other => knotlab(&other),
            })?;
            Ok((episode, drawn))
        });
        let (episode, drawn) = made.map_err(Failure::into_py)?;
        Ok(Self { inner: Mutex::new(episode), drawn })
    }

    /// One step: `command` holds, per instrument (left, right, assist), the tip's velocity (m/s, world
    /// frame), its rate of turn (rad/s, the axis scaled by the rate) and the jaw's opening (rad), 21
    /// numbers. Returns `(ending, out_of_reach)`: why the episode ended (`"time_limit"`,
    /// `"released"`, `"fault: ..."`) or None, and the instruments whose target was out of reach
    /// (those targets stayed where they were).
    fn step(&self, py: Python<'_>, command: Vec<f64>) -> PyResult<(Option<String>, Vec<String>)> {
        if command.len() != PER_ARM * ARMS.len() {
            return Err(PyValueError::new_err(format!(
                "a command has {} numbers (7 per instrument: velocity, turn rate, jaw), not {}",
                PER_ARM * ARMS.len(),
                command.len()
            )));
        }
        let commands: [TipCommand; 3] = std::array::from_fn(|k| {
            let c = &command[PER_ARM * k..PER_ARM * (k + 1)];
            TipCommand {
                world_velocity_mps: Vector3::new(c[0], c[1], c[2]),
                world_turn_rad_s: Vector3::new(c[3], c[4], c[5]),
                jaw_rad: c[6],
            }
        });
        let mut guard = self.lock()?;
        let episode: &mut StepWise = &mut guard;
        let report = py.detach(|| episode.step(&commands)).map_err(|e| match e {
            EpisodeError::Command { .. } => PyValueError::new_err(e.to_string()),
            other => knotlab_error(other),
        })?;
        let ending = report.ended.map(|e| match e {
            knotlab_scenarios::episode::Ending::TimeLimit => "time_limit".to_owned(),
            knotlab_scenarios::episode::Ending::Released => "released".to_owned(),
            knotlab_scenarios::episode::Ending::Fault(why) => format!("fault: {why}"),
        });
        Ok((ending, report.out_of_reach.iter().map(|a| a.to_string()).collect()))
    }

    /// What the last step left, as a dict of lists (see `knotlab_scenarios::episode::Observation`).
    fn observation(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let episode = self.lock()?;
        Ok(to_python(py, episode.observation())?.unbind())
    }

    /// The knot's evaluation once the episode has ended (with `verdict`), else None.
    fn evaluation(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let episode = self.lock()?;
        let value = episode.evaluation().map(|e| {
            let mut v = serde_json::to_value(e).unwrap_or(serde_json::Value::Null);
            if let Some(map) = v.as_object_mut() {
                map.insert("verdict".into(), e.verdict.label().into());
            }
            v
        });
        Ok(to_python(py, &value)?.unbind())
    }

    /// What the episode's scene drew (the fields of a Monte Carlo trial's `draw`), None without
    /// randomization.
    fn drawn(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(to_python(py, &self.drawn)?.unbind())
    }

    /// The scene drawn as `knotlab demo --snapshots` draws it (three views side by side: from above,
    /// from the front, from the side, `half_width_m` either side of the wound's centre): `(rgb,
    /// width, height)`, the rows of RGB bytes top first.
    #[pyo3(signature = (pixels=160, half_width_m=0.06))]
    fn render(&self, pixels: u32, half_width_m: f64) -> PyResult<(Vec<u8>, u32, u32)> {
        if !(half_width_m.is_finite() && half_width_m > 0.0) {
            return Err(PyValueError::new_err(format!("half_width_m {half_width_m}: a positive length")));
        }
        let episode = self.lock()?;
        let world = episode.world();
        let view = View { pixels, ..View::around_wound_of_width(&world, half_width_m) };
        let rgb = render_rgb(&world, &view).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok((rgb, 3 * pixels, pixels))
    }
}

/// The commands that play the demonstration in `demo` (the shipped one when None) back through an
/// episode at `control_hz`: one list of 21 numbers a step, as `Episode.step` takes them.
#[pyfunction]
#[pyo3(signature = (demo=None, control_hz=20.0, max_jaw_rad=0.8))]
pub fn demonstration_steps(
    demo: Option<PathBuf>,
    control_hz: f64,
    max_jaw_rad: f64,
) -> PyResult<Vec<Vec<f64>>> {
    let demonstration = shipped::demonstration(demo.as_deref()).map_err(knotlab_error)?;
    let settings = EpisodeSettings { control_hz, max_jaw_rad, ..EpisodeSettings::default() };
    let commands = demonstration_commands(&demonstration, &settings)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(commands
        .iter()
        .map(|step| {
            step.iter()
                .flat_map(|c| {
                    let (v, w) = (c.world_velocity_mps, c.world_turn_rad_s);
                    [v.x, v.y, v.z, w.x, w.y, w.z, c.jaw_rad]
                })
                .collect()
        })
        .collect())
}
