//! Planning from a rough on the page: an uploaded `.obj`/`.stl` mesh (or a bundled crystal form
//! with a size) planned in the background as `facetlab plan` plans it, one plan run at a time,
//! watched by polling, stoppable between families, with its plans, pictures and report.
//!
//! `POST /api/plan` starts a run (409 while one is going); the rough is read and checked in
//! memory first, so a bad one (not a mesh, open, flat, too large) is a 422 naming `rough` and
//! nothing is written. `GET /api/plan` gives its status (`state`: `running`, `done`, `stopped`
//! or `failed`; `family`, `starts_done`, `starts`, `elapsed_s`, and once done `rough`, `material`, `plans`
//! as in `summary.json`, each with `views`: its three-view picture's address, `overview`,
//! `report`); `POST /api/plan/stop` stops it after the family being planned (the families
//! planned are kept); `GET /api/plan/report` is its `report.html`, `GET /api/plan/picture/NAME`
//! one of its pictures. With `stones` above 1 (and `kerf_mm`, `allowance_mm`, `margin_mm`,
//! `inclusions`: OBJ texts in the rough's coordinates; `cutter`: `saw` or `laser`) the rough is sawn into a layout of
//! several stones as `facetlab plan --stones N` plans it ([`facetlab::plan::plan_layout`]):
//! `starts` counts its saw cuts judged, and the status adds `stones` (each stone's family,
//! carats, value as `objective`, `centre_mm`, piece), `saw_plan` and `layout` as in
//! `summary.json`, with the overview picture of the rough, the saw planes and the stones.
//! The run folder ([`facetlab::plan::write_folder`]) goes to a
//! temporary folder that is removed once its pictures and report are read in.

use super::error::{ApiError, ApiResult};
use super::request::{decode_base64, json_object, short, Field};
use super::runs::{lock_err, Going, Slot};
use super::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{Path, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use facetlab::error::{Error, Setting};
use facetlab::optics::Material;
use facetlab::plan::config::check_families;
use facetlab::plan::config::{MAX_GAP_MM, MAX_STONES};
use facetlab::plan::mesh::read_triangles;
use facetlab::plan::{plan_families, write_folder, Run as Folder};
use facetlab::plan::{plan_layout, Cutter, Inclusion, PlanConfig, Rough, CRYSTALS};
use facetlab::report::PlanDrawings;
use serde::{Deserialize, Serialize};
use serde_json::{json, Number, Value};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Largest rough mesh accepted, in triangles (a scanned rough of the issue has 2,000).
pub const MAX_ROUGH_TRIANGLES: usize = 20_000;
/// Distinct plans kept per family: allowed range and default.
pub const TOP: (u64, u64, u64) = (1, 10, 2);
/// Search starts per family (each a local search of pose and proportions): range and default.
pub const STARTS: (u64, u64, u64) = (1, 48, 8);
/// Families planned when the request names none.
pub const DEFAULT_FAMILY: &str = "round-brilliant";

/// What the page polls.
#[derive(Clone, Debug, Default, Serialize)]
pub struct PlanStatus {
    id: u64,
    name: String,
    state: &'static str,
    family: Option<String>,
    families: Vec<String>,
    starts_done: u64,
    starts: u64,
    elapsed_s: f64,
    rough: Option<Value>,
    material: Option<String>,
    plans: Vec<Value>,
    overview: Option<String>,
    error: Option<String>,
    report: bool,
    warnings: Vec<String>,
    /// A layout of several stones (`stones` above 1, or inclusions): `summary.json`'s
    /// `stones`, `saw_plan` and `layout`.
    stones: Vec<Value>,
    saw_plan: Vec<Value>,
    layout: Option<Value>,
}

/// A plan run in progress or finished: its status and, once done, its files in memory.
pub struct PlanRun {
    stop: AtomicBool,
    started: Instant,
    status: Mutex<PlanStatus>,
    files: Mutex<BTreeMap<String, Vec<u8>>>,
}

/// The plan runs of one server: the current (or last) one.
pub type PlanRuns = Slot<PlanRun>;

impl Going for PlanRun {
    fn going(&self) -> bool {
        self.status.lock().is_ok_and(|s| s.state == "running")
    }
    fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
    }
}

