//! Optimization configs in Python: `facetlab.optimize(config)` (a run folder, as `facetlab
//! optimize` writes it) and `facetlab.Grid(config, axes)` (the points of `facetlab sweep`,
//! evaluated all at once or a chunk at a time, and merged back into the sweep's CSV). A config
//! is a path to its TOML or a dict of the TOML's shape.
//!
//! Long runs go on a worker thread while the calling thread watches ([`watched`]): it passes
//! progress to the Python callback and, on Ctrl-C (`KeyboardInterrupt`), raises the run's stop
//! flag, waits for the run to write its folder, then re-raises.

use super::args::Whole;
use super::call::{self, run};
use crate::error::{Error, Result};
use crate::optimize::{
    self as opt, BeamEvaluator, Config, Hooks, PhotonVerifier, Progress, RunOptions, Status,
};
use crate::sweep::{self, Grid, GridCell};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Duration;

/// The config a Python argument names: a path to a TOML file, or a dict of the TOML's shape
/// (written out as TOML and read as the command line reads a file, so the errors are the
/// same; relative paths inside it are relative to the working folder).
pub(crate) fn config_of(obj: &Bound<'_, PyAny>) -> PyResult<Config> {
    let py = obj.py();
    if obj.cast::<PyDict>().is_ok() {
        let text: String = py
            .import("json")?
            .call_method1("dumps", (obj,))?
            .extract()?;
        return run(py, || {
            let value: serde_json::Value =
                serde_json::from_str(&text).map_err(|e| Error::invalid("config", e.to_string()))?;
            let toml = toml::to_string(&value)
                .map_err(|e| Error::invalid("config", format!("not a TOML table: {e}")))?;
            Config::from_str(&toml, "config")
        });
    }
    let path: PathBuf = obj.extract().map_err(|_| {
        call::Error::new_err("config: expected a path to a TOML config or a dict of its shape")
    })?;
    run(py, || Config::load(&path))
}

/// The latest progress snapshot, handed from the run's threads to the watching thread.
#[derive(Default)]
struct Latest(Mutex<Option<Status>>);

impl Progress for Latest {
    fn update(&self, s: &Status) {
        if let Ok(mut l) = self.0.lock() {
            *l = Some(*s);
        }
    }
}

/// Run `work` on a worker thread while this thread, every 50 ms, checks for Ctrl-C and calls
/// `tick` (the progress callback). On `KeyboardInterrupt` or an exception from `tick`, `stop`
/// is raised, the work allowed to finish (it writes what it found), and the exception is
/// returned after it. A panic in `work` becomes `facetlab.InternalError`.
pub(crate) fn watched<T: Send>(
    py: Python<'_>,
    stop: &AtomicBool,
    work: impl FnOnce() -> Result<T> + Send,
    tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    let (result, pending) = watch(py, stop, work, tick)?;
    if let Some(e) = pending {
        return Err(e);
    }
    result.map_err(call::error)
}

/// [`watched`], handing back both what the work returned and the exception that stopped it
/// (a `KeyboardInterrupt`), so the caller can write what was found before raising it.
pub(crate) fn watch<T: Send>(
    py: Python<'_>,
    stop: &AtomicBool,
    work: impl FnOnce() -> Result<T> + Send,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<(Result<T>, Option<PyErr>)> {
    let mut pending: Option<PyErr> = None;
    let out = std::thread::scope(|s| {
        let h = s.spawn(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)));
        loop {
            let done = py.detach(|| {
                for _ in 0..10 {
                    if h.is_finished() {
                        return true;
                    }
                    std::thread::sleep(Duration::from_millis(5));
                }
                false
            });
            if pending.is_none() {
                if let Err(e) = py.check_signals().and_then(|_| tick(py)) {
                    stop.store(true, Ordering::SeqCst);
                    pending = Some(e);
                }
            }
            if done {
                break;
            }
        }
        py.detach(|| h.join())
    });
    match out {
        Ok(Ok(r)) => Ok((r, pending)),
        Ok(Err(p)) | Err(p) => Err(call::panicked(p)),
    }
}

