//! The router of `facetlab serve` and the cut endpoints: `GET /api/presets`, `POST /api/cut`,
//! `/api/score`, `/api/render` and `/api/export` (the optimization runs' endpoints are in
//! [`super::runs`], the page's in [`super::page`]).

use super::error::{no_store, ApiError, ApiResult};
use super::jobs::{build, build_design, heavy, jobs};
use super::request::{parse_req, stone_for, Source, EXPORTS, FORMATS, PHOTO, STONE};
use super::{
    page, plans, recipes, runs, AppState, BODY_LIMIT, EXPOSURE_MAX, SIZE_RANGE, TILT_LIMIT,
};
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{DefaultBodyLimit, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use facetlab::cut::{families, Unit};
use facetlab::document::info::info_json;
use facetlab::io;
use facetlab::metrics::{score, ScoreConfig};
use facetlab::optics::Material;
use facetlab::optics::StoneSize;
use facetlab::plot::diagram::diagram;
use facetlab::plot::palette::STAGE_GROUND;
use facetlab::render::{render, Light, Pictures};
use serde_json::{json, Value};
use std::sync::Arc;
use std::time::Instant;
use tokio::sync::Semaphore;

/// The router: the page, its assets and the API.
pub fn app() -> Router {
    let state = Arc::new(AppState {
        jobs: Arc::new(Semaphore::new(jobs())),
        presets: presets_json().to_string(),
        runs: runs::Runs::default(),
        plans: plans::PlanRuns::default(),
        designs: Arc::default(),
    });
    Router::new()
        .merge(page::routes())
        .route("/api/presets", get(presets))
        .route("/api/cut", post(cut_info))
        .route("/api/score", post(score_cut))
        .route("/api/render", post(render_cut))
        .route("/api/export", post(export_cut))
        .route("/api/recipe/build", post(recipes::build_recipe))
        .route("/api/recipe/infer", post(recipes::infer_recipe))
        .route("/api/configs", get(runs::configs))
        .route("/api/optimize", post(runs::start).get(runs::status))
        .route("/api/optimize/stop", post(runs::stop))
        .route("/api/optimize/report", get(runs::report))
        .route("/api/plan", post(plans::start).get(plans::status))
        .route("/api/plan/stop", post(plans::stop))
        .route("/api/plan/report", get(plans::report))
        .route("/api/plan/picture/{name}", get(plans::picture))
        .fallback(|| async {
            ApiError::new(StatusCode::NOT_FOUND, "path", "no such page or endpoint")
        })
        .layer(DefaultBodyLimit::max(BODY_LIMIT))
        .with_state(state)
}

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
        "photo_lights": facetlab::render::photo::PhotoLight::names(),
        "light_table": facetlab::render::lights::table(),
        "formats": FORMATS,
        "materials": materials_json(),
        "crystals": facetlab::plan::CRYSTALS,
        "plan": {
            "default_family": plans::DEFAULT_FAMILY,
            "top": [plans::TOP.0, plans::TOP.1, plans::TOP.2],
            "starts": [plans::STARTS.0, plans::STARTS.1, plans::STARTS.2],
            "max_triangles": plans::MAX_ROUGH_TRIANGLES,
        },
        "limits": {
            "colour_density": [0.0, facetlab::optics::DENSITY_MAX],
            "stone_mm": [0.0, facetlab::optics::StoneSize::MAX_MM],
            "rough_mm": [0.0, facetlab::plan::ROUGH_MAX_MM],
            "size": [SIZE_RANGE.0, SIZE_RANGE.1],
            "tilt": [-TILT_LIMIT, TILT_LIMIT],
            "exposure": [0.0, EXPOSURE_MAX],
            "head_shadow": [0.0, super::HEAD_SHADOW_MAX],
            "body_bytes": BODY_LIMIT,
        },
    })
}

/// The materials a stone can be (`facetlab materials`): the table's, then the coloured
/// varieties, each with `colour`: its body colour seen through the default width as
/// `#rrggbb` (`null` when colourless or no spectrum is published), and `optic_axis`: a
/// uniaxial stone's default optic axis, degrees from the table's normal (`null` for others).
fn materials_json() -> Vec<Value> {
    let w = facetlab::optics::StoneSize::DEFAULT_WIDTH_MM;
    let table = Material::table().into_iter().map(|m| {
        json!({
            "name": m.name,
            "colour": m.colour.as_ref().map(|c| c.hex_through(w)),
            "optic_axis": m.uniaxial.as_ref().map(|u| u.axis.tilt_deg),
        })
    });
    let varieties = facetlab::optics::Variety::all().iter().map(|v| {
        let c = v.body_colour();
        json!({
            "name": v.name,
            "colour": c.as_ref().map(|c| c.hex_through(w)),
            "source": c.map(|c| c.source),
            "optic_axis": v.material().uniaxial.as_ref().map(|u| u.axis.tilt_deg),
        })
    });
    table.chain(varieties).collect()
}

