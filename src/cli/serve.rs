//! `facetlab serve`: the cutter's workbench in the browser. A local web server with one page
//! (embedded, no build step, no network) over a small JSON API; the page uses only the API.
//!
//! ```text
//! facetlab serve                      # http://127.0.0.1:8737/
//! facetlab serve --port 0 --open      # any free port, open the default browser
//! ```
//!
//! API (see the README's "serve" section):
//!
//! - `GET /api/presets`: presets, families with their parameters and ranges, lights, limits.
//! - `POST /api/cut`: the cut's `info --json` record plus `svg` (the diagram).
//! - `POST /api/score`: the keys of `score --json` (`"quick": true` uses
//!   [`ScoreConfig::fast`]).
//! - `POST /api/render`: `image/png` of the face-up (or tilted) picture.
//! - `POST /api/export`: the cut as `.asc`, `.obj`, `.stl` or `.toml` bytes.
//!
//! Every body is a JSON object: `cut` (a preset name, or the text of a file with `format`),
//! `set` (parameter changes), and per endpoint `light`, `size`, `tilt`, `exposure`, `quick`, `to`. Errors are
//! 4xx JSON `{"error": "field: message", "field": "field"}`. Bodies over
//! [`BODY_LIMIT`] bytes are refused. Uploads are parsed in memory; nothing a client sends
//! becomes a file path. Heavy work (building, tracing, scoring) runs on blocking threads, at
//! most [`jobs`] at a time; a request waiting for its turn that the client gives up on never
//! starts.

mod runs;

use super::cuts::info_json;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{DefaultBodyLimit, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use facetlab::cut::{families, Cut, Unit};
use facetlab::error::{Error, Result};
use facetlab::geometry::Polyhedron;
use facetlab::io;
use facetlab::metrics::{score, ScoreConfig};
use facetlab::optics::Material;
use facetlab::plot::diagram::diagram;
use facetlab::render::{render, Light, RenderOptions, Tilt};
use serde_json::{json, Map, Value};
use std::collections::BTreeMap;
use std::net::IpAddr;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::sync::Semaphore;

/// Flags of `facetlab serve`.
#[derive(clap::Args, Debug, Clone)]
pub struct ServeArgs {
    /// Port to listen on; 0 picks a free one (the printed URL says which).
    #[arg(long, default_value_t = DEFAULT_PORT, value_name = "N")]
    pub port: u16,
    /// Address to listen on. Anything but loopback (127.0.0.1, ::1) lets other machines use
    /// the workbench (a warning is printed).
    #[arg(long, default_value = "127.0.0.1", value_name = "ADDR")]
    pub bind: String,
    /// Open the page in the default browser (xdg-open); failing to is only a note.
    #[arg(long)]
    pub open: bool,
}

/// Default port.
pub const DEFAULT_PORT: u16 = 8737;
/// Largest request body, bytes.
pub const BODY_LIMIT: usize = 5 * 1024 * 1024;
/// Allowed picture sizes, pixels per side.
pub const SIZE_RANGE: (u64, u64) = (16, 1024);
/// Allowed tilt of the picture, degrees.
pub const TILT_LIMIT: f64 = 45.0;
/// Largest exposure factor of a picture.
pub const EXPOSURE_MAX: f64 = 16.0;

const PAGE_HTML: &str = include_str!("serve/page.html");
const PAGE_JS: &str = include_str!("serve/page.js");
const PAGE_CSS: &str = include_str!("serve/page.css");

/// Heavy jobs allowed to run at once: one per core.
pub fn jobs() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(2)
        .clamp(1, 8)
}

/// The address in `--bind`: an IP address or `localhost`.
fn bind_addr(s: &str) -> Result<IpAddr> {
    if s.eq_ignore_ascii_case("localhost") {
        return Ok(IpAddr::from([127, 0, 0, 1]));
    }
    s.trim().parse().map_err(|_| {
        Error::invalid(
            "--bind",
            format!("`{s}` is not an IP address; give e.g. 127.0.0.1 (default), ::1 or 0.0.0.0"),
        )
    })
}