/// What the status endpoints say before the first plan.
const NO_PLAN: &str = "no plan yet; POST /api/plan";

/// A body of `POST /api/plan` as sent.
#[derive(Default, Deserialize)]
#[serde(default)]
struct Body {
    rough: Field<String>,
    format: Field<String>,
    encoding: Field<String>,
    name: Field<String>,
    crystal: Field<String>,
    size_mm: Field<Number>,
    families: Field<Vec<String>>,
    top: Field<Number>,
    starts: Field<Number>,
    material: Field<String>,
    stones: Field<Number>,
    kerf_mm: Field<Number>,
    allowance_mm: Field<Number>,
    margin_mm: Field<Number>,
    inclusions: Field<Vec<String>>,
    cutter: Field<String>,
}

const KEYS: [&str; 16] = [
    "rough",
    "format",
    "encoding",
    "name",
    "crystal",
    "size_mm",
    "families",
    "top",
    "starts",
    "material",
    "stones",
    "kerf_mm",
    "allowance_mm",
    "margin_mm",
    "inclusions",
    "cutter",
];

/// Stones per layout: allowed range and default (1: the single plans of each family).
pub const STONES: (u64, u64, u64) = (1, MAX_STONES as u64, 1);
/// Inclusions a request may send.
pub const MAX_INCLUSIONS: usize = 8;

fn unprocessable(field: &str, message: impl Into<String>) -> ApiError {
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, field, message)
}

/// A whole number in `range` (lo, hi, default) from `f`, or the error naming `field`.
fn whole(f: &Field<Number>, field: &str, range: (u64, u64, u64)) -> ApiResult<u64> {
    let bad = |sent: String| {
        ApiError::bad(
            field,
            format!(
                "{} is not allowed; give a whole number from {} to {}",
                short(&sent),
                range.0,
                range.1
            ),
        )
    };
    match f.given() {
        Ok(None) => Ok(range.2),
        Ok(Some(n)) => match n.as_u64() {
            Some(k) if (range.0..=range.1).contains(&k) => Ok(k),
            _ => Err(bad(n.to_string())),
        },
        Err(v) => Err(bad(v.to_string())),
    }
}

/// A distance in mm in `[0, MAX_GAP_MM]` from `f` (`default` when not sent), or the error
/// naming `field`.
fn gap(f: &Field<Number>, field: &str, default: f64) -> ApiResult<f64> {
    match f.given() {
        Ok(None) => Ok(default),
        Ok(Some(n)) => match n.as_f64() {
            Some(x) if (0.0..=MAX_GAP_MM).contains(&x) => Ok(x),
            _ => Err(unprocessable(
                field,
                format!(
                    "{} is not allowed; give a distance in [0, {MAX_GAP_MM}] mm",
                    short(&n.to_string())
                ),
            )),
        },
        Err(_) => Err(ApiError::bad(field, "must be a number of millimetres")),
    }
}

/// The inclusions a body sends (OBJ texts in mm in the rough's coordinates), grown by
/// `margin`; errors name `inclusions`.
fn inclusions(b: &Body, margin: f64) -> ApiResult<Vec<Inclusion>> {
    let texts = match b.inclusions.given() {
        Ok(None) => return Ok(Vec::new()),
        Ok(Some(t)) => t,
        Err(_) => {
            return Err(ApiError::bad(
                "inclusions",
                "must be a list of .obj mesh texts (mm, the rough's coordinates)",
            ))
        }
    };
    if texts.len() > MAX_INCLUSIONS {
        return Err(unprocessable(
            "inclusions",
            format!("{} sent; allowed at most {MAX_INCLUSIONS}", texts.len()),
        ));
    }
    texts
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let name = format!("inclusion-{}", k + 1);
            Inclusion::from_bytes(
                t.as_bytes(),
                "obj",
                &name,
                &format!("inclusions[{k}]"),
                margin,
            )
            .map_err(|e| unprocessable("inclusions", e.to_string()))
        })
        .collect()
}

