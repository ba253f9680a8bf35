//! `facetlab.render`: a cut's picture under one of the lights, as `facetlab render` draws it
//! (one cut, `--bare`), with its linear values, its sRGB bytes and its statistics (the
//! `render --json` document's keys, from [`crate::document::render`]).

use super::cuts::cut_of;
use super::keywords::{self, Keywords};
use super::run;
use super::stone::StoneArgs;
use crate::document::render::{CutJson, FrameJson};
use crate::error::{Error, Result};
use crate::plot::palette::PICTURE_GROUND;
use crate::render::{self, pose::parse_tilt, Image, Light, RenderOptions};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::Instant;

/// A rendered picture.
///
/// >>> r = facetlab.render("tolkowsky", light="aset", size=32)
/// >>> r.srgb.shape, r.linear.dtype.name, sorted(r.stats["aset"])
/// ((32, 32, 3), 'float32', ['blue', 'green', 'leak', 'port', 'red'])
#[pyclass(name = "Render", module = "facetlab", frozen)]
pub struct PyRender {
    image: Image,
    exposure: f64,
    stats: String,
    float64: bool,
}

#[pymethods]
impl PyRender {
    /// Linear RGB relative to a white diffuser, H×W×3 (rows from the top; a grey light's
    /// value in all three channels), float32 (float64 with `render(..., float64=True)`).
    #[getter]
    fn linear<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.image.size();
        let ch = &self.image.channels;
        let value = |k: usize, q: usize| ch[q.min(ch.len() - 1)].data[k];
        let mut out = Vec::with_capacity(n * n * 3);
        for j in 0..n {
            for i in 0..n {
                let k = (n - 1 - j) * n + i;
                for q in 0..3 {
                    out.push(value(k, q));
                }
            }
        }
        if self.float64 {
            Ok(PyArray1::from_vec(py, out).reshape([n, n, 3])?.into_any())
        } else {
            let out: Vec<f32> = out.into_iter().map(|v| v as f32).collect();
            Ok(PyArray1::from_vec(py, out).reshape([n, n, 3])?.into_any())
        }
    }

    /// The picture's 8-bit sRGB pixels, H×W×3 uint8: the bytes of the PNG `facetlab render
    /// --bare` writes.
    #[getter]
    fn srgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.image.size();
        let bytes = self.image.to_srgb8(self.exposure, PICTURE_GROUND);
        Ok(PyArray1::from_vec(py, bytes).reshape([n, n, 3])?.into_any())
    }

    /// Share of each pixel the stone's outline covers, H×W float64 (rows from the top).
    #[getter]
    fn coverage<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.image.size();
        let c = &self.image.coverage.data;
        let out: Vec<f64> = (0..n)
            .flat_map(|j| (0..n).map(move |i| (n - 1 - j) * n + i))
            .map(|k| c[k])
            .collect();
        Ok(PyArray1::from_vec(py, out).reshape([n, n])?.into_any())
    }

    /// The statistics as `facetlab render --json` writes them for one cut (`output` is empty:
    /// nothing was written).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        super::from_json(py, &self.stats)
    }

    /// Write the picture as a PNG (the `--bare` picture), atomically; an existing file is
    /// replaced only with `overwrite=True`.
    ///
    /// >>> import os, tempfile
    /// >>> path = os.path.join(tempfile.mkdtemp(), "t.png")
    /// >>> facetlab.render("tolkowsky", size=16).write_png(path)
    /// >>> open(path, "rb").read(4)
    /// b'\x89PNG'
    #[pyo3(signature = (path, overwrite=false))]
    fn write_png(&self, py: Python<'_>, path: std::path::PathBuf, overwrite: bool) -> PyResult<()> {
        let n = self.image.size() as u32;
        let image = &self.image;
        let exposure = self.exposure;
        run(py, || {
            if path.exists() && !overwrite {
                return Err(Error::invalid(
                    "path",
                    format!(
                        "{} exists; pass overwrite=True to replace it",
                        path.display()
                    ),
                ));
            }
            let rgb = image.to_srgb8(exposure, PICTURE_GROUND);
            crate::io::png::write_rgb8(&path, n, n, &[rgb.as_slice()], 0)
        })
    }

    fn __repr__(&self) -> String {
        let n = self.image.size();
        format!(
            "<Render {} {n}×{n}, mean {:.4}>",
            self.image.light.name(),
            self.image.stats.mean
        )
    }
}

