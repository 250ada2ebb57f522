//! The package's exception: every error of knotlab's crates (a bad file, a trial that could not be
//! set up, a run folder of another run) reaches Python as `knotlab.KnotlabError` with the crate's
//! message, which names the file, line, field and value where there is one.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    _knotlab,
    KnotlabError,
    PyException,
    "An error of knotlab: a bad input file or argument, a trial that could not be set up, a run folder that holds another run."
);

/// `error` as a [`KnotlabError`], its causes joined as the command line joins them.
pub fn knotlab_error(error: impl std::fmt::Display) -> PyErr {
    KnotlabError::new_err(error.to_string())
}

/// Why work done without the GIL failed, sorted as Python will see it: the caller's argument
/// (`ValueError`) or knotlab's own failure (`KnotlabError`).
pub enum Failure {
    /// An argument out of what is allowed.
    Value(String),
    /// Anything else.
    Knotlab(String),
}

impl Failure {
    /// The Python exception.
    pub fn into_py(self) -> PyErr {
        match self {
            Self::Value(text) => pyo3::exceptions::PyValueError::new_err(text),
            Self::Knotlab(text) => knotlab_error(text),
        }
    }
}

/// A Rust value serialized to JSON and read back by Python's `json` module as a dict or list.
pub fn to_python<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(knotlab_error)?;
    py.import("json")?.call_method1("loads", (text,))
}