/// The rough a body names, read and checked in memory: a mesh's errors name `rough`, a size's
/// `size_mm`.
fn rough(b: &Body) -> ApiResult<Rough> {
    let size = match b.size_mm.given() {
        Ok(None) => None,
        Ok(Some(n)) => Some(
            facetlab::plan::rough_size_mm("size_mm", n.as_f64().unwrap_or(f64::NAN)).map_err(
                |e| match e {
                    Error::Invalid { message, .. } => unprocessable("size_mm", message),
                    other => unprocessable("size_mm", other.to_string()),
                },
            )?,
        ),
        Err(_) => return Err(ApiError::bad("size_mm", "must be a number of millimetres")),
    };
    let lib = |e: Error| match e {
        // A setting the request sends by its field (the rough's size: `size_mm`), else the
        // rough itself.
        Error::Invalid { field, message } => {
            let f = Setting::from_name(&field).and_then(super::error::field);
            unprocessable(f.unwrap_or("rough"), message)
        }
        other => unprocessable("rough", other.to_string()),
    };
    match (b.crystal.given(), b.rough.given()) {
        (Ok(Some(_)), Ok(Some(_))) => Err(ApiError::bad(
            "crystal",
            "give either rough (a mesh) or crystal (a bundled form), not both",
        )),
        (Ok(Some(form)), _) => {
            if !CRYSTALS.contains(&form.as_str()) {
                return Err(unprocessable(
                    "crystal",
                    format!(
                        "unknown crystal form {:?}; allowed: {}",
                        short(form),
                        CRYSTALS.join(", ")
                    ),
                ));
            }
            let Some(l) = size else {
                return Err(unprocessable(
                    "size_mm",
                    format!("the crystal form {form} needs size_mm (its largest extent in mm)"),
                ));
            };
            Rough::crystal(form, l).map_err(lib)
        }
        (Err(_), _) => Err(ApiError::bad("crystal", "must be a string")),
        (_, Err(_)) => Err(ApiError::bad("rough", "must be a string: a mesh file's text")),
        (Ok(None), Ok(None)) => Err(ApiError::bad(
            "rough",
            "missing; give the text of an .obj or .stl mesh in mm with \"format\", or \"crystal\" with \"size_mm\"",
        )),
        (Ok(None), Ok(Some(text))) => {
            let format = match b.format.given() {
                Ok(Some(f)) if matches!(f.trim().to_ascii_lowercase().as_str(), "obj" | ".obj") => "obj",
                Ok(Some(f)) if matches!(f.trim().to_ascii_lowercase().as_str(), "stl" | ".stl") => "stl",
                Ok(None) => return Err(ApiError::bad("format", "missing; give obj or stl")),
                _ => return Err(ApiError::bad("format", "allowed: obj, stl")),
            };
            let bytes = match b.encoding.given() {
                Ok(None) => text.as_bytes().to_vec(),
                Ok(Some(e)) if e == "text" => text.as_bytes().to_vec(),
                Ok(Some(e)) if e == "base64" => decode_base64(text)
                    .ok_or_else(|| ApiError::bad("rough", "is not valid base64"))?,
                _ => return Err(ApiError::bad("encoding", "allowed: \"text\" or \"base64\"")),
            };
            let name = match b.name.given() {
                Ok(n) => n.map(|s| clean_stem(s)).filter(|s| !s.is_empty()),
                Err(_) => return Err(ApiError::bad("name", "must be a string")),
            }
            .unwrap_or_else(|| "rough".to_string());
            let source = format!("{name}.{format}");
            let mesh = read_triangles(&bytes, format, &source).map_err(lib)?;
            if mesh.triangles.len() > MAX_ROUGH_TRIANGLES {
                return Err(unprocessable(
                    "rough",
                    format!(
                        "{source} has {} triangles; allowed at most {MAX_ROUGH_TRIANGLES} (simplify the scan)",
                        mesh.triangles.len()
                    ),
                ));
            }
            Rough::from_trimesh(&name, &source, mesh, size).map_err(lib)
        }
    }
}

