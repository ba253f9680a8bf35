//! Cuts in Python: `facetlab.cut(CUT)` (whatever the command line's CUT takes: a preset name
//! or a `.toml .asc .gem .obj .stl` path), `facetlab.family(name, **params)`, and the `Cut`
//! class with `with_set`, `write`, its name, family and parameters; `presets()` and
//! `families()` list what there is.

use super::call::{self, run};
use crate::cut::Cut;
use crate::error::Error;
use crate::io;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString, PyType};
use std::collections::BTreeMap;

/// A cut: a solid with its name, its family and parameters (a family's cut) or its GemCad
/// record (a design).
///
/// >>> c = facetlab.cut("tolkowsky")
/// >>> c.name, c.family, c.facets
/// ('Tolkowsky', 'round-brilliant', 73)
#[pyclass(name = "Cut", module = "facetlab", frozen)]
#[derive(Clone)]
pub struct PyCut {
    pub(crate) cut: Cut,
}

// The literal default of `meet_tol` in `Cut.info`'s signature is the library's.
const _: () = assert!(crate::design::MEET_TOL == 1e-4);

/// The cut a Python argument names: a `Cut`, or a preset name or path (`str` or
/// `os.PathLike`) loaded as the command line loads its CUT.
pub(crate) fn cut_of(obj: &Bound<'_, PyAny>) -> PyResult<Cut> {
    if let Ok(c) = obj.cast::<PyCut>() {
        return Ok(c.get().cut.clone());
    }
    let text = spec_of(obj)?;
    run(obj.py(), || io::load_cut(&text))
}

/// How a cut argument is named in documents (the command line's CUT as given): the text or
/// path given, or a `Cut`'s name.
pub(crate) fn input_of(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(c) = obj.cast::<PyCut>() {
        return Ok(c.get().cut.name.clone());
    }
    spec_of(obj)
}

/// A preset name or a path as text (`os.fspath` for path objects).
fn spec_of(obj: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(s) = obj.cast::<PyString>() {
        return s.extract::<String>();
    }
    let os = obj.py().import("os")?;
    match os.call_method1("fspath", (obj,)) {
        Ok(p) => Ok(p.extract::<String>()?),
        Err(_) => Err(call::Error::new_err(format!(
            "cut: expected a Cut, a preset name or a path, got {}",
            obj.get_type().name()?
        ))),
    }
}

/// Numbers of a `{key: value}` mapping.
fn numbers(d: Option<&Bound<'_, PyDict>>) -> PyResult<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    if let Some(d) = d {
        for (k, v) in d.iter() {
            let key: String = k.extract()?;
            let value: f64 = v
                .extract()
                .map_err(|_| call::Error::new_err(format!("{key}: `{v}` is not a number")))?;
            out.insert(key, value);
        }
    }
    Ok(out)
}

#[pymethods]
impl PyCut {
    /// The cut's name (a preset's, a file's stem, or the family's).
    #[getter]
    fn name(&self) -> &str {
        &self.cut.name
    }

    /// The family a parametric cut is built from, or `None` for a design or mesh.
    #[getter]
    fn family(&self) -> Option<&str> {
        self.cut.family.as_deref()
    }

    /// A family cut's parameters, `{key: value}` (empty for a design or mesh).
    #[getter]
    fn params(&self) -> BTreeMap<String, f64> {
        self.cut.params.clone()
    }

    /// How many facets the solid has.
    #[getter]
    fn facets(&self) -> usize {
        self.cut.solid.facets().len()
    }

    /// The cut with parameters changed, as `--set KEY=VALUE` changes them: a family's
    /// (`crown_angle=34.5`) or a design's tier angle (`P1=41.2`, its depths solved so its
    /// meets are kept). A tie such as `C1=C2` goes in the mapping: `with_set({"C1=C2": 35})`.
    ///
    /// >>> facetlab.cut("tolkowsky").with_set(crown_angle=34.5).params["crown_angle"]
    /// 34.5
    #[pyo3(signature = (changes=None, **kwargs))]
    fn with_set(
        &self,
        py: Python<'_>,
        changes: Option<&Bound<'_, PyDict>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyCut> {
        let mut all = numbers(changes)?;
        all.extend(numbers(kwargs)?);
        let cut = &self.cut;
        let out = run(py, || {
            crate::design::with_set(cut, &all).map_err(|e| match e {
                // Changes that make no solid: named by the method itself.
                Error::Invalid { field, message } if field == crate::design::CUT_PARAMETER => {
                    Error::Invalid {
                        field: "with_set".into(),
                        message,
                    }
                }
                Error::Invalid { field, message } => Error::Invalid {
                    field: format!("with_set {field}"),
                    message,
                },
                other => other,
            })
        })?;
        Ok(PyCut { cut: out })
    }

