//! A learned skill: the knowledge base the demonstration was cut into, and the demonstration itself
//! (the replay baseline plays it back), learned with a task pattern or loaded from `knotlab learn`'s
//! file; the shipped demonstration and pattern when none are given.

use std::path::PathBuf;

use pyo3::prelude::*;

use knotlab_learner::primitive::{
    learn as learn_kb, load_knowledge_base, parse_knowledge_base, write_knowledge_base,
};
use knotlab_scenarios::shipped;
use knotlab_scenarios::trial::Learned;

use crate::error::{knotlab_error, to_python};

/// How a skill pickles: the function that rebuilds it, and its arguments.
type Reduced = (Py<PyAny>, (String, Option<PathBuf>));

/// A learned skill (`knotlab.learn()`, `knotlab.load_skill(path)`).
///
/// It pickles as its knowledge base and the directory its demonstration was read from (None: the
/// shipped one), which unpickling reads again.
#[pyclass(module = "knotlab._knotlab", frozen)]
pub struct Skill {
    learned: Learned,
    demo: Option<PathBuf>,
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

    /// The knowledge base as the JSON text `knotlab learn --out` writes.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.learned.knowledge).map_err(knotlab_error)
    }

    fn __reduce__(&self, py: Python<'_>) -> PyResult<Reduced> {
        let rebuild = py.import("knotlab._knotlab")?.getattr("skill_from_json")?.unbind();
        Ok((rebuild, (self.to_json()?, self.demo.clone())))
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
    let learned = py.detach(|| learn_from(demo.clone(), pattern)).map_err(knotlab_error)?;
    Ok(Skill { learned, demo })
}

/// Loads a knowledge base (`knotlab learn --out FILE`) with the demonstration it came from (the
/// replay baseline plays it back; the shipped one when not given).
#[pyfunction]
#[pyo3(signature = (path, demo=None))]
pub fn load_skill(path: PathBuf, demo: Option<PathBuf>) -> PyResult<Skill> {
    let knowledge = load_knowledge_base(&path).map_err(knotlab_error)?;
    let demonstration = shipped::demonstration(demo.as_deref()).map_err(knotlab_error)?;
    Ok(Skill { learned: Learned { knowledge, demonstration }, demo })
}

/// A skill from a knowledge base's JSON text (`Skill.to_json()`) and the directory of its
/// demonstration (the shipped one when None).
#[pyfunction]
#[pyo3(signature = (text, demo=None))]
pub fn skill_from_json(text: &str, demo: Option<PathBuf>) -> PyResult<Skill> {
    let knowledge = parse_knowledge_base(text, "a pickled skill").map_err(knotlab_error)?;
    let demonstration = shipped::demonstration(demo.as_deref()).map_err(knotlab_error)?;
    Ok(Skill { learned: Learned { knowledge, demonstration }, demo })
}
