//! How every Python call meets the library: the library runs with the GIL released ([`run`]);
//! a library error becomes `facetlab.Error` (a `ValueError`) carrying the command line's
//! one-line message with the settings it names spelled as keyword arguments ([`keyword`]),
//! and a panic (a bug) is caught and becomes `facetlab.InternalError`, so no panic crosses
//! into Python. The library's JSON documents reach Python as dicts ([`from_json`]).

use crate::error::Setting;
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
/// its text ([`crate::error::setting`]), as the command line's flags name theirs: a `match`
/// over [`Setting`] with no wildcard arm, so a setting added to the library needs a decision
/// here to compile. `None`: the package has no keyword of its own for it (a setting of a
/// command the package does not have, or one it takes under the library's name), and the
/// message shows the setting by its own name.
pub(crate) const fn keyword(s: Setting) -> Option<&'static str> {
    match s {
        Setting::RoughSize => Some("size_mm"),
        Setting::PhotonCount => Some("photons"),
        Setting::Output => Some("path"),
        Setting::Force => Some("overwrite=True"),
        Setting::PictureLight => Some("light"),
        Setting::PictureSize => Some("size"),
        Setting::PictureTilt => Some("tilt"),
        Setting::PictureHeadShadow => Some("head_shadow"),
        Setting::PictureExposure => Some("exposure"),
        Setting::PictureView => Some("view"),
        Setting::PictureDistance => Some("distance"),
        Setting::PictureAperture => Some("aperture"),
        Setting::PictureGround => Some("ground"),
        Setting::PictureGroundGap => Some("ground_gap"),
        Setting::PictureLightRotation => Some("light_rotation"),
        Setting::PictureTone => Some("tone"),
        Setting::PictureBands => Some("bands"),
        Setting::PictureDiameter => Some("diameter_mm"),
        Setting::LightAngle
        | Setting::TraceDepth
        | Setting::AbsorptionModel
        | Setting::FixedWavelength
        | Setting::RefractiveIndex
        | Setting::Material
        | Setting::InclusionMesh
        | Setting::SweepScore
        | Setting::SweepYAxis
        | Setting::SweepGrid
        | Setting::RunFolder
        | Setting::FirstAxis
        | Setting::GridAxes
        | Setting::SlicePoint
        | Setting::MapAxes
        | Setting::ShardFolder
        | Setting::Shard
        | Setting::BatchOutput
        | Setting::ScoreDocument
        | Setting::JsonOutput
        | Setting::HdrOutput
        | Setting::PlotsFolder
        | Setting::PictureRock
        | Setting::PictureTurn
        | Setting::CutParameter => None,
    }
}

/// The keyword argument of the library's setting `name` ([`keyword`]).
pub(crate) fn keyword_of(name: &str) -> Option<String> {
    Setting::from_name(name)
        .and_then(keyword)
        .map(str::to_string)
}

/// A library error as `facetlab.Error`: the setting it names as its field, and those its
/// message names, spelled as keyword arguments ([`keyword`]).
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
