//! `facetlab.render`: a cut's picture as `facetlab render` draws it (one cut, `--bare`), under
//! a laboratory light or photographed under a studio rig, a map or `env:FILE`, with its linear
//! values, its sRGB bytes and its statistics (the `render --json` document's keys, from
//! [`crate::document::render`]). Each of the picture's settings is read by the library's parser
//! of it ([`read`]) into the settings the command line's pictures are made from too
//! ([`PictureSettings`]); its errors name the keyword argument.

use super::args::{number, Number, Size, Whole};
use super::call::{error, from_json, run};
use super::cuts::cut_of;
use super::stone::{refuse_existing, StoneArgs};
use crate::error::{Error, Result};
use crate::plot::palette::PICTURE_GROUND;
use crate::render::photo::{Photo, Tone};
use crate::render::settings::{self as picture, read, LightChoice};
use crate::render::Image;
use crate::render::{PictureSettings, Pictures};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

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
        from_json(py, &self.stats)
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
/// its exposure and its statistics as `render --json` writes them (`output` empty), frame 0
/// and its record as the command line's `render` makes them ([`crate::plot::render`]).
fn draw(
    cut: &crate::cut::Cut,
    input: &str,
    settings: &PictureSettings,
    stone: &StoneArgs,
) -> Result<(Picture, f64, String)> {
    use crate::plot::render::{lab_frame, lab_record, photo_frame, photo_record};
    let choice = stone.choice()?;
    let pictures = settings.pictures(&choice.material, choice.size)?;
    let (material, width_mm) = stone.material_for(cut)?;
    let name = (cut.name.as_str(), input);
    let (picture, exposure, json) = match pictures {
        Pictures::Lab(p) => {
            let (img, frame) = lab_frame(&p, &cut.solid, material.clone(), width_mm, 0);
            let record = lab_record(&p, name, material, width_mm, vec![frame]);
            let json = serde_json::to_string(&record);
            (Picture::Lab(Box::new(img)), p.exposure, json)
        }
        Pictures::Photo(p) => {
            let (opts, photo, frame) = photo_frame(&p, &cut.solid, material.clone(), width_mm, 0);
            let record = photo_record(&p, name, material, width_mm, &photo.stats, vec![frame]);
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
#[pyo3(name = "render", signature = (cut, *, light="iso", size=256, tilt=None, view=None,
    distance=None, aperture=None, ground=None, ground_gap=None, light_rotation=None, tone=None,
    bands=None, head_shadow=None, exposure=1.0, polarization=true, material=None, ri=None,
    colour=None, colour_density=None, size_mm=None, diameter_mm=None, birefringence=None,
    optic_axis=None, colour_e=None, float64=false))]
#[allow(clippy::too_many_arguments)]
fn render_cut(
    py: Python<'_>,
    cut: &Bound<'_, PyAny>,
    light: &str,
    #[pyo3(from_py_with = picture_size)] size: usize,
    tilt: Option<Size>,
    view: Option<Size>,
    distance: Option<Number>,
    aperture: Option<Number>,
    ground: Option<String>,
    ground_gap: Option<Number>,
    light_rotation: Option<Number>,
    tone: Option<String>,
    bands: Option<Whole>,
    head_shadow: Option<Number>,
    #[pyo3(from_py_with = exposure)] exposure: f64,
    polarization: bool,
    material: Option<String>,
    ri: Option<Number>,
    colour: Option<String>,
    colour_density: Option<Number>,
    size_mm: Option<Size>,
    diameter_mm: Option<Number>,
    birefringence: Option<bool>,
    optic_axis: Option<String>,
    colour_e: Option<String>,
    float64: bool,
) -> PyResult<PyRender> {
    use crate::render::photo::{parse_view, GroundKind, Tone};
    use crate::render::pose::parse_tilt;
    // Each as the command line's text (a number of degrees or `DEG@AZ`, …), read by its
    // setting's parser, whose error names the keyword.
    let num = |n: Option<Number>| n.map(Number::text);
    let settings = PictureSettings {
        light: LightChoice::parse(picture::LIGHT, light).map_err(error)?,
        size: Some(size),
        tilt: read(tilt.map(|t| t.text()).as_deref(), picture::TILT, parse_tilt).map_err(error)?,
        head_shadow: read(
            num(head_shadow).as_deref(),
            picture::HEAD_SHADOW,
            picture::parse_head_shadow,
        )
        .map_err(error)?,
        exposure: Some(exposure),
        polarization,
        view: read(view.map(|v| v.text()).as_deref(), picture::VIEW, parse_view).map_err(error)?,
        distance: read(
            num(distance).as_deref(),
            picture::DISTANCE,
            picture::parse_distance,
        )
        .map_err(error)?,
        aperture: read(
            num(aperture).as_deref(),
            picture::APERTURE,
            picture::parse_aperture,
        )
        .map_err(error)?,
        ground: read(ground.as_deref(), picture::GROUND, GroundKind::parse).map_err(error)?,
        ground_gap: read(
            num(ground_gap).as_deref(),
            picture::GROUND_GAP,
            picture::parse_ground_gap,
        )
        .map_err(error)?,
        light_rotation: read(
            num(light_rotation).as_deref(),
            picture::LIGHT_ROTATION,
            picture::parse_light_rotation,
        )
        .map_err(error)?,
        tone: read(tone.as_deref(), picture::TONE, Tone::parse).map_err(error)?,
        bands: read(
            bands.as_ref().map(Whole::text),
            picture::BANDS,
            picture::parse_bands,
        )
        .map_err(error)?,
    };
    let stone = StoneArgs::given(
        material,
        ri,
        colour,
        colour_density,
        size_mm,
        diameter_mm,
        birefringence,
        optic_axis,
        colour_e,
    );
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

/// `render`'s `size`: pixels per side, read as `--size` is ([`picture::parse_size`]).
fn picture_size(obj: &Bound<'_, PyAny>) -> PyResult<usize> {
    let n = obj.extract::<Whole>()?;
    picture::parse_size(picture::SIZE, n.text()).map_err(error)
}

/// `render`'s `exposure`: a brightness factor, read as `--exposure` is
/// ([`picture::parse_exposure`]).
fn exposure(obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    let x = Number(number(obj)?);
    picture::parse_exposure(picture::EXPOSURE, &x.text()).map_err(error)
}

/// Add `render` and its class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRender>()?;
    m.add_function(wrap_pyfunction!(render_cut, m)?)?;
    Ok(())
}
