//! `facetlab.plan`: the largest, best cuts inside a rough stone (`facetlab plan ROUGH`),
//! returned as plans ([`crate::plan::run::plan_families`], as the command line plans them),
//! and with `out=` the run folder `facetlab plan --out` writes ([`crate::plan::write_folder`]
//! with the report's drawings, [`crate::report::PlanDrawings`], the binary's call).

use super::args::{within, Whole};
use super::call::{self, run};
use super::cuts::PyCut;
use super::runs::watch;
use crate::error::Error;
use crate::optics::Material;
use crate::plan::config::check_families;
use crate::plan::config::{Cutter, MAX_GAP_MM, MAX_STONES};
use crate::plan::{
    check_out, load_rough, plan_layout, plan_warnings, write_folder, Inclusion, Plan, PlanConfig,
    Rough, Run, CRYSTALS,
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
///
/// Several stones (issue 54, `facetlab plan --stones N`): `stones` (1–8), `kerf` and
/// `allowance` (mm), `inclusions` (paths of closed `.obj`/`.stl` meshes in mm in the rough's
/// coordinates) and `margin` (mm) override the config's `[rough]` keys; with `stones` above 1
/// or any inclusion the rough is sawn into pieces and one stone placed in each
/// (`crate::plan::plan_layout`). The plans are then the layout's stones in the order of
/// their pieces, each dict also with `piece` (its piece's label), `centre_mm` (the stone's
/// centroid in the rough's coordinates) and `holds` (the inclusions it holds at the price
/// table's `included` factor); with `out` the returned dict also has `layout`: `total`,
/// `carats`, `yield_fraction`, `kerf_loss_mm3` and `saw_plan` (the cuts in cutting order,
/// each `piece`, `normal`, `offset_mm` and `kerf_loss_mm3`), as `summary.json` has them.
/// `cutter` (`"saw"` or `"laser"`, the config's `[rough] cutter`): with a laser the stones
/// are parted pair by pair, not by cuts through the piece, and `saw_plan` holds the laser's
/// cuts; `layout` also has `cutter` and `pairs` (each pair's `stones`, indices from 0, and
/// the plane between them, `normal` and `offset_mm`). A config with `[objective] kind =
/// "colour"` ranks the layout by value × colour (docs/plan.md): each stone's dict then
/// also has `worth` (its price-table value, else its carats) and `colour_factor` (its
/// face-up chroma over the material's reference; `objective` is their product, `colour` its
/// face-up colour), and `layout` has `total_worth` and `colour_reference` (C*).
#[pyfunction]
#[pyo3(signature = (rough, *, config=None, families=None, size_mm=None, material=None, top=None,
    stones=None, kerf=None, allowance=None, inclusions=None, margin=None, cutter=None, out=None))]
#[allow(clippy::too_many_arguments)]
fn plan<'py>(
    py: Python<'py>,
    rough: PathBuf,
    config: Option<PathBuf>,
    families: Option<Vec<String>>,
    size_mm: Option<f64>,
    material: Option<String>,
    top: Option<Whole>,
    stones: Option<Whole>,
    kerf: Option<f64>,
    allowance: Option<f64>,
    inclusions: Option<Vec<PathBuf>>,
    margin: Option<f64>,
    cutter: Option<String>,
    out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let started = Instant::now();
    // Read as the command line reads --top and --stones.
    let top = top.map(|t| t.get("top", 1, 50)).transpose()?;
    let stones = stones
        .map(|t| t.get("stones", 1, MAX_STONES as u64))
        .transpose()?;
    let inclusion_paths = inclusions.unwrap_or_default();
    let rough_arg = rough.display().to_string();
    let (cfg, rough, material, inclusions) = run(py, || {
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
            crate::plan::rough_size_mm("size_mm", s)?;
        }
        if let Some(n) = stones {
            cfg.stones = n as usize;
        }
        if let Some(c) = &cutter {
            cfg.cutter = Cutter::named("cutter", c)?;
        }
        for (name, value, to) in [
            ("kerf", kerf, &mut cfg.kerf_mm),
            ("allowance", allowance, &mut cfg.allowance_mm),
            ("margin", margin, &mut cfg.margin_mm),
        ] {
            if let Some(v) = value {
                *to = within(name, v, 0.0, MAX_GAP_MM, "a distance in mm")?;
            }
        }
        if !inclusion_paths.is_empty()
            && size_mm.is_some()
            && !CRYSTALS.contains(&rough_arg.as_str())
        {
            return Err(Error::invalid(
                "inclusions",
                "a mesh rescaled by size_mm has no coordinates the inclusions could share; give the rough in mm without size_mm",
            ));
        }
        let inclusions: Vec<Inclusion> = inclusion_paths
            .iter()
            .map(|p| Inclusion::from_mesh(p, cfg.margin_mm))
            .collect::<crate::error::Result<_>>()?;
        if let Some(o) = &out {
            check_out("out", o, &rough_arg, config.as_deref(), &cfg)?;
            for p in &inclusion_paths {
                crate::io::guard::refuse_overwrite(&[("out", o.clone())], std::slice::from_ref(p))?;
            }
        }
        let rough = load_rough(&rough_arg, size_mm)?;
        Ok((cfg, rough, material, inclusions))
    })?;
    if cfg.stones > 1 || !inclusions.is_empty() {
        let job = Job {
            input: &rough_arg,
            config: &cfg,
            material: &material,
            rough: &rough,
            inclusions: &inclusions,
            started,
        };
        return layout(py, &job, out);
    }
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
    let all = planned.map_err(call::error)?;
    let plans = PyList::empty(py);
    for (family, family_plans) in &all {
        for (rank, p) in family_plans.iter().enumerate() {
            plans.append(plan_dict(py, &cfg, family, rank + 1, p)?)?;
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

/// One plan as a dict (see [`plan`]).
fn plan_dict<'py>(
    py: Python<'py>,
    cfg: &PlanConfig,
    family: &str,
    rank: usize,
    p: &Plan,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("family", family)?;
    d.set_item("rank", rank)?;
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
        Some(c) => Some(call::from_json(
            py,
            &serde_json::to_string(c)
                .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?,
        )?),
        None => None,
    };
    d.set_item("colour", colour)?;
    d.set_item("cut", Py::new(py, PyCut { cut: p.cut.clone() })?)?;
    Ok(d)
}

