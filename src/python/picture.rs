//! `facetlab.render`: a cut's picture as `facetlab render` draws it (one cut, `--bare`), under
//! a laboratory light or photographed under a studio rig, a map or `env:FILE`, with its linear
//! values, its sRGB bytes and its statistics (the `render --json` document's keys, from
//! [`crate::document::render`]). Each of the picture's settings is read by the library's parser
//! of it ([`read`]) into the settings the command line's pictures are made from too
//! ([`PictureSettings`]); its errors name the keyword argument.

use super::cuts::cut_of;
use super::keywords::{self, Keywords};
use super::run;
use super::stone::{refuse_existing, StoneArgs};
use crate::document::render::{CutJson, FrameJson, PhotoFrame, PhotoRecord};
use crate::error::{Error, Result};
use crate::plot::palette::PICTURE_GROUND;
use crate::render::photo::{Photo, PhotoOptions, Tone};
use crate::render::settings::{self as picture, read, LightChoice};
use crate::render::{self, Image, RenderOptions};
use crate::render::{PictureSettings, Pictures};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::Instant;

/// The picture drawn: a laboratory picture, or a photograph with its tone curve.
enum Picture {
    Lab(Box<Image>),
    Photo(Box<Photo>, Tone),
}

/// A rendered picture.
///
/// >>> r = facetlab.render("tolkowsky", light="aset", size=32)
/// >>> r.srgb.shape, r.linear.dtype.name, sorted(r.stats["aset"])
/// ((32, 32, 3), 'float32', ['blue', 'green', 'leak', 'port', 'red'])
#[pyclass(name = "Render", module = "facetlab", frozen)]
pub struct PyRender {
    picture: Picture,
    exposure: f64,
    stats: String,
    float64: bool,
}

impl PyRender {
    fn size(&self) -> usize {
        match &self.picture {
            Picture::Lab(image) => image.size(),
            Picture::Photo(photo, _) => photo.size(),
        }
    }

    /// The 8-bit sRGB bytes, rows from the top: the PNG's.
    fn rgb8(&self) -> Vec<u8> {
        match &self.picture {
            Picture::Lab(image) => image.to_srgb8(self.exposure, PICTURE_GROUND),
            Picture::Photo(photo, tone) => photo.to_srgb8(self.exposure, *tone),
        }
    }
}