/// Run `facetlab serve` until Ctrl-C or SIGTERM.
pub fn run(a: &ServeArgs) -> Result<()> {
    let ip = bind_addr(&a.bind)?;
    if !ip.is_loopback() {
        eprintln!(
            "facetlab serve: warning: listening on {ip}, not loopback: anyone who can reach this address can use the workbench and its CPU (there is no login)"
        );
    }
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|e| Error::io("serve", e))?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind((ip, a.port))
            .await
            .map_err(|e| {
                Error::invalid(
                    "--port",
                    format!("cannot listen on {ip} port {}: {e}", a.port),
                )
            })?;
        let addr = listener.local_addr().map_err(|e| Error::io("serve", e))?;
        let url = format!("http://{addr}/");
        println!("facetlab serve: {url}  (Ctrl-C stops it)");
        use std::io::Write;
        let _ = std::io::stdout().flush();
        if a.open {
            open_browser(&url);
        }
        axum::serve(listener, app())
            .with_graceful_shutdown(shutdown())
            .await
            .map_err(|e| Error::io("serve", e))
    })
}

/// Try to open `url` in the default browser; a failure is a note, never an error.
fn open_browser(url: &str) {
    match std::process::Command::new("xdg-open")
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
    {
        Ok(mut child) => {
            // Reap it in the background so it never lingers as a zombie.
            std::thread::spawn(move || {
                if let Ok(s) = child.wait() {
                    if !s.success() {
                        eprintln!("facetlab serve: could not open a browser (xdg-open failed); open the URL yourself");
                    }
                }
            });
        }
        Err(e) => eprintln!(
            "facetlab serve: could not open a browser (xdg-open: {e}); open the URL yourself"
        ),
    }
}

async fn shutdown() {
    let ctrl_c = async {
        let _ = tokio::signal::ctrl_c().await;
    };
    #[cfg(unix)]
    let term = async {
        match tokio::signal::unix::signal(tokio::signal::unix::SignalKind::terminate()) {
            Ok(mut s) => {
                s.recv().await;
            }
            Err(_) => std::future::pending::<()>().await,
        }
    };
    #[cfg(not(unix))]
    let term = std::future::pending::<()>();
    tokio::select! {
        _ = ctrl_c => {},
        _ = term => {},
    }
}

/// Shared state: the job limit and the presets' JSON (built once).
struct AppState {
    jobs: Arc<Semaphore>,
    presets: String,
    runs: runs::Runs,
}

/// The router: the page, its assets and the API.
pub fn app() -> Router {
    let state = Arc::new(AppState {
        jobs: Arc::new(Semaphore::new(jobs())),
        presets: presets_json().to_string(),
        runs: runs::Runs::default(),
    });
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", PAGE_HTML) }),
        )
        .route(
            "/page.js",
            get(|| async { asset("text/javascript; charset=utf-8", PAGE_JS) }),
        )
        .route(
            "/page.css",
            get(|| async { asset("text/css; charset=utf-8", PAGE_CSS) }),
        )
        .route("/api/presets", get(presets))
        .route("/api/cut", post(cut_info))
        .route("/api/score", post(score_cut))
        .route("/api/render", post(render_cut))
        .route("/api/export", post(export_cut))
        .route("/api/configs", get(runs::configs))
        .route("/api/optimize", post(runs::start).get(runs::status))
        .route("/api/optimize/stop", post(runs::stop))
        .route("/api/optimize/report", get(runs::report))
        .fallback(|| async {
            ApiError::new(StatusCode::NOT_FOUND, "path", "no such page or endpoint")
        })
        .layer(DefaultBodyLimit::max(BODY_LIMIT))
        .with_state(state)
}

