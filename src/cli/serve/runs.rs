//! Optimization runs from the page: one at a time, started from a bundled `optim/` config (or
//! a config's text), watched by polling, stoppable, with its one-page report at the end.
//!
//! `GET /api/configs` lists the bundled configs; `POST /api/optimize` with `{"config": NAME}`
//! or `{"config_text": TOML}` starts a run (409 while one is going); `GET /api/optimize` gives
//! its status (`state`: `running`, `done`, `stopped` or `failed`; `evaluations`, `budget`,
//! `best_cost`, `elapsed_s`, `curve`: `[[evaluations, best cost], …]`, `best`: the winner's
//! free parameters and scores, `error`, `report`); `POST /api/optimize/stop` stops it (the
//! run still writes what it found); `GET /api/optimize/report` is its `report.html`.
//! The run folder goes to a temporary folder that is removed once the report is read in.

use super::error::{ApiError, ApiResult};
use super::request::Field;
use super::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::State;
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use facetlab::optimize::{self as opt, Config, Hooks, Progress, RunOptions, Status};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

/// The bundled configs, embedded: a client names one, never a path.
pub const CONFIGS: [(&str, &str); 5] = [
    (
        "round-brilliance",
        include_str!("../../../optim/round-brilliance.toml"),
    ),
    (
        "round-balanced",
        include_str!("../../../optim/round-balanced.toml"),
    ),
    ("pso-round", include_str!("../../../optim/pso-round.toml")),
    ("princess", include_str!("../../../optim/princess.toml")),
    (
        "pareto-round",
        include_str!("../../../optim/pareto-round.toml"),
    ),
];

/// What the status endpoints say before the first run.
const NO_RUN: &str = "no run yet; POST /api/optimize";

/// Largest config text accepted.
const MAX_CONFIG: usize = 64 * 1024;

/// Points kept of the convergence curve (thinned by half when full).
const MAX_CURVE: usize = 2000;

/// What the page polls.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RunStatus {
    id: u64,
    name: String,
    state: &'static str,
    evaluations: u64,
    budget: u64,
    best_cost: Option<f64>,
    elapsed_s: f64,
    curve: Vec<(u64, f64)>,
    best: Option<Value>,
    error: Option<String>,
    report: bool,
}

/// A run in progress or finished.
pub struct Run {
    stop: Arc<AtomicBool>,
    status: Mutex<RunStatus>,
    report: Mutex<Option<String>>,
}

/// The optimization runs of one server: the current (or last) one.
pub type Runs = Slot<Run>;

/// One background run of a kind at a time (an optimization, a plan): the current (or last)
/// one, numbered from 1.
pub struct Slot<T> {
    current: Mutex<Option<Arc<T>>>,
    next: AtomicU64,
}

impl<T> Default for Slot<T> {
    fn default() -> Self {
        Slot {
            current: Mutex::new(None),
            next: AtomicU64::new(0),
        }
    }
}

/// A background run that says whether it is still going, and can be asked to stop.
pub trait Going {
    fn going(&self) -> bool;
    fn stop(&self);
}

impl<T: Going> Slot<T> {
    /// Number and keep the run `make(id)`, unless one is going: then a 409 naming `field`
    /// that says `busy`.
    pub fn start(
        &self,
        field: &str,
        busy: &str,
        make: impl FnOnce(u64) -> T,
    ) -> ApiResult<(u64, Arc<T>)> {
        let mut cur = self.current.lock().map_err(|_| lock_err())?;
        if cur.as_ref().is_some_and(|r| r.going()) {
            return Err(ApiError::new(StatusCode::CONFLICT, field, busy));
        }
        let id = self.next.fetch_add(1, Ordering::SeqCst) + 1;
        let run = Arc::new(make(id));
        *cur = Some(run.clone());
        Ok((id, run))
    }

    /// The current (or last) run, or a 404 about `run` that says `none`.
    pub fn current(&self, none: &str) -> ApiResult<Arc<T>> {
        self.current
            .lock()
            .map_err(|_| lock_err())?
            .clone()
            .ok_or_else(|| ApiError::new(StatusCode::NOT_FOUND, "run", none))
    }

    /// Ask the current run to stop (`POST …/stop`); a 404 saying `none` when there is none.
    pub fn stop(&self, none: &str) -> ApiResult<Response> {
        self.current(none)?.stop();
        Ok(axum::Json(json!({ "stopping": true })).into_response())
    }
}

impl Going for Run {
    fn going(&self) -> bool {
        self.status.lock().is_ok_and(|s| s.state == "running")
    }
    fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
    }
}

struct Watch(Arc<Run>);