    /// Write the cut to `path` in the format its extension names (`.toml .asc .gem .obj
    /// .stl`, or `.svg` for the facet diagram), atomically; an existing file is replaced only
    /// with `overwrite=True`.
    ///
    /// >>> import os, tempfile
    /// >>> path = os.path.join(tempfile.mkdtemp(), "t.asc")
    /// >>> facetlab.cut("tolkowsky").write(path)
    /// >>> facetlab.cut(path).facets
    /// 73
    #[pyo3(signature = (path, overwrite=false))]
    fn write(&self, py: Python<'_>, path: &Bound<'_, PyAny>, overwrite: bool) -> PyResult<()> {
        let path: std::path::PathBuf = path.extract().map_err(|_| {
            call::Error::new_err(format!(
                "path: expected a file name (str or os.PathLike), got {}",
                path.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        })?;
        let cut = &self.cut;
        run(py, || {
            super::stone::refuse_existing(&path, overwrite)?;
            let ext = path
                .extension()
                .map(|e| e.to_string_lossy().to_ascii_lowercase())
                .unwrap_or_default();
            let bytes: Vec<u8> = match ext.as_str() {
                "svg" => crate::plot::diagram::diagram(cut).into_bytes(),
                e if io::CUT_FORMATS.contains(&e) => io::write_cut(cut, e)?,
                _ => {
                    return Err(Error::invalid(
                        "path",
                        format!("cannot write `.{ext}`; allowed extensions: .toml, .asc, .gem, .obj, .stl, .svg"),
                    ))
                }
            };
            io::write_atomic(&path, &bytes)
        })
    }

    /// The `facetlab info --json` document as a dict: proportions, tiers, ratios, size and
    /// weight (a width of `diameter_mm` in `material`, default the design's own, else
    /// diamond), checks and grade; with `instructions=True` the cutting instructions, with
    /// `meets=True` the design's meets within `meet_tol` of W.
    ///
    /// >>> info = facetlab.cut("tolkowsky").info()
    /// >>> info["family"], round(info["carats"], 2)
    /// ('round-brilliant', 0.99)
    #[pyo3(signature = (*, diameter_mm=6.5, material=None, instructions=false, meets=false,
        meet_tol=1e-4))]
    fn info<'py>(
        &self,
        py: Python<'py>,
        diameter_mm: f64,
        material: Option<String>,
        instructions: bool,
        meets: bool,
        meet_tol: f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let cut = &self.cut;
        let text = run(py, || {
            crate::optics::StoneSize::check_mm(diameter_mm, "diameter_mm")?;
            if !(meet_tol.is_finite() && meet_tol > 0.0 && meet_tol <= 0.01) {
                return Err(Error::invalid(
                    "meet_tol",
                    format!(
                        "{} is not allowed; give a tolerance in (0, 0.01] of W",
                        crate::error::shown(meet_tol)
                    ),
                ));
            }
            let stone = super::stone::StoneArgs {
                material,
                ..Default::default()
            };
            let (m, _) = stone.material_for(cut)?;
            let mut j = crate::document::info::info_json(cut, diameter_mm, &m);
            if instructions {
                j.instructions = Some(io::asc::cutting_instructions(cut, 0));
            }
            if meets {
                j.meets = Some(crate::document::info::meets_json(cut, meet_tol)?);
            }
            serde_json::to_string(&j).map_err(|e| Error::invalid("info", e.to_string()))
        })?;
        call::from_json(py, &text)
    }

    /// Pickling (Dask ships cuts to its workers this way): the cut's exact bytes
    /// ([`io::exact`]: every number bit for bit, its names and notes; no file is read again),
    /// restored by `Cut._from_state`.
    ///
    /// >>> import pickle
    /// >>> c = facetlab.family("round-brilliant", table=0.56).with_set(crown_angle=34.5)
    /// >>> back = pickle.loads(pickle.dumps(c))
    /// >>> back.params == c.params, facetlab.score(back).to_dict() == facetlab.score(c).to_dict()
    /// (True, True)
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyBytes>,))> {
        let restore = py.get_type::<PyCut>().getattr("_from_state")?;
        Ok((
            restore,
            (PyBytes::new(py, &io::exact::cut_bytes(&self.cut)),),
        ))
    }

    /// The cut of `__reduce__`'s bytes (for pickle).
    ///
    /// >>> c = facetlab.cut("tolkowsky")
    /// >>> facetlab.Cut._from_state(c.__reduce__()[1][0]).facets
    /// 73
    #[classmethod]
    fn _from_state(_cls: &Bound<'_, PyType>, py: Python<'_>, state: &[u8]) -> PyResult<PyCut> {
        let cut = run(py, || io::exact::cut_from_bytes(state))?;
        Ok(PyCut { cut })
    }

    fn __repr__(&self) -> String {
        match &self.cut.family {
            Some(f) => format!("<Cut {} ({f}, {} facets)>", self.cut.name, self.facets()),
            None => format!("<Cut {} ({} facets)>", self.cut.name, self.facets()),
        }
    }
}