/// A display name from a client: a file stem, at most 64 letters, digits, `-` and `_`.
fn clean_stem(s: &str) -> String {
    let stem = s.rsplit(['/', '\\']).next().unwrap_or(s);
    let stem = stem.rsplit_once('.').map_or(stem, |(a, _)| a);
    stem.chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '-'
            }
        })
        .take(64)
        .collect::<String>()
        .trim_matches('-')
        .to_string()
}

/// `POST /api/plan`: check the rough and the choices, then start the run.
pub async fn start(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let m = json_object(
        body,
        "expected a JSON object like {\"crystal\": \"octahedron\", \"size_mm\": 6}",
    )?;
    for k in m.keys() {
        if !KEYS.contains(&k.as_str()) {
            return Err(ApiError::bad(
                short(k),
                format!("unknown field; allowed: {}", KEYS.join(", ")),
            ));
        }
    }
    let b =
        Body::deserialize(Value::Object(m)).map_err(|e| ApiError::bad("body", e.to_string()))?;
    let families = match b.families.given() {
        Ok(None) => vec![DEFAULT_FAMILY.to_string()],
        // Each a known family, named once (as `facetlab plan` and Python check them).
        Ok(Some(f)) => check_families(f).map_err(|m| unprocessable("families", m))?,
        Err(_) => {
            return Err(ApiError::bad(
                "families",
                "must be a list of family names, e.g. [\"round-brilliant\", \"oval\"]",
            ))
        }
    };
    let top = whole(&b.top, "top", TOP)? as usize;
    let starts = whole(&b.starts, "starts", STARTS)? as usize;
    let material = match b.material.given() {
        Ok(n) => Material::by_name(n.map_or("diamond", String::as_str)).map_err(|e| match e {
            Error::Invalid { message, .. } => unprocessable("material", message),
            other => unprocessable("material", other.to_string()),
        })?,
        Err(_) => {
            return Err(ApiError::bad(
                "material",
                "must be a string such as \"diamond\"",
            ))
        }
    };
    let defaults = PlanConfig::default();
    let stones = whole(&b.stones, "stones", STONES)? as usize;
    let kerf_mm = gap(&b.kerf_mm, "kerf_mm", defaults.kerf_mm)?;
    let allowance_mm = gap(&b.allowance_mm, "allowance_mm", defaults.allowance_mm)?;
    let margin_mm = gap(&b.margin_mm, "margin_mm", defaults.margin_mm)?;
    let cutter = match b.cutter.given() {
        Ok(None) => defaults.cutter,
        Ok(Some(c)) => Cutter::named("cutter", c).map_err(|e| match e {
            Error::Invalid { message, .. } => unprocessable("cutter", message),
            other => unprocessable("cutter", other.to_string()),
        })?,
        Err(_) => return Err(ApiError::bad("cutter", "must be \"saw\" or \"laser\"")),
    };
    // The meshes are read on a blocking thread (a large upload takes a moment).
    let (rough, inclusions) =
        super::jobs::heavy(&st, move || Ok((rough(&b)?, inclusions(&b, margin_mm)?))).await?;
    if rough.ball.is_some() && (stones > 1 || !inclusions.is_empty()) {
        return Err(unprocessable(
            "stones",
            "the sphere is planned as an exact ball, one stone; several stones or inclusions need a polyhedral rough",
        ));
    }
    let config = PlanConfig {
        name: rough.name.clone(),
        families,
        top,
        starts,
        material: material.name.clone(),
        stones,
        kerf_mm,
        allowance_mm,
        margin_mm,
        cutter,
        ..defaults
    };
    let layout = config.stones > 1 || !inclusions.is_empty();
    let (id, run) = st.plans.start(
        "rough",
        "a plan is running; stop it first (POST /api/plan/stop)",
        |id| PlanRun {
            stop: AtomicBool::new(false),
            started: Instant::now(),
            status: Mutex::new(PlanStatus {
                id,
                name: rough.name.clone(),
                state: "running",
                families: config.families.clone(),
                starts: if layout {
                    facetlab::plan::layout::candidates(&config)
                } else {
                    (config.families.len() * config.starts) as u64
                },
                ..Default::default()
            }),
            files: Mutex::new(BTreeMap::new()),
        },
    )?;
    std::thread::spawn(move || execute(&run, &rough, &config, &material, &inclusions, id));
    Ok(axum::Json(json!({ "id": id })).into_response())
}

