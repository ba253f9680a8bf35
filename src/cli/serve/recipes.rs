//! The tier editor's endpoints: `POST /api/recipe/build` (a recipe's TOML text built tier by
//! tier, [`facetlab::design::recipe`]: the cut as `/api/cut` answers it, with the steps and
//! findings) and `POST /api/recipe/infer` (the recipe of the cut a request names, as the page's
//! editor holds it). A recipe that cannot be cut is a 422 naming the tier (`"field": "tier P2"`)
//! or the design's field (`design.gear`).

use super::error::{no_store, ApiError, ApiResult};
use super::jobs::{build, heavy};
use super::request::{parse_req, stone_for, Source, STONE};
use super::AppState;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::State;
use axum::http::{HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use facetlab::design::recipe::{infer, Angle, FindingKind, Place, Recipe};
use facetlab::document::info::info_json;
use facetlab::error::Error;
use facetlab::io;
use facetlab::plot::diagram::diagram;
use serde_json::{json, Value};
use std::sync::Arc;
use std::time::Instant;

/// A library error about a recipe, named by the recipe's field: `tier NAME`, `design.KEY`, or
/// `recipe` (a TOML syntax error, with its line).
pub fn recipe_error(e: Error) -> ApiError {
    let named = |text: &str| -> Option<(String, String)> {
        let (head, rest) = text.split_once(": ")?;
        (head.starts_with("tier") || head.starts_with("design"))
            .then(|| (head.to_string(), rest.to_string()))
    };
    let (field, message) = match e {
        Error::Parse { source, message } => {
            named(&message).unwrap_or_else(|| ("recipe".into(), format!("{source}: {message}")))
        }
        Error::Invalid { field, message } if field.starts_with("tier") => (field, message),
        Error::Invalid { field, message }
            if ["gear", "symmetry", "offset", "index"].contains(&field.as_str()) =>
        {
            (format!("design.{field}"), message)
        }
        other => {
            let text = other.to_string();
            named(&text).unwrap_or(("recipe".into(), text))
        }
    };
    ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, field, message)
}

/// The recipe's text a request sends as `cut` (with `format: "toml"`).
fn recipe_text(r: &super::request::Req) -> ApiResult<(String, String)> {
    match &r.source {
        Source::File {
            format: "toml",
            bytes,
            name,
        } => Ok((String::from_utf8_lossy(bytes).into_owned(), name.clone())),
        _ => Err(ApiError::bad(
            "format",
            "a recipe is sent as its TOML text: {\"cut\": \"[design]…\", \"format\": \"toml\"}",
        )),
    }
}

/// `POST /api/recipe/build`: `/api/cut`'s answer (`info --json` and `svg`) for the recipe sent
/// as `cut`, plus `steps` (tier, angle, indices, depth, instruction), `findings` (tier, kind,
/// message) and `build_ms`; the time is also the `server-timing` header.
pub async fn build_recipe(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &STONE)?;
    let (v, timing) = heavy(&st, move || {
        let t0 = Instant::now();
        let (text, name) = recipe_text(&r)?;
        let stem = name.strip_suffix(".toml").unwrap_or(&name).to_string();
        let recipe = io::recipe::parse(&text, "recipe", &stem).map_err(recipe_error)?;
        let built = recipe.build().map_err(recipe_error)?;
        let t1 = Instant::now();
        let cut = &built.cut;
        let (material, width) = stone_for(&r, cut)?;
        let info = info_json(cut, width, &material);
        let mut v = serde_json::to_value(&info)
            .map_err(|e| ApiError::new(StatusCode::INTERNAL_SERVER_ERROR, "cut", e.to_string()))?;
        let steps: Vec<Value> = built
            .steps
            .iter()
            .map(|s| {
                json!({"tier": s.tier, "angle": s.angle, "indices": s.indices,
                    "depth": s.depth, "instruction": s.instruction})
            })
            .collect();
        let findings: Vec<Value> = built
            .findings
            .iter()
            .map(|f| {
                json!({"tier": f.tier, "message": f.message, "kind": match f.kind {
                    FindingKind::SmallFacet => "small-facet",
                    FindingKind::BelowCritical => "below-critical",
                }})
            })
            .collect();
        if let Value::Object(m) = &mut v {
            m.insert("svg".into(), Value::String(diagram(cut)));
            m.insert("steps".into(), Value::Array(steps));
            m.insert("findings".into(), Value::Array(findings));
            let ms = (t1 - t0).as_secs_f64() * 1e3;
            m.insert("build_ms".into(), json!(ms));
        }
        let timing = format!(
            "build;dur={:.1}, answer;dur={:.1}",
            (t1 - t0).as_secs_f64() * 1e3,
            t1.elapsed().as_secs_f64() * 1e3
        );
        Ok((v, timing))
    })
    .await?;
    let mut resp = axum::Json(v).into_response();
    if let Ok(h) = HeaderValue::from_str(&timing) {
        resp.headers_mut().insert("server-timing", h);
    }
    Ok(no_store(resp))
}