/// A cut from anything the command line's CUT takes: a preset name or a path.
///
/// >>> facetlab.cut("gia-reference").name
/// 'GIA reference'
#[pyfunction]
fn cut(obj: &Bound<'_, PyAny>) -> PyResult<PyCut> {
    Ok(PyCut { cut: cut_of(obj)? })
}

/// A family's cut with parameters (`family("round-brilliant", table=0.56)`); the others
/// take the family's defaults. `name` names the cut (default: the family's name).
///
/// >>> facetlab.family("round-brilliant", table=0.56).params["table"]
/// 0.56
#[pyfunction]
#[pyo3(signature = (family, name=None, **params))]
fn family(
    py: Python<'_>,
    family: &str,
    name: Option<&str>,
    params: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyCut> {
    let values = numbers(params)?;
    let name = name.unwrap_or(family);
    let cut = run(py, || Cut::from_family(name, family, &values))?;
    Ok(PyCut { cut })
}

/// The preset names, as `facetlab list --names` prints them.
///
/// >>> "tolkowsky" in facetlab.presets()
/// True
#[pyfunction]
fn presets() -> Vec<&'static str> {
    io::presets::names()
}

/// The families: `{name: {"doc": …, "params": {key: {"default", "min", "max", "unit",
/// "doc"}}}}`.
///
/// >>> facetlab.families()["round-brilliant"]["params"]["table"]["unit"]
/// 'fraction of girdle diameter'
#[pyfunction]
fn families(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for f in crate::cut::families() {
        let params = PyDict::new(py);
        for p in f.params {
            let d = PyDict::new(py);
            d.set_item("default", p.default)?;
            d.set_item("min", p.min)?;
            d.set_item("max", p.max)?;
            d.set_item("open", p.open)?;
            d.set_item("unit", p.unit.label())?;
            d.set_item("doc", p.doc)?;
            params.set_item(p.key, d)?;
        }
        let fam = PyDict::new(py);
        fam.set_item("doc", f.doc)?;
        fam.set_item("params", params)?;
        out.set_item(f.name, fam)?;
    }
    Ok(out)
}

/// The materials and coloured varieties with their data, as `facetlab materials --json`
/// lists them (dicts: `name`, `nd`, `dispersion`, `formula`, `source`, `optic`, `density`,
/// `aliases`; a variety also `variety_of`, `chromophores`, `colour`, and a uniaxial one
/// `colour_e`, its E∥c colour or None with `no_spectrum_e` saying why).
///
/// >>> diamond = next(m for m in facetlab.materials() if m["name"] == "diamond")
/// >>> round(diamond["nd"], 4)
/// 2.4173
#[pyfunction]
fn materials(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let text = serde_json::to_string(&crate::document::materials::rows())
        .map_err(|e| call::Error::new_err(format!("materials: {e}")))?;
    call::from_json(py, &text)
}

/// Add the cut functions and class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyCut>()?;
    m.add_function(wrap_pyfunction!(cut, m)?)?;
    m.add_function(wrap_pyfunction!(family, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    m.add_function(wrap_pyfunction!(families, m)?)?;
    m.add_function(wrap_pyfunction!(materials, m)?)?;
    Ok(())
}
