//! The tier editor's endpoints as a client sees them: `POST /api/recipe/infer` writes the
//! recipe of a cut, `POST /api/recipe/build` builds a recipe's TOML text into the stone (the
//! same as the design it was inferred from), with its steps and findings; a tier that cannot
//! be cut is a 422 naming it. And the time the page waits for an update while typing.

use super::*;

/// `{"cut": TEXT, "format": "toml", "name": NAME}` for a recipe's text.
fn body(toml: &str) -> String {
    serde_json::json!({"cut": toml, "format": "toml", "name": "srb.toml"}).to_string()
}

/// The recipe of tolkowsky (a standard round brilliant) as the server infers it.
fn srb(server: &Server) -> String {
    let r = server.post("/api/recipe/infer", r#"{"cut": "tolkowsky"}"#);
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let j = r.json();
    let tiers = j["recipe"]["tiers"].as_array().unwrap();
    assert_eq!(tiers[0]["place"], "centre", "{j}");
    assert!(tiers.iter().any(|t| t["place"] == "meet"), "{j}");
    j["toml"].as_str().unwrap().to_string()
}

#[test]
fn a_recipe_builds_the_design_it_was_inferred_from() {
    let server = Server::start();
    let toml = srb(&server);
    let r = server.post("/api/recipe/build", &body(&toml));
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    assert!(
        r.header("server-timing")
            .is_some_and(|t| t.contains("build;dur=")),
        "{:?}",
        r.headers
    );
    let built = r.json();
    let cut = server.post("/api/cut", r#"{"cut": "tolkowsky"}"#).json();
    assert_eq!(built["facet_count"], cut["facet_count"]);
    let (a, b) = (
        built["volume"].as_f64().unwrap(),
        cut["volume"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-9, "{a} {b}");
    assert!(built["svg"].as_str().unwrap().contains("<svg"));
    let steps = built["steps"].as_array().unwrap();
    assert_eq!(steps[0]["instruction"], "cut to centre point", "{steps:?}");
    assert_eq!(steps.len(), toml.matches("[[tier]]").count());
    assert!(built["findings"].as_array().unwrap().is_empty(), "{built}");
    // The other endpoints take the recipe as a .toml cut: the same stone, pictured.
    let png = server.post(
        "/api/render",
        &serde_json::json!({"cut": toml, "format": "toml", "size": 64}).to_string(),
    );
    assert_eq!(png.status, 200);
    assert_eq!(png.header("content-type"), Some("image/png"));
    // A steeper pavilion changes the stone.
    let steeper = toml.replacen("angle = -40.75", "angle = -41.5", 1);
    assert_ne!(steeper, toml, "tolkowsky's pavilion mains are at 40.75°");
    let v = server.post("/api/recipe/build", &body(&steeper)).json();
    assert!(v["volume"].as_f64().unwrap() > a + 1e-4, "{v}");
}

#[test]
fn a_tier_that_cannot_be_cut_is_named() {
    let server = Server::start();
    let toml = srb(&server);
    // A tier with two placements.
    let two = toml.replacen("centre = true", "centre = true\ndepth = 1.0", 1);
    let r = server.post("/api/recipe/build", &body(&two));
    assert_eq!(r.status, 422);
    let j = r.json();
    assert_eq!(j["field"], "tier P1", "{j}");
    assert!(
        j["error"]
            .as_str()
            .unwrap()
            .starts_with("tier P1: give exactly one of"),
        "{j}"
    );
    // An index off the gear.
    let off = toml.replacen("indices = [", "indices = [96.5, ", 1);
    let j = server.post("/api/recipe/build", &body(&off)).json();
    assert_eq!(j["field"], "tier P1", "{j}");
    assert!(
        j["error"].as_str().unwrap().contains("off the 96 gear"),
        "{j}"
    );
    // The design's settings, and TOML that does not parse.
    let bad = toml.replacen("symmetry = 8", "symmetry = 7", 1);
    let j = server.post("/api/recipe/build", &body(&bad)).json();
    assert_eq!(j["field"], "design.symmetry", "{j}");
    let j = server
        .post("/api/recipe/build", &body("[design\nname = 1"))
        .json();
    assert_eq!(j["field"], "recipe", "{j}");
    // Not a recipe's text.
    let r = server.post("/api/recipe/build", r#"{"cut": "tolkowsky"}"#);
    assert_eq!(
        (r.status, r.json()["field"].clone()),
        (400, "format".into())
    );
}

/// The page's update while typing: one request to `/api/recipe/build` for the SRB recipe, as
/// the client waits for it (the median of 15), printed (docs/serve.md gives the figure).
#[test]
fn the_update_while_typing_is_timed() {
    let server = Server::start();
    let toml = srb(&server);
    let mut ms: Vec<f64> = (0..15)
        .map(|k| {
            // A different angle each time, as while typing.
            let t = toml.replacen(
                "angle = -40.75",
                &format!("angle = -{}", 40.0 + k as f64 / 10.0),
                1,
            );
            let t0 = Instant::now();
            let r = server.post("/api/recipe/build", &body(&t));
            assert_eq!(r.status, 200);
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    ms.sort_by(f64::total_cmp);
    eprintln!(
        "POST /api/recipe/build, the SRB recipe: median {:.1} ms, max {:.1} ms",
        ms[7], ms[14]
    );
    // The issue's target for the update while typing (the answer takes about 2 ms).
    assert!(ms[7] < 100.0, "{ms:?}");
}