/// A recipe as the page's editor holds it: the design's settings, and each tier's name, angle
/// and indices as text, its placement (`place`: meet, centre, depth, scale, girdle, table) and
/// value (`"G1-P1"` for a meet, `""` for centre), side and note.
pub fn editor_json(r: &Recipe) -> Value {
    let tiers: Vec<Value> = r
        .tiers
        .iter()
        .map(|t| {
            let angle = match &t.angle {
                Angle::Degrees(a) if *a == 0.0 && a.is_sign_negative() => "-0".to_string(),
                Angle::Degrees(a) => format!("{a}"),
                Angle::Expr(e) => e.clone(),
            };
            let indices: Vec<String> = t.indices.iter().map(|x| format!("{x}")).collect();
            let (place, value) = match &t.place {
                Place::Meet(m) => ("meet", m.join("-")),
                Place::Centre => ("centre", String::new()),
                Place::Depth(d) => ("depth", format!("{d}")),
                Place::Scale(d) => ("scale", format!("{d}")),
                Place::Girdle(g) => ("girdle", format!("{g}")),
                Place::Table(w) => ("table", format!("{w}")),
            };
            json!({"name": t.name, "angle": angle, "indices": indices.join(" "),
                "place": place, "value": value, "side": t.side.map(|s| s.name()),
                "note": t.note})
        })
        .collect();
    json!({
        "design": {"name": r.name, "gear": r.gear, "offset": r.offset, "symmetry": r.symmetry,
            "mirror": r.mirror, "index": r.index, "fractional": r.fractional,
            "title": r.title, "notes": r.notes},
        "tiers": tiers,
    })
}

/// `POST /api/recipe/infer`: the recipe of the cut the request names (a preset, a file, with
/// `set`), as `facetlab design --from` writes it: `recipe` ([`editor_json`]), `toml` (the
/// file) and `notes` (ambiguous meets, renamed tiers).
pub async fn infer_recipe(
    State(st): State<Arc<AppState>>,
    body: std::result::Result<Bytes, BytesRejection>,
) -> ApiResult<Response> {
    let r = parse_req(body, &[])?;
    let designs = st.designs.clone();
    let v = heavy(&st, move || {
        let cut = build(&designs, &r)?;
        let inferred = infer(&cut)
            .map_err(|e| ApiError::new(StatusCode::UNPROCESSABLE_ENTITY, "cut", e.to_string()))?;
        Ok(json!({
            "recipe": editor_json(&inferred.recipe),
            "toml": io::recipe::write(&inferred.recipe),
            "notes": inferred.notes,
        }))
    })
    .await?;
    Ok(no_store(axum::Json(v).into_response()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_tier_or_the_design_field() {
        let text = "[design]\nsymmetry = 8\n[[tier]]\nname = \"P1\"\nangle = -42\nindices = [96]\n";
        let e = recipe_error(io::recipe::parse(text, "recipe", "r").unwrap_err());
        assert_eq!(e.field, "tier P1", "{e:?}");
        assert!(e.message.contains("exactly one of"), "{e:?}");
        let text = "[design]\nsymmetry = 7\n[[tier]]\nname = \"P1\"\nangle = -42\nindices = [96]\ncentre = true\n";
        let r = io::recipe::parse(text, "recipe", "r").unwrap();
        let e = recipe_error(r.build().unwrap_err());
        assert_eq!(e.field, "design.symmetry", "{e:?}");
        let e = recipe_error(io::recipe::parse("[design\n", "recipe", "r").unwrap_err());
        assert_eq!(e.field, "recipe", "{e:?}");
    }

    #[test]
    fn the_editor_form_of_an_inferred_recipe_names_each_placement() {
        let cut = io::presets::load("tolkowsky").unwrap().unwrap();
        let r = infer(&cut).unwrap().recipe;
        let j = editor_json(&r);
        let tiers = j["tiers"].as_array().unwrap();
        assert_eq!(tiers.len(), r.tiers.len());
        assert_eq!(tiers[0]["place"], "centre");
        assert!(tiers.iter().any(|t| t["place"] == "meet"), "{j}");
        assert_eq!(j["design"]["gear"], r.gear);
    }
}
