//! The Python package's native module `facetlab._facetlab` (cargo feature `python`, built by
//! maturin from `pyproject.toml`): a face on top of the library, like the binary's `cli`.
//! Nothing in the library imports it; it calls the library only, never the binary.
//!
//! Every call runs the library with the GIL released ([`call::run`]): a library error becomes
//! `facetlab.Error` (a `ValueError`) carrying the command line's one-line message, and a panic
//! (a bug) is caught and becomes `facetlab.InternalError`, so no panic crosses into Python.
//! Each function's signature spells its parameters and defaults, read into the library's
//! types as they arrive ([`args`]). The pure-Python side (`src/python/facetlab/`:
//! `__init__.py`, the stubs `_facetlab.pyi`, the Dask layer `dask.py`) re-exports and
//! documents these functions.

mod args;
mod call;
mod cuts;
mod picture;
mod recipe;
mod rough;
mod runs;
mod score;
mod stone;
mod tally;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _facetlab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("Error", py.get_type::<call::Error>())?;
    m.add("InternalError", py.get_type::<call::InternalError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    cuts::register(m)?;
    score::register(m)?;
    picture::register(m)?;
    tally::register(m)?;
    runs::register(m)?;
    rough::register(m)?;
    recipe::register(m)?;
    Ok(())
}