fn asset(kind: &'static str, body: &'static str) -> Response {
    (
        [
            (header::CONTENT_TYPE, kind),
            (header::CACHE_CONTROL, "no-cache"),
        ],
        body,
    )
        .into_response()
}

/// An API error: a status and a one-line message naming the field.
#[derive(Debug)]
struct ApiError {
    status: StatusCode,
    field: String,
    message: String,
}

impl ApiError {
    fn new(status: StatusCode, field: impl Into<String>, message: impl Into<String>) -> Self {
        ApiError {
            status,
            field: field.into(),
            message: message.into(),
        }
    }
    fn bad(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(StatusCode::BAD_REQUEST, field, message)
    }
    /// A library error about the cut or its parameters, named by the request's field.
    fn from_cut(e: Error) -> Self {
        match e {
            Error::Invalid { field, message } => {
                let field = field.strip_prefix("--set ").unwrap_or(&field).to_string();
                // Parameter keys are plain identifiers; anything else is about the cut.
                let key = field.rsplit(": ").next().unwrap_or(&field);
                if !key.is_empty()
                    && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
                    && key != "family"
                {
                    Self::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        format!("set.{key}"),
                        message,
                    )
                } else {
                    Self::new(
                        StatusCode::UNPROCESSABLE_ENTITY,
                        "cut",
                        format!("{field}: {message}"),
                    )
                }
            }
            Error::Geometry(m) => Self::new(StatusCode::UNPROCESSABLE_ENTITY, "set", m),
            other => Self::from_load(other),
        }
    }
    /// A library error while reading the cut itself (a preset or an uploaded file): about
    /// `cut`, even when the file names a parameter.
    fn from_load(e: Error) -> Self {
        match e {
            Error::Invalid { field, message } => Self::new(
                StatusCode::UNPROCESSABLE_ENTITY,
                "cut",
                format!("{field}: {message}"),
            ),
            other => {
                let text = other.to_string();
                let msg = text.strip_prefix("cut:").unwrap_or(&text).trim_start();
                let msg = if msg.starts_with(|c: char| c.is_ascii_digit()) {
                    format!("line {msg}")
                } else {
                    msg.to_string()
                };
                Self::new(StatusCode::UNPROCESSABLE_ENTITY, "cut", msg)
            }
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let one_line: String = self
            .message
            .split_whitespace()
            .collect::<Vec<_>>()
            .join(" ");
        let body = json!({
            "error": format!("{}: {one_line}", self.field),
            "field": self.field,
        });
        (
            self.status,
            [(header::CACHE_CONTROL, "no-store")],
            axum::Json(body),
        )
            .into_response()
    }
}

type ApiResult<T> = std::result::Result<T, ApiError>;

/// `GET /api/presets`.
async fn presets(State(st): State<Arc<AppState>>) -> Response {
    (
        [(header::CONTENT_TYPE, "application/json")],
        st.presets.clone(),
    )
        .into_response()
}

fn presets_json() -> Value {
    let presets: Vec<Value> = io::presets::names()
        .into_iter()
        .filter_map(|n| {
            let cut = io::presets::load(n)?.ok()?;
            Some(json!({
                "name": n,
                "title": cut.name,
                "family": cut.family,
                "params": cut.params,
            }))
        })
        .collect();
    let fams: Vec<Value> = families()
        .iter()
        .map(|f| {
            let params: Vec<Value> = f
                .params
                .iter()
                .map(|p| {
                    let (unit, step) = match p.unit {
                        Unit::Degrees => ("degrees", 0.05),
                        Unit::Fraction => ("fraction", 0.001),
                        Unit::Ratio => ("ratio", 0.01),
                        Unit::Count => ("count", 1.0),
                    };
                    json!({
                        "key": p.key, "default": p.default, "min": p.min, "max": p.max,
                        "open": p.open, "unit": unit, "step": step, "doc": p.doc,
                    })
                })
                .collect();
            json!({"name": f.name, "doc": f.doc, "params": params})
        })
        .collect();
    json!({
        "presets": presets,
        "families": fams,
        "lights": Light::ALL.map(Light::name),
        "formats": FORMATS,
        "limits": {
            "size": [SIZE_RANGE.0, SIZE_RANGE.1],
            "tilt": [-TILT_LIMIT, TILT_LIMIT],
            "exposure": [0.0, EXPOSURE_MAX],
            "body_bytes": BODY_LIMIT,
        },
    })
}