/// What a layout is planned from.
struct Job<'a> {
    input: &'a str,
    config: &'a PlanConfig,
    material: &'a Material,
    rough: &'a Rough,
    inclusions: &'a [Inclusion],
    started: Instant,
}

/// A layout of several stones (see [`plan`]): its stones as plan dicts, with `out` the run
/// folder the command line writes and the layout's totals and saw plan.
fn layout<'py>(py: Python<'py>, job: &Job, out: Option<PathBuf>) -> PyResult<Bound<'py, PyAny>> {
    let stop = AtomicBool::new(false);
    let (planned, stopped) = watch(
        py,
        &stop,
        || {
            plan_layout(
                job.rough,
                job.config,
                job.material,
                job.inclusions,
                &|| {},
                Some(&stop),
            )
        },
        |_| Ok(()),
    )?;
    if let Some(e) = stopped {
        return Err(e);
    }
    let layout = planned.map_err(call::error)?;
    let plans = PyList::empty(py);
    for (k, s) in layout.stones.iter().enumerate() {
        let d = plan_dict(py, job.config, &s.family, k + 1, &s.plan)?;
        d.set_item("piece", &s.piece)?;
        let c = s.plan.placed_solid().map_err(call::error)?.centroid();
        d.set_item("centre_mm", [c.x, c.y, c.z])?;
        let holds: Vec<&str> = s
            .holds
            .iter()
            .map(|&i| job.inclusions[i].name.as_str())
            .collect();
        d.set_item("holds", holds)?;
        if let Some(w) = s.colour {
            d.set_item("worth", w.worth)?;
            d.set_item("colour_factor", w.factor)?;
        }
        plans.append(d)?;
    }
    let Some(out) = out else {
        return Ok(plans.into_any());
    };
    run(py, || {
        let run = Run {
            out: &out,
            input: job.input,
            config: job.config,
            material: job.material,
            rough: job.rough,
            all: &[],
            started: job.started,
            warnings: &[],
            layout: Some(&layout),
            inclusions: job.inclusions,
        };
        write_folder(&run, &PlanDrawings)
    })?;
    let l = PyDict::new(py);
    l.set_item("total", layout.total)?;
    l.set_item("carats", layout.carats)?;
    l.set_item("yield_fraction", layout.yield_fraction)?;
    l.set_item("kerf_loss_mm3", layout.kerf_loss_mm3)?;
    let saw = PyList::empty(py);
    for c in &layout.saw {
        let d = PyDict::new(py);
        d.set_item("piece", &c.piece)?;
        d.set_item("normal", [c.normal.x, c.normal.y, c.normal.z])?;
        d.set_item("offset_mm", c.offset)?;
        d.set_item("kerf_loss_mm3", c.kerf_loss_mm3)?;
        saw.append(d)?;
    }
    l.set_item("saw_plan", saw)?;
    l.set_item("cutter", layout.cutter.name())?;
    let pairs = PyList::empty(py);
    for p in &layout.pairs {
        let d = PyDict::new(py);
        d.set_item("stones", p.stones)?;
        d.set_item("normal", [p.normal.x, p.normal.y, p.normal.z])?;
        d.set_item("offset_mm", p.offset)?;
        pairs.append(d)?;
    }
    l.set_item("pairs", pairs)?;
    if let Some(r) = layout.colour_reference {
        let worth: f64 = layout
            .stones
            .iter()
            .filter_map(|s| s.colour)
            .map(|c| c.worth)
            .sum();
        l.set_item("total_worth", worth)?;
        l.set_item("colour_reference", r)?;
    }
    let done = PyDict::new(py);
    done.set_item("plans", plans)?;
    done.set_item("folder", out.display().to_string())?;
    done.set_item("layout", l)?;
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