/// Plan, write the run folder into a temporary folder, keep its summary, pictures and report.
fn execute(
    run: &PlanRun,
    rough: &Rough,
    config: &PlanConfig,
    material: &Material,
    inclusions: &[Inclusion],
    id: u64,
) {
    let tick = || {
        if let Ok(mut s) = run.status.lock() {
            s.starts_done += 1;
            s.elapsed_s = run.started.elapsed().as_secs_f64();
        }
    };
    let family = |f: &str| {
        if let Ok(mut s) = run.status.lock() {
            s.family = Some(f.to_string());
        }
        !run.stop.load(Ordering::SeqCst)
    };
    let dir = std::env::temp_dir().join(format!("facetlab-serve-{}-plan-{id}", std::process::id()));
    let result = if config.stones > 1 || !inclusions.is_empty() {
        plan_layout(rough, config, material, inclusions, &tick, Some(&run.stop)).and_then(|l| {
            let folder = Folder {
                out: &dir,
                input: &rough.name,
                config,
                material,
                rough,
                all: &[],
                started: run.started,
                warnings: &[],
                layout: Some(&l),
                inclusions,
            };
            write_folder(&folder, &PlanDrawings)?;
            read_folder(&dir).map(Some)
        })
    } else {
        plan_families(rough, config, material, &family, &tick, None).and_then(|all| {
            if all.is_empty() {
                return Ok(None);
            }
            let warnings = facetlab::plan::plan_warnings(config, &all);
            let folder = Folder {
                out: &dir,
                input: &rough.name,
                config,
                material,
                rough,
                all: &all,
                started: run.started,
                warnings: &warnings,
                layout: None,
                inclusions: &[],
            };
            write_folder(&folder, &PlanDrawings)?;
            read_folder(&dir).map(Some)
        })
    };
    let _ = std::fs::remove_dir_all(&dir);
    let stopped = run.stop.load(Ordering::SeqCst);
    let Ok(mut st) = run.status.lock() else {
        return;
    };
    st.elapsed_s = run.started.elapsed().as_secs_f64();
    st.family = None;
    match result {
        Ok(found) => {
            st.state = if stopped { "stopped" } else { "done" };
            if let Some((summary, files)) = found {
                st.rough = summary.get("rough").cloned();
                st.material = summary["material"].as_str().map(str::to_string);
                st.warnings = summary["warnings"]
                    .as_array()
                    .map(|w| {
                        w.iter()
                            .filter_map(|x| x.as_str().map(str::to_string))
                            .collect()
                    })
                    .unwrap_or_default();
                st.plans = summary["plans"]
                    .as_array()
                    .cloned()
                    .unwrap_or_default()
                    .into_iter()
                    .map(|mut p| {
                        let views = format!("{}-views.png", p["stem"].as_str().unwrap_or(""));
                        if files.contains_key(&views) {
                            p["views"] = Value::String(format!("/api/plan/picture/{views}"));
                        }
                        p
                    })
                    .collect();
                // A layout's stones (family, carats, value, position, piece) and saw plan.
                let list = |k: &str| summary[k].as_array().cloned().unwrap_or_default();
                st.stones = list("stones");
                st.saw_plan = list("saw_plan");
                st.layout = summary.get("layout").cloned();
                st.overview = files
                    .contains_key("overview.png")
                    .then(|| "/api/plan/picture/overview.png".to_string());
                st.report = files.contains_key("report.html");
                if let Ok(mut f) = run.files.lock() {
                    *f = files;
                }
            }
        }
        // A layout stopped part-way has nothing to show.
        Err(_) if stopped => st.state = "stopped",
        Err(e) => {
            st.state = "failed";
            st.error = Some(e.to_string());
        }
    }
}