/// File formats accepted as `format` and produced as `to`.
const FORMATS: [&str; 4] = ["asc", "obj", "stl", "toml"];

/// What `POST /api/export` writes: the cut's files, and `html`, its one-page report
/// ([`facetlab::report`]).
const EXPORTS: [&str; 5] = ["asc", "obj", "stl", "toml", "html"];

/// Where a cut comes from.
#[derive(Clone, Debug)]
enum Source {
    Preset(String),
    File {
        format: &'static str,
        bytes: Vec<u8>,
        name: String,
    },
}

/// A request body, validated (the cut itself is built later, on a blocking thread).
#[derive(Clone, Debug)]
struct Req {
    source: Source,
    set: BTreeMap<String, f64>,
    light: Light,
    size: usize,
    tilt: f64,
    exposure: f64,
    quick: bool,
    to: Option<&'static str>,
}

/// Which keys an endpoint takes beyond `cut`, `format`, `encoding`, `name`, `set`.
const COMMON: [&str; 5] = ["cut", "format", "encoding", "name", "set"];

fn parse_req(body: std::result::Result<Bytes, BytesRejection>, extra: &[&str]) -> ApiResult<Req> {
    let body = body.map_err(|r| {
        let status = r.status();
        let msg = if status == StatusCode::PAYLOAD_TOO_LARGE {
            format!(
                "the request is larger than {} MB",
                BODY_LIMIT / (1024 * 1024)
            )
        } else {
            r.body_text()
        };
        ApiError::new(status, "body", msg)
    })?;
    let v: Value = serde_json::from_slice(&body)
        .map_err(|e| ApiError::bad("body", format!("not JSON: {e}")))?;
    let Value::Object(m) = v else {
        return Err(ApiError::bad(
            "body",
            "expected a JSON object like {\"cut\": \"tolkowsky\"}",
        ));
    };
    for k in m.keys() {
        if !COMMON.contains(&k.as_str()) && !extra.contains(&k.as_str()) {
            let mut allowed: Vec<&str> = COMMON.to_vec();
            allowed.extend_from_slice(extra);
            return Err(ApiError::bad(
                short(k),
                format!("unknown field; allowed: {}", allowed.join(", ")),
            ));
        }
    }
    Ok(Req {
        source: source(&m)?,
        set: set(&m)?,
        light: match m.get("light") {
            None | Some(Value::Null) => Light::Iso,
            Some(Value::String(s)) => Light::parse(s).map_err(|_| {
                ApiError::bad(
                    "light",
                    format!(
                        "unknown light {:?}; allowed {}",
                        short(s),
                        Light::ALL.map(Light::name).join(", ")
                    ),
                )
            })?,
            Some(_) => return Err(ApiError::bad("light", "must be a string such as \"iso\"")),
        },
        size: match m.get("size") {
            None | Some(Value::Null) => 512,
            Some(v) => match v.as_u64() {
                Some(n) if (SIZE_RANGE.0..=SIZE_RANGE.1).contains(&n) => n as usize,
                _ => {
                    return Err(ApiError::bad(
                        "size",
                        format!(
                            "{} is not allowed; give whole pixels from {} to {}",
                            short(&v.to_string()),
                            SIZE_RANGE.0,
                            SIZE_RANGE.1
                        ),
                    ))
                }
            },
        },
        tilt: match m.get("tilt") {
            None | Some(Value::Null) => 0.0,
            Some(v) => match v.as_f64() {
                Some(t) if t.abs() <= TILT_LIMIT => t,
                _ => {
                    return Err(ApiError::bad(
                        "tilt",
                        format!(
                            "{} is not allowed; give degrees from {} to {}",
                            short(&v.to_string()),
                            -TILT_LIMIT,
                            TILT_LIMIT
                        ),
                    ))
                }
            },
        },
        exposure: match m.get("exposure") {
            None | Some(Value::Null) => 1.0,
            Some(v) => match v.as_f64() {
                Some(x) if x > 0.0 && x <= EXPOSURE_MAX => x,
                _ => {
                    return Err(ApiError::bad(
                        "exposure",
                        format!(
                            "{} is not allowed; give a factor in (0, {EXPOSURE_MAX}] (1 = a white diffuser shows white)",
                            short(&v.to_string())
                        ),
                    ))
                }
            },
        },
        quick: match m.get("quick") {
            None | Some(Value::Null) => false,
            Some(Value::Bool(b)) => *b,
            Some(_) => return Err(ApiError::bad("quick", "must be true or false")),
        },
        to: match m.get("to") {
            None | Some(Value::Null) => None,
            Some(Value::String(s)) => Some(export_of(s).ok_or_else(|| {
                ApiError::bad(
                    "to",
                    format!("cannot write {:?}; allowed: {}", short(s), EXPORTS.join(", ")),
                )
            })?),
            Some(_) => return Err(ApiError::bad("to", "must be one of asc, obj, stl, toml, html")),
        },
    })
}

