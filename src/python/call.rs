//! How every Python call meets the library: the library runs with the GIL released ([`run`]);
//! a library error becomes `facetlab.Error` (a `ValueError`) carrying the command line's
//! one-line message with the settings it names spelled as keyword arguments ([`SETTINGS`]),
//! and a panic (a bug) is caught and becomes `facetlab.InternalError`, so no panic crosses
//! into Python. The library's JSON documents reach Python as dicts ([`from_json`]).

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

/// The keyword argument that sets each library setting an error names, as its field or inside
/// its text ([`crate::error::setting`]), as the command line's `FLAGS` names its flag; a
/// setting with no keyword here is shown by its own name. A picture's settings are
/// [`crate::render::settings::SETTINGS`].
pub(crate) const SETTINGS: &[(&str, &str)] = &[
    ("rough size", "size_mm"),
    ("photon count", "photons"),
    ("output", "path"),
    ("force", "overwrite=True"),
    ("picture light", "light"),
    ("picture size", "size"),
    ("picture tilt", "tilt"),
    ("picture head-shadow", "head_shadow"),
    ("picture exposure", "exposure"),
    ("picture view", "view"),
    ("picture distance", "distance"),
    ("picture aperture", "aperture"),
    ("picture ground", "ground"),
    ("picture ground-gap", "ground_gap"),
    ("picture light-rotation", "light_rotation"),
    ("picture tone", "tone"),
    ("picture bands", "bands"),
    ("picture diameter-mm", "diameter_mm"),
];

/// The keyword argument of the library's setting `name` ([`SETTINGS`]).
pub(crate) fn keyword_of(name: &str) -> Option<String> {
    SETTINGS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, k)| k.to_string())
}

/// A library error as `facetlab.Error`: the setting it names as its field, and those its
/// message names, spelled as keyword arguments ([`SETTINGS`]).
pub(crate) fn error(e: crate::error::Error) -> PyErr {
    use crate::error::Error as E;
    let e = match e.spell_settings(&keyword_of) {
        E::Invalid { field, message } => E::Invalid {
            field: keyword_of(&field).unwrap_or(field),
            message,
        },
        E::Parse { source, message } => E::Parse {
            source: keyword_of(&source).unwrap_or(source),
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

/// `json.loads(text)`: the library's JSON documents handed to Python as dicts and lists.
pub(crate) fn from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}