impl Progress for Watch {
    fn update(&self, s: &Status) {
        let Ok(mut st) = self.0.status.lock() else {
            return;
        };
        st.evaluations = s.evaluations;
        st.budget = s.budget;
        st.elapsed_s = s.elapsed;
        if s.best_cost.is_finite() {
            st.best_cost = Some(s.best_cost);
            if st.curve.last().map(|p| p.0) != Some(s.evaluations) {
                st.curve.push((s.evaluations, s.best_cost));
                if st.curve.len() > MAX_CURVE {
                    let thinned: Vec<(u64, f64)> = st.curve.iter().copied().step_by(2).collect();
                    st.curve = thinned;
                }
            }
        }
    }
}

/// The error of a poisoned lock.
pub fn lock_err() -> ApiError {
    ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        "server",
        "a lock was poisoned",
    )
}

/// `GET /api/configs`.
pub async fn configs() -> Response {
    let list: Vec<Value> = CONFIGS
        .iter()
        .map(|(name, text)| {
            let c = Config::from_str(text, &format!("{name}.toml")).ok();
            json!({
                "name": name,
                "description": c.as_ref().and_then(|c| c.description.clone()),
                "family": c.as_ref().map(|c| c.space.name()),
                "budget": c.as_ref().map(|c| c.budget.max_evaluations),
                "pareto": c.as_ref().map(|c| c.pareto.is_some()),
            })
        })
        .collect();
    axum::Json(json!({ "configs": list })).into_response()
}

/// A body of `POST /api/optimize`: a bundled config's name or a config file's text.
#[derive(Default, Deserialize)]
#[serde(default)]
struct StartBody {
    config: Field<String>,
    config_text: Field<String>,
    design: Field<String>,
    design_name: Field<String>,
}

/// The fields of `POST /api/optimize`.
const START_FIELDS: [&str; 4] = ["config", "config_text", "design", "design_name"];

/// `POST /api/optimize`: start a run.
pub async fn start(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let body = body.map_err(|e| ApiError::bad("body", e.body_text()))?;
    let v: Value = serde_json::from_slice(&body)
        .map_err(|e| ApiError::bad("body", format!("not JSON: {e}")))?;
    let Value::Object(m) = v else {
        return Err(ApiError::bad("body", "must be a JSON object"));
    };
    for k in m.keys() {
        if !START_FIELDS.contains(&k.as_str()) {
            return Err(ApiError::bad(
                super::request::short(k),
                "unknown field; give config or config_text (and design with design_name)",
            ));
        }
    }
    let b = StartBody::deserialize(Value::Object(m))
        .map_err(|e| ApiError::bad("body", e.to_string()))?;
    let (name, text) = match (&b.config, &b.config_text) {
        (Field::Given(n), Field::Absent) => {
            let Some((name, text)) = CONFIGS.iter().find(|(c, _)| c == n) else {
                return Err(ApiError::bad(
                    "config",
                    format!(
                        "no bundled config {:?}; allowed: {}",
                        n.chars().take(40).collect::<String>(),
                        CONFIGS.map(|c| c.0).join(", ")
                    ),
                ));
            };
            (name.to_string(), text.to_string())
        }
        (Field::Absent, Field::Given(t)) if t.len() <= MAX_CONFIG => {
            ("config".to_string(), t.clone())
        }
        (Field::Absent, Field::Given(_)) => {
            return Err(ApiError::bad("config_text", "longer than 64 KB"))
        }
        _ => return Err(ApiError::bad(
            "config",
            "give one of config (a bundled config's name) or config_text (a config file's text)",
        )),
    };
    let design = uploaded_design(&b)?;
    let designs = |file: &str| -> Option<facetlab::error::Result<facetlab::cut::Cut>> {
        let (name, format, text) = design.as_ref()?;
        (file == name)
            .then(|| facetlab::io::parse_cut(format, text.as_bytes(), stem_of(name), "design"))
    };
    // No value a client sends becomes a file path: `[cut] file` names a preset or the design
    // sent with the config, nothing else (and the error repeats nothing of what it named).
    let config =
        Config::from_str_without_files(&text, &format!("{name}.toml"), &designs).map_err(|e| {
            ApiError::bad(
                if !matches!(b.config, Field::Absent) {
                    "config"
                } else {
                    "config_text"
                },
                e.to_string(),
            )
            .unprocessable()
        })?;
    let (id, run) = st.runs.start(
        "config",
        "a run is going; stop it first (POST /api/optimize/stop)",
        |id| Run {
            stop: Arc::new(AtomicBool::new(false)),
            status: Mutex::new(RunStatus {
                id,
                name: config.name.clone(),
                state: "running",
                budget: config.budget.max_evaluations,
                ..Default::default()
            }),
            report: Mutex::new(None),
        },
    )?;
    std::thread::spawn(move || execute(run, config, id));
    Ok(axum::Json(json!({ "id": id })).into_response())
}