/// Run an optimization as `facetlab optimize CONFIG --out OUT` does and return its
/// `report.json` as a dict with `folder` (the run folder written). `progress(status)` is
/// called about every 50 ms with `{"iterations", "evaluations", "budget", "best_cost",
/// "elapsed"}`; Ctrl-C stops the search after the current iteration, writes the folder with
/// what was found, and raises `KeyboardInterrupt`. A trade-off config (`[objective]
/// pareto`) writes the folder `facetlab optimize` writes for it and returns its
/// `pareto.json` (the front, its corners and knee, `scores`, `searches`, …) with `folder`.
///
/// >>> import os, tempfile
/// >>> config = {"cut": {"family": "round-brilliant"}, "free": {"crown_angle": [32, 36]},
/// ...           "score": {"ri": 1.54, "polarization": False},
/// ...           "method": {"starts": 1, "max_evaluations": 4}, "verify": {"winners": 0}}
/// >>> out = os.path.join(tempfile.mkdtemp(), "run")
/// >>> report = facetlab.optimize(config, out=out)
/// >>> report["folder"] == out, os.path.isfile(os.path.join(out, "best.asc"))
/// (True, True)
#[pyfunction]
#[pyo3(signature = (config, *, out=None, seed=None, verify=true, progress=None, overwrite=false))]
fn optimize<'py>(
    py: Python<'py>,
    config: &Bound<'py, PyAny>,
    out: Option<PathBuf>,
    seed: Option<Whole>,
    verify: bool,
    progress: Option<Bound<'py, PyAny>>,
    overwrite: bool,
) -> PyResult<Bound<'py, PyAny>> {
    // Read as the command line reads --seed.
    let seed = seed.map(|s| s.get("seed", 0, u64::MAX)).transpose()?;
    let mut config = config_of(config)?;
    if let Some(s) = seed {
        config.seed = s;
    }
    if let Some(dir) = &out {
        let busy = dir.is_dir()
            && std::fs::read_dir(dir)
                .map(|mut d| d.next().is_some())
                .unwrap_or(false);
        if busy && !overwrite {
            return Err(call::Error::new_err(format!(
                "out: folder {} is not empty; choose a new folder, or pass overwrite=True",
                dir.display()
            )));
        }
    }
    run(py, || config.start_cut().map(|_| ()))?;
    let stop = AtomicBool::new(false);
    let latest = Latest::default();
    let evaluator = BeamEvaluator::new(&config);
    let verifier = PhotonVerifier::new(&config);
    let verifier: Option<&dyn opt::Verifier> = if verify { Some(&verifier) } else { None };
    let report_progress = |py: Python<'_>| -> PyResult<()> {
        let Some(cb) = &progress else { return Ok(()) };
        let s = latest.0.lock().ok().and_then(|mut l| l.take());
        if let Some(s) = s {
            let d = PyDict::new(py);
            d.set_item("iterations", s.iterations)?;
            d.set_item("evaluations", s.evaluations)?;
            d.set_item("budget", s.budget)?;
            d.set_item("best_cost", s.best_cost)?;
            d.set_item("elapsed", s.elapsed)?;
            cb.call1((d,))?;
        }
        Ok(())
    };
    if config.pareto.is_some() {
        // A trade-off (`[objective] pareto`): its folder as `facetlab optimize` writes it
        // (pareto.csv, pareto.json, the chart, config.toml), and pareto.json as the answer.
        let dir = out
            .unwrap_or_else(|| opt::new_run_dir(&RunOptions::default().results_root, &config.name));
        run(py, || crate::io::check_writable(&dir))?;
        watched(
            py,
            &stop,
            || {
                let hooks = Hooks {
                    stop: Some(&stop),
                    progress: Some(&latest),
                };
                opt::run_pareto(
                    &config,
                    &evaluator,
                    verifier,
                    &dir,
                    Some(crate::plot::pareto::pareto),
                    &hooks,
                )
            },
            report_progress,
        )?;
        let text = std::fs::read_to_string(dir.join("pareto.json"))
            .map_err(|e| call::Error::new_err(format!("{}: {e}", dir.display())))?;
        let front = call::from_json(py, &text)?;
        front.set_item("folder", dir.display().to_string())?;
        return Ok(front);
    }
    let summary = watched(
        py,
        &stop,
        || {
            let opts = RunOptions {
                out,
                writers: crate::plot::optimize::run_writers(&config),
                convergence: Some(crate::plot::optimize::convergence),
                hooks: Hooks {
                    stop: Some(&stop),
                    progress: Some(&latest),
                },
                html_report: Some(crate::report::run_page),
                ..RunOptions::default()
            };
            opt::run(&config, &evaluator, verifier, &opts)
        },
        report_progress,
    )?;
    let text = serde_json::to_string(&summary.report)
        .map_err(|e| call::Error::new_err(format!("report: {e}")))?;
    let report = call::from_json(py, &text)?;
    report.set_item("folder", summary.dir.display().to_string())?;
    Ok(report)
}

