//! `knotlab._knotlab`: the Rust half of the Python package, a thin layer over the crates the command
//! line uses (no logic of its own). The Python half (`python/knotlab/`) re-exports it, reads run
//! folders into pandas and registers the Gymnasium environments.
//!
//! - [`error`]: the package's exception and how library errors become it.
//! - [`skill`]: a learned skill (knowledge base and demonstration): learned, loaded, saved.
//! - [`scene`]: a scene file's presets and randomization.
//! - [`trial`]: one trial, reported as `knotlab run --json` reports it; a Monte Carlo run's trial,
//!   its primitives moved by offsets of their own (the skill environment's engine).
//! - [`episode`]: the Gymnasium environment's engine: a drawn scene stepped by tip commands.
//! - [`mc`]: a Monte Carlo run on the engine of `knotlab mc`, and a run folder read back.

mod episode;
mod error;
mod mc;
mod scene;
mod skill;
mod trial;

use pyo3::prelude::*;

/// The module.
#[pymodule]
fn _knotlab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("KnotlabError", m.py().get_type::<error::KnotlabError>())?;
    m.add_class::<skill::Skill>()?;
    m.add_function(wrap_pyfunction!(skill::learn, m)?)?;
    m.add_function(wrap_pyfunction!(skill::load_skill, m)?)?;
    m.add_function(wrap_pyfunction!(skill::skill_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(scene::scene_info, m)?)?;
    m.add_function(wrap_pyfunction!(trial::run_trial, m)?)?;
    m.add_function(wrap_pyfunction!(trial::draw_trial, m)?)?;
    m.add_function(wrap_pyfunction!(trial::run_drawn_trial, m)?)?;
    m.add_function(wrap_pyfunction!(mc::run_mc, m)?)?;
    m.add_function(wrap_pyfunction!(mc::read_run, m)?)?;
    m.add_class::<episode::Episode>()?;
    m.add_function(wrap_pyfunction!(episode::demonstration_steps, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