/// A client's string as shown in a message: at most 40 characters, one line.
fn short(s: &str) -> String {
    let mut out: String = s
        .chars()
        .take(40)
        .map(|c| if c.is_control() { '?' } else { c })
        .collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out
}

fn export_of(s: &str) -> Option<&'static str> {
    let s = s.trim().trim_start_matches('.').to_ascii_lowercase();
    EXPORTS.into_iter().find(|f| *f == s)
}

fn format_of(s: &str) -> Option<&'static str> {
    let s = s.trim().trim_start_matches('.').to_ascii_lowercase();
    FORMATS.into_iter().find(|f| *f == s)
}

fn source(m: &Map<String, Value>) -> ApiResult<Source> {
    let cut = match m.get("cut") {
        Some(Value::String(s)) => s,
        None | Some(Value::Null) => {
            return Err(ApiError::bad(
                "cut",
                "missing; give a preset name or the text of a .asc, .obj, .stl or .toml file with \"format\"",
            ))
        }
        Some(_) => return Err(ApiError::bad("cut", "must be a string")),
    };
    let format = match m.get("format") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(format_of(s).ok_or_else(|| {
            ApiError::bad(
                "format",
                format!(
                    "unknown format {:?}; allowed: {}",
                    short(s),
                    FORMATS.join(", ")
                ),
            )
        })?),
        Some(_) => return Err(ApiError::bad("format", "must be a string")),
    };
    let base64 = match m.get("encoding") {
        None | Some(Value::Null) => false,
        Some(Value::String(s)) if s == "text" => false,
        Some(Value::String(s)) if s == "base64" => true,
        Some(_) => return Err(ApiError::bad("encoding", "allowed: \"text\" or \"base64\"")),
    };
    let name = match m.get("name") {
        None | Some(Value::Null) => None,
        Some(Value::String(s)) => Some(clean_name(s)),
        Some(_) => return Err(ApiError::bad("name", "must be a string")),
    };
    let Some(format) = format else {
        if base64 {
            return Err(ApiError::bad(
                "encoding",
                "only with \"format\" (a file's contents)",
            ));
        }
        if io::presets::names().contains(&cut.as_str()) {
            return Ok(Source::Preset(cut.clone()));
        }
        return Err(ApiError::bad(
            "cut",
            format!(
                "unknown preset {:?}; presets: {}; or send a file's text with \"format\"",
                short(cut),
                io::presets::names().join(", ")
            ),
        ));
    };
    let bytes = if base64 {
        decode_base64(cut).ok_or_else(|| ApiError::bad("cut", "is not valid base64"))?
    } else {
        cut.as_bytes().to_vec()
    };
    let name = name
        .filter(|n| !n.is_empty())
        .unwrap_or_else(|| "upload".to_string());
    Ok(Source::File {
        format,
        bytes,
        name,
    })
}