/// The points of a sweep over a config's parameters (`facetlab sweep CONFIG --axis …`).
///
/// >>> config = {"cut": {"family": "round-brilliant"}, "free": {"crown_angle": [30, 38]},
/// ...           "score": {"ri": 1.54, "polarization": False}}
/// >>> g = facetlab.Grid(config, ["crown_angle:33:34:1"])
/// >>> len(g), [r["crown_angle"] for r in g.rows()]
/// (2, [33.0, 34.0])
/// >>> g.csv(g.rows()).splitlines()[0]
/// 'crown_angle,brilliance,fire,scintillation,objective,...'
#[pyclass(name = "Grid", module = "facetlab", frozen)]
pub struct PyGrid {
    config: Config,
    grid: Grid,
}

impl PyGrid {
    /// A row dict of a grid point, with the values a shard's `rows.csv` line holds (the
    /// library's [`GridCell::named`]): `index`, the axes' values, the four scores, `ok` and
    /// the extra scores.
    fn row<'py>(&self, py: Python<'py>, cell: &GridCell) -> PyResult<Bound<'py, PyDict>> {
        let (fixed, extras) = cell.named(&self.grid);
        let d = PyDict::new(py);
        d.set_item("index", cell.index)?;
        for (k, v) in fixed {
            d.set_item(k, v)?;
        }
        d.set_item("ok", extras.is_some())?;
        for (k, v) in extras.into_iter().flatten() {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// A row dict back as its grid point (the library's [`GridCell::from_named`]).
    fn cell(&self, row: &Bound<'_, PyDict>) -> PyResult<GridCell> {
        let index: usize = row
            .get_item("index")?
            .ok_or_else(|| call::Error::new_err("rows: a row has no `index`"))?
            .extract()?;
        let ok: bool = match row.get_item("ok")? {
            Some(v) => v.extract()?,
            None => true,
        };
        let mut values = Vec::new();
        for (k, v) in row.iter() {
            let k: String = k.extract()?;
            if k != "index" && k != "ok" {
                values.push((k, v.extract::<f64>()?));
            }
        }
        GridCell::from_named(&self.grid, index, ok, &values)
            .map_err(|e| call::Error::new_err(format!("rows: {e}")))
    }
}

#[pymethods]
impl PyGrid {
    /// The grid over `axes` ("KEY:MIN:MAX:STEP" each, as `--x`, `--y` and `--axis` take
    /// them, in that order) of the config (a TOML path or a dict of its shape).
    #[new]
    fn new(py: Python<'_>, config: &Bound<'_, PyAny>, axes: Vec<String>) -> PyResult<PyGrid> {
        let config = config_of(config)?;
        let grid = run(py, || {
            let parsed = axes
                .iter()
                .map(|a| sweep::Axis::parse("axes", a, &config))
                .collect::<Result<Vec<_>>>()?;
            Grid::new(parsed)
        })?;
        Ok(PyGrid { config, grid })
    }

