//! `facetlab.score` and `facetlab.score_many`: the beam tracer's scores of cuts, as
//! `facetlab score` computes them, returned as `Scores` objects whose `to_dict()` is the
//! `score --json` document (the library's [`crate::metrics::json`]).

use super::args::{number, Number, Size};
use super::call::{error, from_json, run};
use super::cuts::cut_of;
use super::stone::StoneArgs;
use crate::cut::Cut;
use crate::document::score::scores_json;
use crate::error::{Error, Result};
use crate::metrics::{score as score_solid, ScoreConfig, Scores};
use pyo3::prelude::*;
use pyo3::types::PyList;
use rayon::prelude::*;
use std::collections::BTreeMap;

/// One cut's scores: attributes for each score and `to_dict()` for the whole document.
///
/// >>> s = facetlab.score("tolkowsky")
/// >>> round(s.brilliance, 2), round(sum(s.aset.values()), 12)
/// (0.67, 1.0)
#[pyclass(name = "Scores", module = "facetlab", frozen)]
pub struct PyScores {
    name: String,
    scores: Scores,
    /// The `score --json` document of this cut.
    json: String,
}

#[pymethods]
impl PyScores {
    /// The cut's name.
    #[getter]
    fn cut(&self) -> &str {
        &self.name
    }
    /// Share of overhead parallel light leaving upward, [0, 1].
    #[getter]
    fn overhead_light_return(&self) -> f64 {
        self.scores.overhead_light_return
    }
    /// (ISO + COS) / 2, [0, 1].
    #[getter]
    fn brilliance(&self) -> f64 {
        self.scores.brilliance
    }
    /// Light return under ISO lighting, averaged over poses.
    #[getter]
    fn brilliance_iso(&self) -> f64 {
        self.scores.brilliance_iso
    }
    /// Light return under COS lighting, averaged over poses.
    #[getter]
    fn brilliance_cos(&self) -> f64 {
        self.scores.brilliance_cos
    }
    /// Luminance-weighted CIELAB chroma per unit face-up area under spot lights.
    #[getter]
    fn fire(&self) -> f64 {
        self.scores.fire
    }
    /// Change of the spot-light pattern while rocking, [0, 1].
    #[getter]
    fn scintillation(&self) -> f64 {
        self.scores.scintillation
    }
    /// ASET shares: `{"blue", "red", "green", "leak", "port"}`.
    #[getter]
    fn aset(&self) -> BTreeMap<&'static str, f64> {
        let a = &self.scores.aset;
        BTreeMap::from([
            ("blue", a.blue),
            ("red", a.red),
            ("green", a.green),
            ("leak", a.leak),
            ("port", a.port),
        ])
    }
    /// The whole `score --json` document of this cut: its scores, `poses`, `colour` for a
    /// coloured stone, and `settings`.
    ///
    /// >>> d = facetlab.score("tolkowsky").to_dict()
    /// >>> d["cut"], d["settings"]["material"]
    /// ('Tolkowsky', 'diamond')
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        from_json(py, &self.json)
    }
    fn __repr__(&self) -> String {
        let s = &self.scores;
        format!(
            "<Scores {}: brilliance {:.4}, fire {:.4}, scintillation {:.4}>",
            self.name, s.brilliance, s.fire, s.scintillation
        )
    }
}

/// The scoring settings of the keyword arguments.
#[derive(Clone, Debug)]
pub(crate) struct ScoreArgs {
    pub stone: StoneArgs,
    pub polarization: bool,
    pub head_shadow: f64,
}

impl ScoreArgs {
    /// The configuration `cut` is scored with.
    pub fn config(&self, cut: &Cut) -> Result<ScoreConfig> {
        let (material, _width) = self.stone.material_for(cut)?;
        let config = ScoreConfig {
            material,
            size: self.stone.size()?,
            head_shadow_deg: self.head_shadow,
            ..ScoreConfig::default()
        }
        .polarized(self.polarization);
        config.validate()?;
        Ok(config)
    }
}

/// Score one cut into its Python object.
fn score_cut(cut: &Cut, args: &ScoreArgs) -> Result<PyScores> {
    let config = args.config(cut)?;
    let scores = score_solid(&cut.solid, &config);
    let results = [(cut.name.clone(), scores)];
    let json = scores_json(&config, &results, |_| None::<BTreeMap<&str, ()>>)
        .map_err(|e| Error::invalid("to_dict", e.to_string()))?;
    let [(name, scores)] = results;
    Ok(PyScores { name, scores, json })
}

/// `score`'s and `score_many`'s `head_shadow`: a number read as `--head-shadow` is (the
/// library's [`crate::render::settings::parse_head_shadow`], 0 to 60 degrees).
fn head_shadow(obj: &Bound<'_, PyAny>) -> PyResult<f64> {
    let x = Number(number(obj)?);
    crate::render::settings::parse_head_shadow("head_shadow", &x.text()).map_err(error)
}