/// A display name from a client: a file stem without its extension, at most 64 characters
/// of letters, digits, `-`, `_`, `.` and spaces.
fn clean_name(s: &str) -> String {
    let stem = s.rsplit(['/', '\\']).next().unwrap_or(s);
    let stem = match stem.rsplit_once('.') {
        Some((a, e)) if format_of(e).is_some() => a,
        _ => stem,
    };
    stem.chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '-' | '_' | '.' | ' '))
        .take(64)
        .collect::<String>()
        .trim()
        .to_string()
}

fn set(m: &Map<String, Value>) -> ApiResult<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    match m.get("set") {
        None | Some(Value::Null) => {}
        Some(Value::Object(o)) => {
            for (k, v) in o {
                let field = format!("set.{}", short(k));
                let x = v.as_f64().ok_or_else(|| {
                    ApiError::bad(&field, format!("{} is not a number", short(&v.to_string())))
                })?;
                out.insert(k.clone(), x);
            }
        }
        Some(_) => {
            return Err(ApiError::bad(
                "set",
                "must be an object of parameter values, e.g. {\"pavilion_angle\": 40.9}",
            ))
        }
    }
    Ok(out)
}

/// Decode standard base64 (padding optional, whitespace ignored).
fn decode_base64(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let (mut acc, mut bits) = (0u32, 0u32);
    for c in s.bytes() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' | b' ' | b'\n' | b'\r' | b'\t' => continue,
            _ => return None,
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

/// Build the cut a request names, with its parameter changes.
fn build(r: &Req) -> ApiResult<Cut> {
    let cut = match &r.source {
        Source::Preset(n) => match io::presets::load(n) {
            Some(c) => c.map_err(ApiError::from_load)?,
            None => return Err(ApiError::bad("cut", "unknown preset")),
        },
        Source::File {
            format,
            bytes,
            name,
        } => load_bytes(format, bytes, name).map_err(ApiError::from_load)?,
    };
    if !r.set.is_empty() && cut.family.is_none() {
        return Err(ApiError::new(
            StatusCode::UNPROCESSABLE_ENTITY,
            "set",
            format!(
                "{} is an explicit facet design, not a parametric family; it has no parameters to set",
                cut.name
            ),
        ));
    }
    cut.with_params(&r.set).map_err(ApiError::from_cut)
}

/// Parse a cut file's bytes in memory; `cut` names the source in messages.
fn load_bytes(format: &str, bytes: &[u8], name: &str) -> Result<Cut> {
    let source = "cut";
    match format {
        "toml" => {
            let text = String::from_utf8_lossy(bytes);
            io::spec::parse(&text, source)?.to_cut(name, source)
        }
        "asc" => io::asc::parse(bytes, source)?.to_cut(name),
        "obj" | "stl" => {
            let planes = if format == "obj" {
                io::mesh::read_obj(bytes, source)?
            } else {
                io::mesh::read_stl(bytes, source)?
            };
            let solid = Polyhedron::from_planes(&planes).map_err(|e| match e {
                Error::Geometry(m) => Error::parse(source, format!("convex hull of the mesh: {m}")),
                other => other,
            })?;
            Ok(Cut {
                name: name.to_string(),
                family: None,
                params: Default::default(),
                solid,
                design: None,
            })
        }
        other => Err(Error::invalid("format", format!("unknown format {other}"))),
    }
}

/// Run `f` on a blocking thread once a job slot is free. A request whose client gives up
/// while waiting is dropped here and never runs.
async fn heavy<T, F>(st: &AppState, f: F) -> ApiResult<T>
where
    T: Send + 'static,
    F: FnOnce() -> ApiResult<T> + Send + 'static,
{
    let permit = tokio::time::timeout(Duration::from_secs(60), st.jobs.clone().acquire_owned())
        .await
        .map_err(|_| {
            ApiError::new(
                StatusCode::SERVICE_UNAVAILABLE,
                "server",
                "busy; try again in a moment",
            )
        })?
        .map_err(|_| ApiError::new(StatusCode::SERVICE_UNAVAILABLE, "server", "shutting down"))?;
    let job = tokio::task::spawn_blocking(move || {
        let _permit = permit;
        f()
    });
    match job.await {
        Ok(r) => r,
        Err(_) => Err(ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "server",
            "the computation failed (see the server's log)",
        )),
    }
}