    /// The number of points.
    fn __len__(&self) -> usize {
        self.grid.len()
    }

    /// The axes' keys, in order.
    #[getter]
    fn keys(&self) -> Vec<String> {
        self.grid.axes.iter().map(|a| a.key.clone()).collect()
    }

    /// Evaluate the points `indices` (default all) in parallel and return their rows in the
    /// order given: dicts with `index`, each axis's value, `brilliance`, `fire`,
    /// `scintillation`, `objective`, `ok` (False where the cut could not be made) and the
    /// extra scores. Ctrl-C stops it and raises `KeyboardInterrupt`.
    ///
    /// >>> g = facetlab.Grid({"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
    /// ...                    "score": {"ri": 1.54, "polarization": False}}, ["table:0.55:0.57:0.01"])
    /// >>> [(r["index"], r["table"], r["ok"]) for r in g.rows([2, 0])]
    /// [(2, 0.57, True), (0, 0.55, True)]
    #[pyo3(signature = (indices=None))]
    fn rows<'py>(
        &self,
        py: Python<'py>,
        indices: Option<Vec<Whole>>,
    ) -> PyResult<Bound<'py, PyList>> {
        let len = self.grid.len();
        let indices: Vec<usize> = match indices {
            None => (0..len).collect(),
            Some(given) => given
                .iter()
                .map(|i| {
                    i.get("indices", 0, len.saturating_sub(1) as u64)
                        .map(|i| i as usize)
                        .map_err(|_| {
                            call::Error::new_err(format!(
                                "indices: `{}` is not allowed; give an index from 0 to {} (the grid's {len} points)",
                                i.text(),
                                len.saturating_sub(1)
                            ))
                        })
                })
                .collect::<PyResult<_>>()?,
        };
        let stop = AtomicBool::new(false);
        let evaluator = BeamEvaluator::new(&self.config);
        let cells = watched(
            py,
            &stop,
            || {
                Ok(sweep::evaluate(
                    &self.config,
                    &evaluator,
                    &self.grid,
                    &indices,
                    Some(&stop),
                    &|_| {},
                ))
            },
            |_| Ok(()),
        )?;
        let rows = cells
            .iter()
            .map(|c| self.row(py, c))
            .collect::<PyResult<Vec<_>>>()?;
        PyList::new(py, rows)
    }

    /// The sweep's CSV (`facetlab sweep`'s `sweep.csv`, byte for byte) of `rows` covering
    /// the grid once each, in any order (merged by `index`).
    ///
    /// >>> g = facetlab.Grid({"cut": {"family": "round-brilliant"}, "free": {"table": [0.5, 0.6]},
    /// ...                    "score": {"ri": 1.54, "polarization": False}}, ["table:0.55:0.57:0.01"])
    /// >>> g.csv(g.rows([2]) + g.rows([0, 1])) == g.csv(g.rows())
    /// True
    fn csv(&self, rows: Vec<Bound<'_, PyDict>>) -> PyResult<String> {
        let mut cells = rows
            .iter()
            .map(|r| self.cell(r))
            .collect::<PyResult<Vec<_>>>()?;
        cells.sort_by_key(|c| c.index);
        let len = self.grid.len();
        let covered = cells.len() == len && cells.iter().enumerate().all(|(i, c)| c.index == i);
        if !covered {
            return Err(call::Error::new_err(format!(
                "rows: give each of the grid's {len} points once (got {} rows)",
                cells.len()
            )));
        }
        Ok(sweep::to_csv(&self.grid, &cells))
    }

    fn __repr__(&self) -> String {
        format!(
            "<Grid {} points over {}>",
            self.grid.len(),
            self.keys().join(", ")
        )
    }
}

/// Add `optimize` and `Grid` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyGrid>()?;
    m.add_function(wrap_pyfunction!(optimize, m)?)?;
    Ok(())
}
