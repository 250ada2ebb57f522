//! A learned skill: the knowledge base the demonstration was cut into, and the demonstration itself
//! (the replay baseline plays it back), learned with a task pattern or loaded from `knotlab learn`'s
//! file; the shipped demonstration and pattern when none are given.

use std::path::PathBuf;

use pyo3::prelude::*;

use knotlab_learner::primitive::{learn as learn_kb, load_knowledge_base, write_knowledge_base};
use knotlab_scenarios::shipped;
use knotlab_scenarios::trial::Learned;

use crate::error::{knotlab_error, to_python};

/// A learned skill (`knotlab.learn()`, `knotlab.load_skill(path)`).
#[pyclass(module = "knotlab._knotlab", frozen)]
pub struct Skill {
    learned: Learned,
}

impl Skill {
    /// What it holds.
    pub fn learned(&self) -> &Learned {
        &self.learned
    }
}

/// The skill of `skill`, or the shipped demonstration learned with the shipped pattern.
pub fn or_shipped(skill: Option<&Skill>) -> Result<Learned, String> {
    match skill {
        Some(s) => Ok(s.learned.clone()),
        None => learn_from(None, None),
    }
}

/// The demonstration in `demo` learned with the pattern in `pattern` (the shipped ones when not
/// given).
fn learn_from(demo: Option<PathBuf>, pattern: Option<PathBuf>) -> Result<Learned, String> {
    let demonstration = shipped::demonstration(demo.as_deref()).map_err(|e| e.to_string())?;
    let task = shipped::pattern(pattern.as_deref()).map_err(|e| e.to_string())?;
    let knowledge = learn_kb(&demonstration, &task).map_err(|e| {
        format!(
            "learning from {} with {}: {e}",
            shipped::demo_name(demo.as_deref()),
            shipped::name(pattern.as_deref(), &shipped::PATTERN)
        )
    })?;
    Ok(Learned { knowledge, demonstration })
}

#[pymethods]
impl Skill {
    /// The task it ties.
    #[getter]
    fn task(&self) -> String {
        self.learned.knowledge.task.clone()
    }

    /// The knowledge base as a dict (the JSON `knotlab learn --out` writes).
    fn knowledge(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(to_python(py, &self.learned.knowledge)?.unbind())
    }

    /// The primitives' names, per instrument in time order.
    fn primitives(&self) -> Vec<(String, String)> {
        self.learned
            .knowledge
            .instruments
            .iter()
            .flat_map(|i| i.primitives.iter().map(|p| (i.instrument.clone(), p.name().to_owned())))
            .collect()
    }

    /// Writes the knowledge base to `path` (JSON, as `knotlab learn --out` does).
    fn save(&self, path: PathBuf) -> PyResult<()> {
        write_knowledge_base(&path, &self.learned.knowledge).map_err(knotlab_error)
    }

    fn __repr__(&self) -> String {
        format!("Skill({:?}, {} primitives)", self.learned.knowledge.task, self.primitives().len())
    }
}

/// Learns a skill: cuts the demonstration (a directory, as `knotlab demo` writes it) into primitives
/// by the task pattern (TOML); the shipped ones when not given.
#[pyfunction]
#[pyo3(signature = (demo=None, pattern=None))]
pub fn learn(py: Python<'_>, demo: Option<PathBuf>, pattern: Option<PathBuf>) -> PyResult<Skill> {
    let learned = py.detach(|| learn_from(demo, pattern)).map_err(knotlab_error)?;
    Ok(Skill { learned })
}

/// Loads a knowledge base (`knotlab learn --out FILE`) with the demonstration it came from (the
/// replay baseline plays it back; the shipped one when not given).
#[pyfunction]
#[pyo3(signature = (path, demo=None))]
pub fn load_skill(path: PathBuf, demo: Option<PathBuf>) -> PyResult<Skill> {
    let knowledge = load_knowledge_base(&path).map_err(knotlab_error)?;
    let demonstration = shipped::demonstration(demo.as_deref()).map_err(knotlab_error)?;
    Ok(Skill { learned: Learned { knowledge, demonstration } })
}
