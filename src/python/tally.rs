//! `facetlab.trace`: the Monte Carlo photon tracer's tallies of one cut, as `facetlab trace`
//! counts them, returned as the `trace --json` document ([`crate::document::trace`]).

use super::args::{whole_in, within, Whole};
use super::call::{from_json, Error as PyError};
use super::cuts::cut_of;
use super::runs::watched;
use super::stone::StoneArgs;
use crate::document::trace::trace_json;
use crate::error::{Error, Result};
use crate::photon::{
    self, Absorption, Light, LightChoice, LightKind, TraceConfig, WavelengthSampling,
};
use pyo3::prelude::*;
use std::sync::atomic::AtomicBool;

/// The photon run of the keyword arguments.
struct TraceArgs {
    light: String,
    angle: Option<f64>,
    rotate: bool,
    photons: u64,
    depth: Option<u32>,
    absorption: String,
    polarization: bool,
    spectrum: String,
    seed: u64,
    stone: StoneArgs,
}

fn light_choice(a: &TraceArgs) -> Result<LightChoice> {
    if let Some(x) = a.angle {
        within("angle", x, 0.0, 180.0, "degrees")?;
    }
    let name = a.light.trim().to_ascii_lowercase();
    Ok(match (name.as_str(), a.rotate, a.angle) {
        ("overhead" | "directed", true, Some(_)) => {
            return Err(Error::invalid(
                "angle",
                "rotate sweeps 0–180° itself; drop angle",
            ))
        }
        ("overhead", true, None) => LightChoice::Rotate(LightKind::Undirected),
        ("directed", true, None) => LightChoice::Rotate(LightKind::Directed),
        ("overhead", false, None) => LightChoice::Single(Light::overhead()),
        ("overhead", false, Some(x)) => {
            LightChoice::Single(Light::rotated(LightKind::Undirected, x))
        }
        ("directed", false, x) => LightChoice::Single(Light::directed(x.unwrap_or(0.0))),
        ("offset" | "offset-directed", true, _) => {
            return Err(Error::invalid(
                "rotate",
                "the rotation sweep is for light overhead or directed",
            ))
        }
        ("offset" | "offset-directed", false, Some(_)) => {
            return Err(Error::invalid("angle", "is for light overhead or directed"))
        }
        ("offset", false, None) => LightChoice::Single(Light::offset()),
        ("offset-directed", false, None) => LightChoice::Single(Light::offset_directed()),
        _ => {
            return Err(Error::invalid(
                "light",
                format!(
                    "`{}` is not allowed; use overhead, offset, offset-directed or directed",
                    a.light
                ),
            ))
        }
    })
}

fn trace_cut(
    cut: &crate::cut::Cut,
    input: &str,
    a: &TraceArgs,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<String> {
    photon::check_photons(a.photons)?;
    let light = light_choice(a)?;
    let wavelengths = WavelengthSampling::parse("spectrum", &a.spectrum)?;
    let (material, _) = a.stone.material_for(cut)?;
    let config = TraceConfig {
        photons: a.photons,
        until_hit: false,
        depth: a.depth,
        absorption: Absorption::parse("absorption", &a.absorption)?,
        polarization: a.polarization,
        material,
        wavelengths,
        seed: a.seed,
        record_paths: 0,
    };
    config.validate()?;
    let tallies = photon::trace_choice_until(&cut.solid, &cut.name, &light, &config, None, stop)?;
    let doc = trace_json(&light, &config, &[input.to_string()], &[tallies])
        .map_err(|e| Error::invalid("trace", e.to_string()))?;
    Ok(doc.to_string())
}

/// Trace photons through a cut (a `Cut`, a preset name or a path) and return the tallies as
/// `facetlab trace --json` writes them: one light's tally with `settings`, or with
/// `rotate=True` the sweep's `{"settings", "results"}`. `depth` is the bounce limit (`None`:
/// unlimited); `absorption` is none, thesis, beer:K or colour[:W]; `spectrum` uniform, d65
/// or a wavelength in nm.
///
/// Ctrl-C stops the photons within a moment and raises `KeyboardInterrupt`.
///
/// >>> t = facetlab.trace("tolkowsky", photons=2000, seed=1)
/// >>> t["photons_shot"], t["settings"]["seed"]
/// (2000, 1)
#[pyfunction]
#[pyo3(signature = (cut, *, light="overhead", angle=None, rotate=false, photons=1_000_000,
    depth=6, absorption="thesis", polarization=true, spectrum="uniform", seed=1,
    material=None, ri=None, birefringence=None, optic_axis=None, colour_e=None))]
#[allow(clippy::too_many_arguments)]
fn trace<'py>(
    py: Python<'py>,
    cut: &Bound<'py, PyAny>,
    light: &str,
    angle: Option<f64>,
    rotate: bool,
    #[pyo3(from_py_with = photons)] photons: u64,
    #[pyo3(from_py_with = depth)] depth: Option<u32>,
    absorption: &str,
    polarization: bool,
    spectrum: &str,
    #[pyo3(from_py_with = seed)] seed: u64,
    material: Option<String>,
    ri: Option<f64>,
    birefringence: Option<bool>,
    optic_axis: Option<String>,
    colour_e: Option<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let args = TraceArgs {
        light: light.to_string(),
        angle,
        rotate,
        photons,
        depth,
        absorption: absorption.to_string(),
        polarization,
        spectrum: spectrum.to_string(),
        seed,
        stone: StoneArgs {
            material,
            ri,
            birefringence,
            optic_axis,
            colour_e,
            ..StoneArgs::default()
        },
    };
    let input = super::cuts::input_of(cut)?;
    let c = cut_of(cut)?;
    // On a worker thread, this one watching for Ctrl-C: the photons stop within a chunk.
    let stop = AtomicBool::new(false);
    let text = watched(
        py,
        &stop,
        || trace_cut(&c, &input, &args, &stop),
        |_| Ok(()),
    )?;
    from_json(py, &text)
}

// `trace`'s whole numbers, read as the command line reads --photons, --depth and --seed.

/// `photons`: 1 or more.
fn photons(obj: &Bound<'_, PyAny>) -> PyResult<u64> {
    whole_in(obj, "photon count", 1, u64::MAX)
}

/// `depth`: the bounce limit, `None` for unlimited.
fn depth(obj: &Bound<'_, PyAny>) -> PyResult<Option<u32>> {
    if obj.is_none() {
        return Ok(None);
    }
    let d = obj.extract::<Whole>()?;
    let n = d
        .get("depth", 1, photon::UNLIMITED_CAP as u64)
        .map_err(|_| {
            PyError::new_err(format!(
                "depth: `{}` is not allowed; give a whole number in 1..={} or None (unlimited)",
                d.text(),
                photon::UNLIMITED_CAP
            ))
        })?;
    Ok(Some(n as u32))
}

/// `seed`: any whole number from 0.
fn seed(obj: &Bound<'_, PyAny>) -> PyResult<u64> {
    whole_in(obj, "seed", 0, u64::MAX)
}

/// Add `trace` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(trace, m)?)?;
    Ok(())
}