/// `POST /api/cut`: `info --json` plus the SVG diagram.
async fn cut_info(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &[])?;
    let v = heavy(&st, move || {
        let cut = build(&r)?;
        let info = info_json(&cut, 6.5, &Material::diamond());
        let mut v = serde_json::to_value(&info)
            .map_err(|e| ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "cut", e.to_string()))?;
        if let Value::Object(m) = &mut v {
            m.insert("svg".into(), Value::String(diagram(&cut)));
            if let Source::Preset(p) = &r.source {
                m.insert("preset".into(), Value::String(p.clone()));
            }
        }
        Ok(v)
    })
    .await?;
    Ok(no_store(axum::Json(v).into_response()))
}

/// `POST /api/score`: the keys of `score --json`.
async fn score_cut(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &["quick"])?;
    let (text, timing) = heavy(&st, move || {
        let t0 = Instant::now();
        let cut = build(&r)?;
        let cfg = if r.quick {
            ScoreConfig::fast()
        } else {
            ScoreConfig::default()
        };
        let s = score(&cut.solid, &cfg);
        let text = super::score::to_json(&cfg, &[(cut.name.clone(), s)], &[], 0).map_err(|e| {
            ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "score", e.to_string())
        })?;
        // The same document with `quick` said, so a client can tell the two apart.
        let mut v: Value = serde_json::from_str(&text).map_err(|e| {
            ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "score", e.to_string())
        })?;
        if let Value::Object(m) = &mut v {
            m.insert("quick".into(), Value::Bool(r.quick));
        }
        let timing = format!("score;dur={:.1}", t0.elapsed().as_secs_f64() * 1e3);
        Ok((v, timing))
    })
    .await?;
    let mut resp = axum::Json(text).into_response();
    if let Ok(h) = HeaderValue::from_str(&timing) {
        resp.headers_mut().insert("server-timing", h);
    }
    Ok(no_store(resp))
}

/// `POST /api/render`: a PNG.
async fn render_cut(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &["light", "size", "tilt", "exposure"])?;
    let (png, stats, timing) = heavy(&st, move || {
        let t0 = Instant::now();
        let cut = build(&r)?;
        let t1 = Instant::now();
        let mut o = RenderOptions::new(r.light);
        o.size = r.size;
        o.tilt = Tilt {
            tilt_deg: r.tilt,
            azimuth_deg: 0.0,
        };
        o.validate()
            .map_err(|e| ApiError::bad("render", e.to_string()))?;
        let img = render(&cut.solid, &o);
        let t2 = Instant::now();
        let rgb = img.to_srgb8(r.exposure, facetlab::plot::palette::STAGE_GROUND);
        let n = r.size as u32;
        let png = io::png::encode_rgb8(n, n, &[&rgb], 0).map_err(|e| {
            ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "render", e.to_string())
        })?;
        let stats = serde_json::to_string(&img.stats).unwrap_or_default();
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        let t3 = Instant::now();
        let timing = format!(
            "build;dur={:.1}, trace;dur={:.1}, png;dur={:.1}",
            ms(t0, t1),
            ms(t1, t2),
            ms(t2, t3)
        );
        Ok((png, stats, timing))
    })
    .await?;
    let mut resp = ([(header::CONTENT_TYPE, "image/png")], png).into_response();
    if let Ok(h) = HeaderValue::from_str(&timing) {
        resp.headers_mut().insert("server-timing", h);
    }
    if let Ok(h) = HeaderValue::from_str(&stats) {
        resp.headers_mut().insert("x-facetlab-stats", h);
    }
    Ok(no_store(resp))
}

