//! `facetlab.plan`: the largest, best cuts inside a rough stone (`facetlab plan ROUGH`),
//! returned as plans ([`crate::plan::run::plan_families`], as the command line plans them;
//! the run folder it writes with its drawings is not written from Python yet).

use super::cuts::PyCut;
use super::run;
use super::runs::watched;
use crate::error::Error;
use crate::optics::Material;
use crate::plan::config::check_families;
use crate::plan::{load_rough, PlanConfig};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// Plan cuts in a rough: an `.obj`/`.stl` mesh in mm (its convex hull) or a crystal form's
/// name, `size_mm` its largest extent. `config` is a plan config's TOML path; `families`,
/// `material` and `top` override it. Returns the plans, best first within each family, as
/// dicts: `family`, `rank`, `cut` (a `Cut`, width 1), `width_mm`, `carats`, `volume_mm3`,
/// `yield_fraction`, `objective`, `grade`. Ctrl-C stops it and raises `KeyboardInterrupt`.
///
/// >>> plans = facetlab.plan("octahedron", size_mm=6, families=["round-brilliant"], top=1)
/// >>> plans[0]["family"], plans[0]["carats"] > 0.2
/// ('round-brilliant', True)
#[pyfunction]
#[pyo3(signature = (rough, *, config=None, families=None, size_mm=None, material=None, top=None))]
fn plan<'py>(
    py: Python<'py>,
    rough: PathBuf,
    config: Option<PathBuf>,
    families: Option<Vec<String>>,
    size_mm: Option<f64>,
    material: Option<String>,
    top: Option<usize>,
) -> PyResult<Bound<'py, PyList>> {
    let rough_arg = rough.display().to_string();
    let (cfg, rough, material) = run(py, || {
        let mut cfg = match &config {
            Some(p) => PlanConfig::load(p)?,
            None => PlanConfig::default(),
        };
        if let Some(f) = &families {
            cfg.families = check_families(f).map_err(|m| Error::invalid("families", m))?;
        }
        if let Some(t) = top {
            if !(1..=50).contains(&t) {
                return Err(Error::invalid(
                    "top",
                    format!("`{t}` is not allowed; give a whole number in [1, 50]"),
                ));
            }
            cfg.top = t;
        }
        if let Some(m) = &material {
            Material::by_name(m)?;
            cfg.material = m.clone();
        }
        let material = Material::by_name(&cfg.material)?;
        if let Some(s) = size_mm {
            if !(s.is_finite() && s > 0.0 && s < 1000.0) {
                return Err(Error::invalid(
                    "size_mm",
                    format!("{s} is not allowed; give the rough's largest extent in (0, 1000) mm"),
                ));
            }
        }
        let rough = load_rough(&rough_arg, size_mm)?;
        Ok((cfg, rough, material))
    })?;
    let stop = AtomicBool::new(false);
    let all = watched(
        py,
        &stop,
        || crate::plan::run::plan_families(&rough, &cfg, &material, &|_| true, &|| {}, Some(&stop)),
        |_| Ok(()),
    )?;
    let out = PyList::empty(py);
    for (family, plans) in all {
        for (rank, p) in plans.into_iter().enumerate() {
            let d = PyDict::new(py);
            d.set_item("family", &family)?;
            d.set_item("rank", rank + 1)?;
            d.set_item("width_mm", p.scale)?;
            d.set_item("carats", p.carats)?;
            d.set_item("volume_mm3", p.volume_mm3)?;
            d.set_item("yield_fraction", p.yield_fraction)?;
            d.set_item("objective", p.objective)?;
            d.set_item("grade", p.grade.map(|g| g.name()))?;
            d.set_item("cut", Py::new(py, PyCut { cut: p.cut })?)?;
            out.append(d)?;
        }
    }
    Ok(out)
}

/// Add `plan` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    Ok(())
}
