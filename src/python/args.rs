//! The typed arguments at the border: each function's `#[pyo3(signature = ...)]` spells its
//! parameters and real defaults (so `inspect.signature` and the stubs agree, a test checks
//! them: tests/python/test_signatures.py), and these types read a value once, as it arrives.
//! A value of the wrong type is a `TypeError` naming the argument (PyO3 prefixes `argument
//! 'ri': `), as for any Python function; a value out of its range is `facetlab.Error` with
//! the command line's line, checked by the library's reader of it ([`crate::io::text`], a
//! picture's [`crate::render::settings`] parsers).
//!
//! Python's `bool` is an `int`: a number argument takes no `True`/`False`, a whole number
//! none either.

use super::call::error;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyInt, PyString};

/// A `TypeError` for `obj` where `what` was wanted (PyO3 names the argument).
fn wrong(obj: &Bound<'_, PyAny>, what: &str) -> PyErr {
    PyTypeError::new_err(format!("`{obj}` is not allowed; give {what}"))
}

/// A whole-number argument as Python gave it, its digits kept to be read by the command
/// line's parser ([`Whole::get`]): a negative or huge int is then `facetlab.Error` with the
/// command line's line, never Python's `OverflowError`. Anything but an int (a bool
/// included) is a `TypeError`, as for any int argument.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Whole(String);

impl<'a, 'py> FromPyObject<'a, 'py> for Whole {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Whole> {
        if obj.is_instance_of::<PyBool>() || !obj.is_instance_of::<PyInt>() {
            return Err(PyTypeError::new_err(format!(
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

    /// The digits as given (`-1`, `18446744073709551616`), for a library parser.
    pub fn text(&self) -> &str {
        &self.0
    }
}

/// A whole-number argument `obj` in `lo..=hi` ([`Whole::get`]): the reader of a
/// `#[pyo3(from_py_with = ...)]` extractor, which lets the signature keep a literal default.
pub(crate) fn whole_in(obj: &Bound<'_, PyAny>, field: &str, lo: u64, hi: u64) -> PyResult<u64> {
    obj.extract::<Whole>()?.get(field, lo, hi)
}

/// A number argument: an int or a float (or anything with `__float__`), never a bool.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Number(pub f64);

impl<'a, 'py> FromPyObject<'a, 'py> for Number {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Number> {
        if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyString>() {
            return Err(wrong(&obj, "a number"));
        }
        obj.extract::<f64>()
            .map(Number)
            .map_err(|_| wrong(&obj, "a number"))
    }
}

impl Number {
    /// The number as the command line's text, for the library's parser of the setting (as
    /// Rust writes it: `0.5`, `11`; NaN as Python writes it, so an error quotes what was
    /// given).
    pub fn text(self) -> String {
        text_of(self.0)
    }
}

fn text_of(x: f64) -> String {
    if x.is_nan() {
        "nan".to_string()
    } else {
        format!("{x}")
    }
}

/// A number argument `obj` ([`Number`]) for a `#[pyo3(from_py_with = ...)]` extractor.
pub(crate) fn number(obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    obj.extract::<Number>().map(|n| n.0)
}

/// A number-or-text argument: a size in mm or `"LxW"`, a tilt in degrees or `"DEG@AZ"`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Size {
    /// A number (an int or a float, not a bool).
    Number(f64),
    /// Text for the library's parser.
    Text(String),
}

impl<'a, 'py> FromPyObject<'a, 'py> for Size {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'a, 'py, PyAny>) -> PyResult<Size> {
        if obj.is_instance_of::<PyString>() {
            return Ok(Size::Text(obj.extract()?));
        }
        match obj.extract::<Number>() {
            Ok(n) => Ok(Size::Number(n.0)),
            Err(_) => Err(wrong(&obj, "a number or a str")),
        }
    }
}

impl Size {
    /// The value as the command line's text (a number as [`Number::text`] writes it).
    pub fn text(&self) -> String {
        match self {
            Size::Number(x) => text_of(*x),
            Size::Text(s) => s.clone(),
        }
    }
}

/// `x` in `[lo, hi]`, checked and worded as the command line checks a number flag
/// ([`crate::io::text::number`]; `what` says what to give), the error naming `field`.
pub(crate) fn within(
    field: &str,
    x: f64,
    lo: f64,
    hi: f64,
    what: &str,
) -> crate::error::Result<f64> {
    crate::io::text::number(field, &text_of(x), lo, hi, what)
}