/// The design sent with a config (`design`: a file's text, `design_name`: its name, whose
/// extension is its format), as (name, format, text).
fn uploaded_design(b: &StartBody) -> ApiResult<Option<(String, &'static str, String)>> {
    let text = b
        .design
        .given()
        .map_err(|_| ApiError::bad("design", "give the text of a .asc, .toml or .obj file"))?;
    let name = b.design_name.given().map_err(|_| {
        ApiError::bad(
            "design_name",
            "give the design's file name, e.g. \"mine.asc\"",
        )
    })?;
    let (text, name) = match (text, name) {
        (None, None) => return Ok(None),
        (Some(t), Some(n)) => (t, n),
        (Some(_), None) => {
            return Err(ApiError::bad(
                "design_name",
                "missing; give the design's file name, e.g. \"mine.asc\", as the config's [cut] file names it",
            ))
        }
        (None, Some(_)) => return Err(ApiError::bad("design", "missing; give the design file's text")),
    };
    if text.len() > MAX_CONFIG * 16 {
        return Err(ApiError::bad("design", "longer than 1 MB"));
    }
    let ext = name
        .rsplit_once('.')
        .map(|(_, e)| e.to_ascii_lowercase())
        .unwrap_or_default();
    let format = match ext.as_str() {
        "asc" => "asc",
        "toml" => "toml",
        "obj" => "obj",
        _ => {
            return Err(ApiError::bad(
                "design_name",
                "give a name ending in .asc, .toml or .obj (the design's format)",
            ))
        }
    };
    Ok(Some((name.clone(), format, text.clone())))
}

/// A design name's stem (its cut's name).
fn stem_of(name: &str) -> &str {
    name.rsplit_once('.').map_or(name, |(s, _)| s)
}

/// Run the search and the verification into a temporary folder; keep the report.
fn execute(run: Arc<Run>, config: Config, id: u64) {
    let dir = std::env::temp_dir().join(format!("facetlab-serve-{}-run-{id}", std::process::id()));
    let watch = Watch(run.clone());
    let (evaluator, verifier) = opt::real_scorers(&config);
    let result = if config.pareto.is_some() {
        opt::run_pareto(
            &config,
            evaluator.as_ref(),
            verifier.as_deref(),
            &dir,
            None,
            &Hooks {
                stop: Some(&run.stop),
                progress: Some(&watch),
            },
        )
        .map(|front| {
            let best = front
                .front
                .last()
                .map(|p| json!({ "free": p.free, "scores": p.scores }));
            (best, None)
        })
    } else {
        let opts = RunOptions {
            out: Some(dir.clone()),
            html_report: Some(facetlab::report::run_page),
            hooks: Hooks {
                stop: Some(&run.stop),
                progress: Some(&watch),
            },
            ..RunOptions::default()
        };
        opt::run(&config, evaluator.as_ref(), verifier.as_deref(), &opts).map(|s| {
            let b = s.outcome.best();
            let best = json!({ "free": b.free, "scores": b.scores, "label": b.label });
            let page = std::fs::read_to_string(dir.join("report.html")).ok();
            (Some(best), page)
        })
    };
    let _ = std::fs::remove_dir_all(&dir);
    let stopped = run.stop.load(Ordering::SeqCst);
    let mut report_out = None;
    if let Ok(mut st) = run.status.lock() {
        match result {
            Ok((best, page)) => {
                st.state = if stopped { "stopped" } else { "done" };
                st.best = best;
                st.report = page.is_some();
                report_out = page;
            }
            Err(e) => {
                st.state = "failed";
                st.error = Some(e.to_string());
            }
        }
    }
    if let Ok(mut r) = run.report.lock() {
        *r = report_out;
    }
}

fn current(st: &AppState) -> ApiResult<Arc<Run>> {
    st.runs.current(NO_RUN)
}

/// `GET /api/optimize`: the current run's status.
pub async fn status(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    let run = current(&st)?;
    let s = run.status.lock().map_err(|_| lock_err())?.clone();
    Ok(axum::Json(s).into_response())
}

/// `POST /api/optimize/stop`.
pub async fn stop(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    st.runs.stop(NO_RUN)
}

/// `GET /api/optimize/report`: the finished run's `report.html`.
pub async fn report(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    let run = current(&st)?;
    let page = run.report.lock().map_err(|_| lock_err())?.clone();
    match page {
        Some(p) => Ok(([(header::CONTENT_TYPE, "text/html; charset=utf-8")], p).into_response()),
        None => Err(ApiError::new(
            StatusCode::NOT_FOUND,
            "run",
            "no report (yet): the run is going, failed, or traced a trade-off",
        )),
    }
}