/// `POST /api/export`: the cut as a file.
async fn export_cut(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &["to"])?;
    let Some(to) = r.to else {
        return Err(ApiError::bad(
            "to",
            format!("missing; give the file format: {}", EXPORTS.join(", ")),
        ));
    };
    let (bytes, name) = heavy(&st, move || {
        let cut = build(&r)?;
        let bytes: Vec<u8> = match to {
            "toml" => io::spec::write(&cut).into_bytes(),
            "asc" => io::asc::write(&cut, io::asc::DEFAULT_GEAR).into_bytes(),
            "obj" => io::mesh::write_obj(&cut).into_bytes(),
            "html" => {
                let o = facetlab::report::ReportOptions {
                    title: format!("facetlab report: {}", cut.name),
                    ..Default::default()
                };
                let page = facetlab::report::measure(&cut.name, &cut, &o)
                    .and_then(|r| facetlab::report::html(&[r], &o))
                    .map_err(|e| {
                        ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "to", e.to_string())
                    })?;
                page.into_bytes()
            }
            _ => io::mesh::write_stl(&cut),
        };
        let stem: String = cut
            .name
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                    c
                } else {
                    '-'
                }
            })
            .take(64)
            .collect();
        let stem = if stem.trim_matches('-').is_empty() {
            "cut".to_string()
        } else {
            stem
        };
        Ok((bytes, format!("{stem}.{to}")))
    })
    .await?;
    let kind = match to {
        "stl" => "model/stl",
        "html" => "text/html; charset=utf-8",
        _ => "text/plain; charset=utf-8",
    };
    let mut resp = ([(header::CONTENT_TYPE, kind)], bytes).into_response();
    if let Ok(h) = HeaderValue::from_str(&format!("attachment; filename=\"{name}\"")) {
        resp.headers_mut().insert(header::CONTENT_DISPOSITION, h);
    }
    Ok(no_store(resp))
}

fn no_store(mut r: Response) -> Response {
    r.headers_mut()
        .insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_names() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGVsbG8").unwrap(), b"hello");
        assert!(decode_base64("a*b").is_none());
        assert_eq!(clean_name("../../etc/passwd"), "passwd");
        assert_eq!(clean_name("my cut.asc"), "my cut");
        assert_eq!(clean_name("a<script>.toml"), "ascript");
        assert!(bind_addr("example").is_err());
        assert!(bind_addr("localhost").unwrap().is_loopback());
    }

    #[test]
    fn errors_name_the_request_field() {
        let mut v = BTreeMap::new();
        v.insert("crown_angle".to_string(), 75.0);
        let e = io::presets::load("tolkowsky")
            .unwrap()
            .unwrap()
            .with_params(&v)
            .unwrap_err();
        assert_eq!(ApiError::from_cut(e).field, "set.crown_angle");
        let e = load_bytes("asc", b"g 96 0\na x3 1 2\n", "u").unwrap_err();
        let a = ApiError::from_load(e);
        assert_eq!(a.field, "cut", "{a:?}");
        assert!(a.message.starts_with("line 2"), "{a:?}");
        // A parameter out of range inside an uploaded spec is about the upload.
        let spec = b"family = \"round-brilliant\"\n[params]\ncrown_angle = 75.0\n";
        let a = ApiError::from_load(load_bytes("toml", spec, "u").unwrap_err());
        assert_eq!(a.field, "cut", "{a:?}");
        assert!(a.message.contains("crown_angle"), "{a:?}");
    }
}