/// The run folder's `summary.json`, and its PNG pictures and `report.html` by file name.
fn read_folder(
    dir: &std::path::Path,
) -> facetlab::error::Result<(Value, BTreeMap<String, Vec<u8>>)> {
    let read = |name: &str| {
        let p = dir.join(name);
        std::fs::read(&p).map_err(|e| Error::io(p.display().to_string(), e))
    };
    let summary: Value = serde_json::from_slice(&read("summary.json")?)
        .map_err(|e| Error::invalid("summary.json", e.to_string()))?;
    let mut files = BTreeMap::new();
    let entries = std::fs::read_dir(dir).map_err(|e| Error::io(dir.display().to_string(), e))?;
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().to_string();
        if name.ends_with(".png") || name == "report.html" {
            files.insert(name.clone(), read(&name)?);
        }
    }
    Ok((summary, files))
}

fn current(st: &AppState) -> ApiResult<Arc<PlanRun>> {
    st.plans.current(NO_PLAN)
}

/// `GET /api/plan`: the current plan run's status.
pub async fn status(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    let run = current(&st)?;
    let mut s = run.status.lock().map_err(|_| lock_err())?.clone();
    if s.state == "running" {
        s.elapsed_s = run.started.elapsed().as_secs_f64();
    }
    Ok(axum::Json(s).into_response())
}

/// `POST /api/plan/stop`: stop after the family being planned.
pub async fn stop(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    st.plans.stop(NO_PLAN)
}

/// `GET /api/plan/report`: the finished run's `report.html`.
pub async fn report(State(st): State<Arc<AppState>>) -> ApiResult<Response> {
    file(&st, "report.html", "text/html; charset=utf-8")
}

/// `GET /api/plan/picture/NAME`: one of the finished run's PNG pictures.
pub async fn picture(
    State(st): State<Arc<AppState>>,
    Path(name): Path<String>,
) -> ApiResult<Response> {
    if !name.ends_with(".png") {
        return Err(ApiError::new(
            StatusCode::NOT_FOUND,
            "path",
            "no such picture",
        ));
    }
    file(&st, &name, "image/png")
}

fn file(st: &AppState, name: &str, kind: &'static str) -> ApiResult<Response> {
    let run = current(st)?;
    let bytes = run.files.lock().map_err(|_| lock_err())?.get(name).cloned();
    match bytes {
        Some(b) => Ok((
            [
                (header::CONTENT_TYPE, kind),
                (header::CACHE_CONTROL, "no-store"),
            ],
            b,
        )
            .into_response()),
        None => Err(ApiError::new(
            StatusCode::NOT_FOUND,
            "path",
            format!("{}: not (yet) in the plan run's files", short(name)),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_stems() {
        assert_eq!(clean_stem("../../etc/passwd"), "passwd");
        assert_eq!(clean_stem("my rough.obj"), "my-rough");
        assert_eq!(clean_stem("<x>.stl"), "x");
    }
}
