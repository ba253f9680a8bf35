//! The Python package's native module `facetlab._facetlab` (cargo feature `python`, built by
//! maturin from `pyproject.toml`): a face on top of the library, like the binary's `cli`.
//! Nothing in the library imports it; it calls the library only, never the binary.
//!
//! Every call runs the library with the GIL released ([`run`]): a library error becomes
//! `facetlab.Error` (a `ValueError`) carrying the command line's one-line message, and a panic
//! (a bug) is caught and becomes `facetlab.InternalError`, so no panic crosses into Python.
//! The pure-Python side (`src/python/facetlab/`: `__init__.py`, the stubs `_facetlab.pyi`,
//! the Dask layer `dask.py`) re-exports and documents these functions.

mod cuts;
mod keywords;
mod picture;
mod recipe;
mod rough;
mod runs;
mod score;
mod stone;
mod tally;

use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};

create_exception!(
    _facetlab,
    Error,
    PyValueError,
    "Bad input: the message is the command line's one-line error naming the field and what is allowed."
);
create_exception!(
    _facetlab,
    InternalError,
    PyRuntimeError,
    "A bug in facetlab (a caught panic); please report it with the call that raised it."
);

/// A library error as `facetlab.Error`: the setting it names as its field, and those its
/// message names, spelled as keyword arguments ([`keywords::SETTINGS`]).
pub(crate) fn error(e: crate::error::Error) -> PyErr {
    use crate::error::Error as E;
    let e = match e.spell_settings(&keywords::keyword_of) {
        E::Invalid { field, message } => E::Invalid {
            field: keywords::keyword_of(&field).unwrap_or(field),
            message,
        },
        E::Parse { source, message } => E::Parse {
            source: keywords::keyword_of(&source).unwrap_or(source),
            message,
        },
        other => other,
    };
    Error::new_err(e.to_string())
}

/// A caught panic's payload as `facetlab.InternalError`.
pub(crate) fn panicked(payload: Box<dyn std::any::Any + Send>) -> PyErr {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic".to_string());
    InternalError::new_err(format!("internal error (a bug in facetlab): {what}"))
}

/// Run library work `f` with the GIL released; its error becomes `facetlab.Error`, a panic
/// `facetlab.InternalError`.
pub(crate) fn run<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> crate::error::Result<T> + Send,
) -> PyResult<T> {
    py.detach(|| catch_unwind(AssertUnwindSafe(f)))
        .map_err(panicked)?
        .map_err(error)
}

/// A whole-number argument as Python gave it, its digits kept to be read by the command
/// line's parser ([`Whole::get`]): a negative or huge int is then `facetlab.Error` with the
/// command line's line, never Python's `OverflowError`. Anything but an int (a bool
/// included) is a `TypeError`, as for any int argument.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Whole(String);

impl From<u64> for Whole {
    fn from(n: u64) -> Whole {
        Whole(n.to_string())
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Whole {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Whole> {
        use pyo3::types::{PyBool, PyInt};
        if obj.is_instance_of::<PyBool>() || !obj.is_instance_of::<PyInt>() {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "'{}' object cannot be interpreted as an integer",
                obj.get_type().name()?
            )));
        }
        Ok(Whole(obj.str()?.to_string()))
    }
}

impl Whole {
    /// The number in `lo..=hi`, else `facetlab.Error` naming `field` as the command line's
    /// flag of it says ([`crate::io::text::count`]).
    pub fn get(&self, field: &str, lo: u64, hi: u64) -> PyResult<u64> {
        crate::io::text::count(field, &self.0, lo, hi).map_err(error)
    }

    /// The digits as given (`-1`, `18446744073709551616`).
    pub fn text(&self) -> &str {
        &self.0
    }
}

/// `json.loads(text)`: the library's JSON documents handed to Python as dicts and lists.
pub(crate) fn from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// The native module.
#[pymodule]
fn _facetlab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<Error>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    cuts::register(m)?;
    keywords::register(m)?;
    score::register(m)?;
    picture::register(m)?;
    tally::register(m)?;
    runs::register(m)?;
    rough::register(m)?;
    recipe::register(m)?;
    Ok(())
}
