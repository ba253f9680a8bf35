//! `facetlab.plan`: the largest, best cuts inside a rough stone (`facetlab plan ROUGH`),
//! returned as plans ([`crate::plan::run::plan_families`], as the command line plans them),
//! and with `out=` the run folder `facetlab plan --out` writes ([`crate::plan::write_folder`]
//! with the report's drawings, [`crate::report::PlanDrawings`], the binary's call).

use super::cuts::PyCut;
use super::runs::watch;
use super::{run, Whole};
use crate::error::Error;
use crate::optics::Material;
use crate::plan::config::check_families;
use crate::plan::{
    check_out, load_rough, plan_warnings, write_folder, Plan, PlanConfig, Rough, Run,
};
use crate::report::PlanDrawings;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Plan cuts in a rough: an `.obj`/`.stl` mesh in mm (its convex hull) or a crystal form's
/// name, `size_mm` its largest extent. `config` is a plan config's TOML path; `families`,
/// `material` and `top` override it. Returns the plans, best first within each family, as
/// dicts: `family`, `rank`, `cut` (a `Cut`, width 1), `width_mm`, `carats`, `volume_mm3`,
/// `yield_fraction`, `objective`, `grade`, `optic_axis` (`DEG@AZ` in the cut's frame, a
/// rough with `[rough] c_axis`) and `colour` (the face-up colour a `kind = "colour"` plan is
/// ranked by, as `score`'s `colour`), each `None` when not planned for. With `out` (a new or empty folder, never one of
/// the inputs) it also writes the run folder `facetlab plan --out` writes (`summary.json`,
/// each plan's `.asc .obj .toml` and pictures, the scene, `report.html`) and returns
/// `{"plans": [...], "folder": out}`. Ctrl-C stops it and raises `KeyboardInterrupt` (with
/// `out`, after writing the families planned so far, as the command line does).
///
/// >>> plans = facetlab.plan("octahedron", size_mm=6, families=["round-brilliant"], top=1)
/// >>> plans[0]["family"], plans[0]["carats"] > 0.2
/// ('round-brilliant', True)
/// >>> import os, tempfile
/// >>> out = os.path.join(tempfile.mkdtemp(), "plan")
/// >>> run = facetlab.plan("octahedron", size_mm=6, families=["oval"], top=1, out=out)
/// >>> run["folder"] == out, sorted(os.listdir(out))[:3]
/// (True, ['oval-1-views.png', 'oval-1-views.svg', 'oval-1.asc'])
#[pyfunction]
#[pyo3(signature = (rough, *, config=None, families=None, size_mm=None, material=None, top=None,
    out=None))]
#[allow(clippy::too_many_arguments)]
fn plan<'py>(
    py: Python<'py>,
    rough: PathBuf,
    config: Option<PathBuf>,
    families: Option<Vec<String>>,
    size_mm: Option<f64>,
    material: Option<String>,
    top: Option<Whole>,
    out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let started = Instant::now();
    // Read as the command line reads --top.
    let top = top.map(|t| t.get("top", 1, 50)).transpose()?;
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
            cfg.top = t as usize;
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
                    format!(
                        "{} is not allowed; give the rough's largest extent in (0, 1000) mm",
                        crate::error::shown(s)
                    ),
                ));
            }
        }
        if let Some(o) = &out {
            check_out("out", o, &rough_arg, config.as_deref(), &cfg)?;
        }
        let rough = load_rough(&rough_arg, size_mm)?;
        Ok((cfg, rough, material))
    })?;
    let stop = AtomicBool::new(false);
    let (planned, stopped) = watch(
        py,
        &stop,
        || crate::plan::run::plan_families(&rough, &cfg, &material, &|_| true, &|| {}, Some(&stop)),
        |_| Ok(()),
    )?;
    // Stopped (Ctrl-C): the families planned so far are written, as the command line writes
    // them, before the exception is raised; nothing is written when none was planned.
    if let Some(e) = stopped {
        if let (Some(o), Ok(all)) = (&out, &planned) {
            if !all.is_empty() {
                run(py, || {
                    write_plan(o, &rough_arg, &cfg, &material, &rough, all, started)
                })?;
            }
        }
        return Err(e);
    }
    let all = planned.map_err(super::error)?;
    let plans = PyList::empty(py);
    for (family, family_plans) in &all {
        for (rank, p) in family_plans.iter().enumerate() {
            let d = PyDict::new(py);
            d.set_item("family", family)?;
            d.set_item("rank", rank + 1)?;
            d.set_item("width_mm", p.scale)?;
            d.set_item("carats", p.carats)?;
            d.set_item("volume_mm3", p.volume_mm3)?;
            d.set_item("yield_fraction", p.yield_fraction)?;
            d.set_item("objective", p.objective)?;
            d.set_item("grade", p.grade.map(|g| g.name()))?;
            // As summary.json gives them: the plan's optic axis (a rough with a c-axis) and
            // the face-up colour it was ranked by (`kind = "colour"`), else None.
            d.set_item("optic_axis", cfg.c_axis.map(|c| p.optic_axis(c).label()))?;
            let colour = match &p.colour {
                Some(c) => Some(super::from_json(
                    py,
                    &serde_json::to_string(c)
                        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?,
                )?),
                None => None,
            };
            d.set_item("colour", colour)?;
            d.set_item("cut", Py::new(py, PyCut { cut: p.cut.clone() })?)?;
            plans.append(d)?;
        }
    }
    let Some(out) = out else {
        return Ok(plans.into_any());
    };
    run(py, || {
        write_plan(&out, &rough_arg, &cfg, &material, &rough, &all, started)
    })?;
    let done = PyDict::new(py);
    done.set_item("plans", plans)?;
    done.set_item("folder", out.display().to_string())?;
    Ok(done.into_any())
}

/// The run folder, by the binary's call.
fn write_plan(
    out: &Path,
    input: &str,
    config: &PlanConfig,
    material: &Material,
    rough: &Rough,
    all: &[(String, Vec<Plan>)],
    started: Instant,
) -> crate::error::Result<()> {
    let warnings = plan_warnings(config, all);
    let run = Run {
        out,
        input,
        config,
        material,
        rough,
        all,
        started,
        warnings: &warnings,
        layout: None,
        inclusions: &[],
    };
    write_folder(&run, &PlanDrawings)
}

/// Add `plan` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    Ok(())
}