/// Render settings from the keyword arguments.
struct RenderArgs {
    light: String,
    size: usize,
    tilt: Option<String>,
    head_shadow: Option<f64>,
    exposure: f64,
    polarization: bool,
    stone: StoneArgs,
}

fn draw(cut: &crate::cut::Cut, input: &str, a: &RenderArgs) -> Result<(Image, String)> {
    let light = Light::parse(a.light.trim().to_ascii_lowercase().as_str()).map_err(|_| {
        Error::invalid(
            "light",
            format!(
                "`{}` is not allowed; use {}",
                a.light,
                Light::ALL.map(Light::name).join(", ")
            ),
        )
    })?;
    let mut opts = RenderOptions::new(light);
    opts.size = a.size;
    if let Some(t) = &a.tilt {
        opts.tilt = parse_tilt("tilt", t)?;
    }
    opts.head_shadow_deg = a.head_shadow;
    opts.trace.polarization = a.polarization;
    if !(0.01..=100.0).contains(&a.exposure) {
        return Err(Error::invalid(
            "exposure",
            format!(
                "`{}` is not allowed; give a factor in [0.01, 100]",
                a.exposure
            ),
        ));
    }
    let (material, width) = a.stone.material_for(cut)?;
    opts.material = material;
    opts.width_mm = width;
    opts.validate()?;
    let t0 = Instant::now();
    let img = render::render(&cut.solid, &opts);
    let elapsed = t0.elapsed().as_secs_f64();
    let frame = FrameJson::new(0, opts.tilt, &img.stats, elapsed);
    let record = CutJson::new(
        (&cut.name, input),
        &opts,
        &opts.material,
        a.exposure,
        vec![frame],
        None,
    );
    let json =
        serde_json::to_string(&record).map_err(|e| Error::invalid("stats", e.to_string()))?;
    Ok((img, json))
}

/// Render a cut (a `Cut`, a preset name or a path) under `light` (iso, cos, aset, fire,
/// hearts, arrows, idealscope) at `size` pixels, tilted `tilt` ("DEG" or "DEG@AZ").
/// Keyword arguments: `light` (default "iso"), `size` (256), `tilt`, `head_shadow`,
/// `exposure` (1.0), `polarization` (True), the stone's as `score` takes them, and `float64`
/// (False: `.linear` is float32).
///
/// >>> r = facetlab.render("tolkowsky", size=32, tilt="10@45")
/// >>> r.stats["tilt_deg"], r.stats["light"]
/// (10.0, 'iso')
#[pyfunction]
#[pyo3(name = "render", signature = (cut, **kwargs))]
fn render_cut(
    py: Python<'_>,
    cut: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyRender> {
    let kw = Keywords::parse("render", &keywords::RENDER, kwargs)?;
    let exposure = kw.f64("exposure")?;
    let args = RenderArgs {
        light: kw.str("light")?,
        size: kw.usize("size")?,
        // A number of degrees, or the command line's DEG@AZ text.
        tilt: kw.size_text("tilt")?,
        head_shadow: kw.opt_f64("head_shadow")?,
        exposure,
        polarization: kw.bool("polarization")?,
        stone: StoneArgs::from_keywords(&kw)?,
    };
    let float64 = kw.bool("float64")?;
    let input = super::cuts::input_of(cut)?;
    let c = cut_of(cut)?;
    let (image, stats) = run(py, || draw(&c, &input, &args))?;
    Ok(PyRender {
        image,
        exposure,
        stats,
        float64,
    })
}

/// Add `render` and its class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRender>()?;
    m.add_function(wrap_pyfunction!(render_cut, m)?)?;
    Ok(())
}