#[pymethods]
impl PyRender {
    /// Linear RGB, H×W×3 (rows from the top), float32 (float64 with `render(...,
    /// float64=True)`): a laboratory picture's relative to a white diffuser (a grey light's
    /// value in all three channels); a photograph's linear sRGB relative to a white diffuser
    /// under the ISO sky, background and ground included, before exposure and tone (the
    /// command line's `--hdr-out` picture).
    #[getter]
    fn linear<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.size();
        let mut out = Vec::with_capacity(n * n * 3);
        for j in 0..n {
            for i in 0..n {
                let k = (n - 1 - j) * n + i;
                match &self.picture {
                    Picture::Lab(image) => {
                        let ch = &image.channels;
                        out.extend((0..3).map(|q| ch[q.min(ch.len() - 1)].data[k]));
                    }
                    Picture::Photo(photo, _) => out.extend(photo.linear_rgb(k).to_array()),
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
    /// --bare` writes (a photograph's through its exposure and tone curve).
    #[getter]
    fn srgb<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.size();
        Ok(PyArray1::from_vec(py, self.rgb8())
            .reshape([n, n, 3])?
            .into_any())
    }

    /// Share of each pixel the stone's outline covers, H×W float64 (rows from the top).
    #[getter]
    fn coverage<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let n = self.size();
        let c = match &self.picture {
            Picture::Lab(image) => &image.coverage.data,
            Picture::Photo(photo, _) => &photo.coverage.data,
        };
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
        let n = self.size() as u32;
        run(py, || {
            refuse_existing(&path, overwrite)?;
            let rgb = self.rgb8();
            crate::io::png::write_rgb8(&path, n, n, &[rgb.as_slice()], 0)
        })
    }

    fn __repr__(&self) -> String {
        let n = self.size();
        let (light, mean) = match &self.picture {
            Picture::Lab(image) => (image.light.name().to_string(), image.stats.mean),
            Picture::Photo(photo, _) => (photo.stats.light.clone(), photo.stats.mean),
        };
        format!("<Render {light} {n}×{n}, mean {mean:.4}>")
    }
}

/// Draw `cut` (given as `input`) as `settings` say, of the stone `stone` chooses: the picture,
/// its exposure and its statistics as `render --json` writes them (`output` empty).
fn draw(
    cut: &crate::cut::Cut,
    input: &str,
    settings: &PictureSettings,
    stone: &StoneArgs,
) -> Result<(Picture, f64, String)> {
    let choice = stone.choice()?;
    let pictures = settings.pictures(&choice.material, choice.size)?;
    let (material, width_mm) = stone.material_for(cut)?;
    let t0 = Instant::now();
    let (picture, exposure, json) = match pictures {
        Pictures::Lab(p) => {
            let opts = RenderOptions {
                material,
                width_mm,
                ..p.opts.clone()
            };
            let img = render::render(&cut.solid, &opts);
            let frame = FrameJson::new(0, opts.tilt, &img.stats, t0.elapsed().as_secs_f64());
            let record = CutJson::new((&cut.name, input), &opts, p.exposure, vec![frame], None);
            (
                Picture::Lab(Box::new(img)),
                p.exposure,
                serde_json::to_string(&record),
            )
        }
        Pictures::Photo(p) => {
            let opts = PhotoOptions {
                material,
                width_mm,
                ..p.frame(0)
            };
            let photo = render::photo::photo(&cut.solid, &opts);
            let stats = &photo.stats;
            let frame = PhotoFrame::new(0, &opts, stats, t0.elapsed().as_secs_f64());
            let record = PhotoRecord::new(
                &cut.name,
                input,
                &opts,
                stats,
                p.exposure,
                vec![frame],
                None,
            );
            let json = serde_json::to_string(&record);
            (Picture::Photo(Box::new(photo), opts.tone), p.exposure, json)
        }
    };
    let json = json.map_err(|e| Error::invalid("stats", e.to_string()))?;
    Ok((picture, exposure, json))
}

/// Render a cut (a `Cut`, a preset name or a path) under a laboratory `light` (iso, cos, aset,
/// fire, hearts, arrows, idealscope), or photograph it under a studio one (tent, darkfield,
/// daylight, office, ring, studio, or "env:FILE", an .hdr or .exr environment map), at `size`
/// pixels, tilted `tilt` ("DEG" or "DEG@AZ"). Keyword arguments, named as `facetlab render`'s
/// flags and read by the same parse: `light` (default "iso"), `size` (256), `tilt`,
/// `exposure` (1.0), `polarization` (True); a laboratory picture's `head_shadow`; a
/// photograph's `view` ("ELEV@AZ", default "30@0"), `distance` (mm; default orthographic),
/// `aperture` (the entrance pupil in mm, 0 = a pinhole; default a 4 mm pupil with `distance`,
/// the ±1° filter without; without `distance` it is read at 250 mm), `ground` ("white", "black", "none"), `ground_gap`, `light_rotation`, `tone` ("filmic",
/// "clip") and `bands` (8); the stone's as `score` takes them; and `float64` (False: `.linear`
/// is float32). One frame: the command line's `--turn` and `--rock` animations are files.
///
/// >>> r = facetlab.render("tolkowsky", size=32, tilt="10@45")
/// >>> r.stats["tilt_deg"], r.stats["light"]
/// (10.0, 'iso')
/// >>> p = facetlab.render("tolkowsky", light="tent", view=60, ground="white", size=32)
/// >>> p.stats["view"]["elevation_deg"], p.stats["ground"], p.stats["tone"]
/// (60.0, 'white', 'filmic')
#[pyfunction]
#[pyo3(name = "render", signature = (cut, **kwargs))]
fn render_cut(
    py: Python<'_>,
    cut: &Bound<'_, PyAny>,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyRender> {
    let kw = Keywords::parse("render", &keywords::RENDER, kwargs)?;
    let settings = picture_settings(&kw)?;
    let stone = StoneArgs::from_keywords(&kw)?;
    let float64 = kw.bool("float64")?;
    let input = super::cuts::input_of(cut)?;
    let c = cut_of(cut)?;
    let (picture, exposure, stats) = run(py, || draw(&c, &input, &settings, &stone))?;
    Ok(PyRender {
        picture,
        exposure,
        stats,
        float64,
    })
}

/// The picture's settings from the keywords: each as the command line's text (a number of
/// degrees or `DEG@AZ`, …), read by its setting's parser, whose error names the keyword.
fn picture_settings(kw: &Keywords) -> PyResult<PictureSettings> {
    use crate::render::photo::{parse_view, GroundKind, Tone};
    use crate::render::pose::parse_tilt;
    let t = |k: &str| kw.text(k);
    let e = super::error;
    Ok(PictureSettings {
        light: LightChoice::parse(picture::LIGHT, &kw.str("light")?).map_err(e)?,
        size: read(t("size")?.as_deref(), picture::SIZE, picture::parse_size).map_err(e)?,
        tilt: read(t("tilt")?.as_deref(), picture::TILT, parse_tilt).map_err(e)?,
        head_shadow: read(
            t("head_shadow")?.as_deref(),
            picture::HEAD_SHADOW,
            picture::parse_head_shadow,
        )
        .map_err(e)?,
        exposure: read(
            t("exposure")?.as_deref(),
            picture::EXPOSURE,
            picture::parse_exposure,
        )
        .map_err(e)?,
        polarization: kw.bool("polarization")?,
        view: read(t("view")?.as_deref(), picture::VIEW, parse_view).map_err(e)?,
        distance: read(
            t("distance")?.as_deref(),
            picture::DISTANCE,
            picture::parse_distance,
        )
        .map_err(e)?,
        aperture: read(
            t("aperture")?.as_deref(),
            picture::APERTURE,
            picture::parse_aperture,
        )
        .map_err(e)?,
        ground: read(t("ground")?.as_deref(), picture::GROUND, GroundKind::parse).map_err(e)?,
        ground_gap: read(
            t("ground_gap")?.as_deref(),
            picture::GROUND_GAP,
            picture::parse_ground_gap,
        )
        .map_err(e)?,
        light_rotation: read(
            t("light_rotation")?.as_deref(),
            picture::LIGHT_ROTATION,
            picture::parse_light_rotation,
        )
        .map_err(e)?,
        tone: read(t("tone")?.as_deref(), picture::TONE, Tone::parse).map_err(e)?,
        bands: read(t("bands")?.as_deref(), picture::BANDS, picture::parse_bands).map_err(e)?,
    })
}

/// Add `render` and its class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRender>()?;
    m.add_function(wrap_pyfunction!(render_cut, m)?)?;
    Ok(())
}