/// Score a cut (a `Cut`, a preset name or a path) with the beam tracer, as `facetlab score`.
/// Keyword arguments (the command line's flags): `material`, `ri`, `colour`,
/// `colour_density`, `size_mm` (a length or "LxW"), `diameter_mm`, `birefringence`,
/// `optic_axis`, `colour_e`, `polarization`, `head_shadow` (degrees; 0 = none).
///
/// >>> round(facetlab.score("tolkowsky", material="cubic-zirconia").brilliance, 2)
/// 0.62
#[pyfunction]
#[pyo3(signature = (cut, *, material=None, ri=None, colour=None, colour_density=None,
    size_mm=None, diameter_mm=None, birefringence=None, optic_axis=None, colour_e=None,
    polarization=true, head_shadow=15.0))]
#[allow(clippy::too_many_arguments)]
fn score(
    py: Python<'_>,
    cut: &Bound<'_, PyAny>,
    material: Option<String>,
    ri: Option<Number>,
    colour: Option<String>,
    colour_density: Option<Number>,
    size_mm: Option<Size>,
    diameter_mm: Option<Number>,
    birefringence: Option<bool>,
    optic_axis: Option<String>,
    colour_e: Option<String>,
    polarization: bool,
    #[pyo3(from_py_with = head_shadow)] head_shadow: f64,
) -> PyResult<PyScores> {
    let args = ScoreArgs {
        stone: StoneArgs::given(
            material,
            ri,
            colour,
            colour_density,
            size_mm,
            diameter_mm,
            birefringence,
            optic_axis,
            colour_e,
        ),
        polarization,
        head_shadow,
    };
    let cut = cut_of(cut)?;
    run(py, || score_cut(&cut, &args))
}

/// Score many cuts in parallel (one task per cut over all cores), results in the order given;
/// the keyword arguments are `score`'s.
///
/// >>> [s.cut for s in facetlab.score_many(["tolkowsky", "gia-reference"])]
/// ['Tolkowsky', 'GIA reference']
#[pyfunction]
#[pyo3(signature = (cuts, *, material=None, ri=None, colour=None, colour_density=None,
    size_mm=None, diameter_mm=None, birefringence=None, optic_axis=None, colour_e=None,
    polarization=true, head_shadow=15.0))]
#[allow(clippy::too_many_arguments)]
fn score_many<'py>(
    py: Python<'py>,
    cuts: &Bound<'py, PyAny>,
    material: Option<String>,
    ri: Option<Number>,
    colour: Option<String>,
    colour_density: Option<Number>,
    size_mm: Option<Size>,
    diameter_mm: Option<Number>,
    birefringence: Option<bool>,
    optic_axis: Option<String>,
    colour_e: Option<String>,
    polarization: bool,
    #[pyo3(from_py_with = head_shadow)] head_shadow: f64,
) -> PyResult<Bound<'py, PyList>> {
    let args = ScoreArgs {
        stone: StoneArgs::given(
            material,
            ri,
            colour,
            colour_density,
            size_mm,
            diameter_mm,
            birefringence,
            optic_axis,
            colour_e,
        ),
        polarization,
        head_shadow,
    };
    // A str is iterable too, letter by letter: one cut is `score`'s.
    if cuts.is_instance_of::<pyo3::types::PyString>() {
        return Err(super::call::Error::new_err(format!(
            "cuts: `{}` is one str, not a list of cuts; give a list such as [\"tolkowsky\"], or score one cut with facetlab.score",
            cuts
        )));
    }
    let cuts: Vec<Cut> = cuts
        .try_iter()?
        .map(|c| cut_of(&c?))
        .collect::<PyResult<_>>()?;
    let scored = run(py, || {
        cuts.par_iter()
            .map(|c| score_cut(c, &args))
            .collect::<Result<Vec<_>>>()
    })?;
    PyList::new(
        py,
        scored
            .into_iter()
            .map(|s| Py::new(py, s))
            .collect::<PyResult<Vec<_>>>()?,
    )
}

// The literal default of `head_shadow` in the signatures above is the library's.
const _: () = assert!(crate::metrics::DEFAULT_HEAD_SHADOW_DEG == 15.0);

/// For the binding-overhead bench (benches/python_overhead.py): seconds of each of `repeats`
/// library calls `metrics::score(solid, config)` on `cut`, timed in Rust with the defaults
/// `facetlab.score(cut)` uses, so Python's own cost is what `facetlab.score` adds.
#[pyfunction]
fn _library_score_seconds(
    py: Python<'_>,
    cut: &Bound<'_, PyAny>,
    repeats: usize,
) -> PyResult<Vec<f64>> {
    let cut = cut_of(cut)?;
    let args = ScoreArgs {
        stone: StoneArgs::default(),
        polarization: true,
        head_shadow: crate::metrics::DEFAULT_HEAD_SHADOW_DEG,
    };
    run(py, || {
        let config = args.config(&cut)?;
        Ok((0..repeats)
            .map(|_| {
                let t0 = std::time::Instant::now();
                std::hint::black_box(score_solid(&cut.solid, &config));
                t0.elapsed().as_secs_f64()
            })
            .collect())
    })
}

/// Add the score functions and class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScores>()?;
    m.add_function(wrap_pyfunction!(score, m)?)?;
    m.add_function(wrap_pyfunction!(score_many, m)?)?;
    m.add_function(wrap_pyfunction!(_library_score_seconds, m)?)?;
    Ok(())
}