/// `POST /api/cut`: `info --json` plus the SVG diagram, and for a cut without a family its
/// tier angles as sliders (`design_space`). The first answer about a design starts probing
/// which meets each tier opens alone, in the background; later answers carry it.
async fn cut_info(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &STONE)?;
    let designs = st.designs.clone();
    let (v, probe) = heavy(&st, move || {
        let (cut, design) = build_design(&designs, &r, true)?;
        let (material, width) = stone_for(&r, &cut)?;
        let info = info_json(&cut, width, &material);
        let mut v = serde_json::to_value(&info)
            .map_err(|e| ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "cut", e.to_string()))?;
        let mut probe = None;
        if let Value::Object(m) = &mut v {
            m.insert("svg".into(), Value::String(diagram(&cut)));
            if let Source::Preset(p) = &r.source {
                m.insert("preset".into(), Value::String(p.clone()));
            }
            match design {
                Some(Ok(d)) => {
                    m.insert("design_space".into(), d.json());
                    probe = d.start_probe().then_some(d);
                }
                Some(Err(e)) => {
                    m.insert("design_space".into(), json!({ "error": e }));
                }
                None => {}
            }
        }
        Ok((v, probe))
    })
    .await?;
    if let Some(d) = probe {
        let st = st.clone();
        tokio::spawn(async move {
            let job = d.clone();
            let done = heavy(&st, move || {
                job.probe();
                Ok(())
            })
            .await;
            if done.is_err() {
                // Never ran (the server was busy): the next answer starts it again.
                d.unstart_probe();
            }
        });
    }
    Ok(no_store(axum::Json(v).into_response()))
}

/// `POST /api/score`: the keys of `score --json`.
async fn score_cut(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &[&["quick", "head_shadow"][..], &STONE].concat())?;
    let designs = st.designs.clone();
    let (text, timing) = heavy(&st, move || {
        let t0 = Instant::now();
        let cut = build(&designs, &r)?;
        // Refuses a length × width that disagrees with the cut's L/W.
        let (material, _) = stone_for(&r, &cut)?;
        let base = if r.quick {
            ScoreConfig::fast()
        } else {
            ScoreConfig::default()
        };
        let cfg = ScoreConfig {
            material,
            size: r.stone.size,
            head_shadow_deg: r.picture.head_shadow.unwrap_or(base.head_shadow_deg),
            ..base
        };
        let s = score(&cut.solid, &cfg);
        let text = facetlab::document::score::score_json(&cfg, &[(cut.name.clone(), s)], &[], 0)
            .map_err(|e| {
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
    let r = parse_req(
        body,
        &[
            &["light", "size", "tilt", "exposure", "head_shadow", "quick"][..],
            &STONE,
            &PHOTO,
        ]
        .concat(),
    )?;
    let designs = st.designs.clone();
    let (png, stats, timing) = heavy(&st, move || {
        let t0 = Instant::now();
        let cut = build(&designs, &r)?;
        let t1 = Instant::now();
        // The cut's own material unless one was sent, as the scores.
        let (material, width) = stone_for(&r, &cut)?;
        let pictures = r
            .picture
            .pictures(&material, StoneSize::Width(width))
            .map_err(ApiError::from_picture)?;
        let p = match pictures {
            Pictures::Photo(p) => return photograph(&r, &cut, p, t0, t1),
            Pictures::Lab(p) => p,
        };
        let mut o = p.opts;
        o.width_mm = width;
        o.validate().map_err(ApiError::from_picture)?;
        let img = render(&cut.solid, &o);
        let t2 = Instant::now();
        let rgb = img.to_srgb8(p.exposure, STAGE_GROUND);
        let n = o.size as u32;
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

/// The photograph of `/api/render` with a photographic light: the PNG, its statistics as
/// JSON and the timing header. `quick` takes the slider's quick settings.
fn photograph(
    r: &super::request::Req,
    cut: &facetlab::cut::Cut,
    p: facetlab::render::PhotoPictures,
    t0: Instant,
    t1: Instant,
) -> ApiResult<(Vec<u8>, String, String)> {
    use facetlab::render::photo::photo;
    let mut o = p.opts;
    if r.quick {
        o = o.quick();
    }
    o.validate().map_err(ApiError::from_picture)?;
    let shot = photo(&cut.solid, &o);
    let t2 = Instant::now();
    let rgb = shot.to_srgb8(p.exposure, o.tone);
    let n = o.size as u32;
    let png = io::png::encode_rgb8(n, n, &[&rgb], 0)
        .map_err(|e| ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "render", e.to_string()))?;
    let stats = serde_json::to_string(&shot.stats).unwrap_or_default();
    let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
    let timing = format!(
        "build;dur={:.1}, trace;dur={:.1}, png;dur={:.1}",
        ms(t0, t1),
        ms(t1, t2),
        ms(t2, Instant::now())
    );
    Ok((png, stats, timing))
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
    let designs = st.designs.clone();
    let (bytes, name) = heavy(&st, move || {
        let cut = build(&designs, &r)?;
        let bytes: Vec<u8> = match to {
            "toml" => io::spec::write(&cut).into_bytes(),
            "asc" => {
                io::asc::check(&cut).map_err(|e| {
                    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "to", e.to_string())
                })?;
                io::asc::write(&cut, io::asc::DEFAULT_GEAR).into_bytes()
            }
            "gem" => io::gem::write(&cut, io::asc::DEFAULT_GEAR).map_err(|e| {
                ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "to", e.to_string())
            })?,
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
        "gem" => "application/octet-stream",
        "html" => "text/html; charset=utf-8",
        _ => "text/plain; charset=utf-8",
    };
    let mut resp = ([(header::CONTENT_TYPE, kind)], bytes).into_response();
    if let Ok(h) = HeaderValue::from_str(&format!("attachment; filename=\"{name}\"")) {
        resp.headers_mut().insert(header::CONTENT_DISPOSITION, h);
    }
    Ok(no_store(resp))
}
