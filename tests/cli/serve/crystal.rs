//! A birefringent stone in the workbench's API: the materials list each uniaxial stone's
//! default optic axis (what the page's slider starts from), the optic axis, birefringence
//! and E ∥ c colour reach the scores, and bad values are refused naming the field.

use super::*;
use serde_json::Value;

#[test]
fn serve_turns_the_optic_axis() {
    let s = Server::start();
    let p = s.get("/api/presets").json();
    let mats = p["materials"].as_array().unwrap();
    let axis = |n: &str| {
        mats.iter()
            .find(|m| m["name"] == n)
            .unwrap_or_else(|| panic!("{n} listed"))["optic_axis"]
            .clone()
    };
    // Singly refractive and biaxial stones have no slider; cutters put a sapphire's c-axis
    // perpendicular to the table and lay a tourmaline's in it.
    assert!(axis("diamond").is_null());
    assert!(axis("peridot").is_null());
    assert_eq!(axis("sapphire"), 0.0);
    assert_eq!(axis("ruby"), 0.0);
    assert_eq!(axis("tourmaline"), 90.0);

    let score = |extra: &str| {
        let r = s.post(
            "/api/score",
            &format!(r#"{{"cut": "tolkowsky", "material": "sapphire", "quick": true{extra}}}"#),
        );
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        r.json()
    };
    let brilliance = |j: &Value| j["brilliance"].as_f64().unwrap_or_else(|| panic!("{j}"));
    // The default is the material's axis, traced birefringent, and says so.
    let default = score("");
    let b = &default["settings"]["birefringence"];
    assert_eq!(b["traced"], true, "{b}");
    assert_eq!(b["optic_axis"]["tilt_deg"], 0.0, "{b}");
    // The slider's value reaches the trace: the same as the default at 0°, another stone at
    // 90° (the same solid, light split differently).
    let up = score(r#", "optic_axis": 0"#);
    assert_eq!(brilliance(&up), brilliance(&default));
    let flat = score(r#", "optic_axis": 90"#);
    assert_eq!(
        flat["settings"]["birefringence"]["optic_axis"]["tilt_deg"],
        90.0
    );
    assert!(
        (brilliance(&flat) - brilliance(&up)).abs() > 1e-6,
        "{} vs {}",
        brilliance(&flat),
        brilliance(&up)
    );
    // Birefringence off: traced with the ordinary index, whatever the axis.
    let off = score(r#", "birefringence": false"#);
    assert_eq!(off["settings"]["birefringence"]["traced"], false);
    let off90 = score(r#", "birefringence": false, "optic_axis": 90"#);
    assert_eq!(brilliance(&off), brilliance(&off90));

    // A pleochroic stone from its two colours: an E ∥ c colour darker than the E ⊥ c one
    // darkens the face-up view most when c is in the table (face-up light then runs with
    // E ∥ c half the time) and least when c is perpendicular to it (E ⊥ c only, for light
    // along the axis).
    let colour = |tilt: u32| {
        let j = score(&format!(
            r##", "colour": "#60a060@10mm", "colour_e": "#203020@10mm", "optic_axis": {tilt}"##
        ));
        assert!(
            j["settings"]["birefringence"]["colour_e"].is_string(),
            "{}",
            j["settings"]
        );
        j["colour"]["l"].as_f64().unwrap_or_else(|| panic!("{j}"))
    };
    let (l0, l90) = (colour(0), colour(90));
    assert!(l90 < l0 - 1.0, "L* {l90} at 90° vs {l0} at 0°");

    // Bad values: one line naming the field.
    let bad = |b: &str, field: &str, status: u16| score_refused(&s, b, field, status);
    let e = bad(
        r#"{"cut": "tolkowsky", "optic_axis": 30}"#,
        "optic_axis",
        422,
    );
    assert!(e.contains("uniaxial"), "says which stones: {e}");
    bad(
        r#"{"cut": "tolkowsky", "material": "sapphire", "optic_axis": 120}"#,
        "optic_axis",
        422,
    );
    bad(
        r#"{"cut": "tolkowsky", "material": "sapphire", "optic_axis": "up"}"#,
        "optic_axis",
        400,
    );
    bad(
        r#"{"cut": "tolkowsky", "material": "sapphire", "birefringence": "yes"}"#,
        "birefringence",
        400,
    );
    let e = bad(
        r#"{"cut": "tolkowsky", "material": "peridot", "birefringence": true}"#,
        "birefringence",
        422,
    );
    assert!(e.contains("biaxial"), "{e}");
    bad(
        r#"{"cut": "tolkowsky", "material": "sapphire", "colour_e": "blue"}"#,
        "colour_e",
        422,
    );
}

/// The server's stones go through the library's `StoneChoice`, as the command line's and
/// Python's: a design traced in its own uniaxial material (no `material` sent) takes the optic
/// axis and birefringence sent, as `score --optic-axis` does, and the refusals are the command
/// line's lines with the body's field for the flag.
#[test]
fn a_design_in_its_own_material_takes_the_crystal_settings() {
    let s = Server::start();
    let quartz = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/optim/quartz-brilliant.asc"
    ))
    .unwrap();
    let score = |extra: serde_json::Value| -> Value {
        let mut b = serde_json::json!({"cut": quartz, "format": "asc", "quick": true});
        for (k, v) in extra.as_object().unwrap() {
            b[k] = v.clone();
        }
        let r = s.post("/api/score", &b.to_string());
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        r.json()
    };
    let default = score(serde_json::json!({}));
    let flat = score(serde_json::json!({"optic_axis": 90}));
    let off = score(serde_json::json!({"birefringence": false}));
    let set = |j: &Value| j["settings"]["birefringence"].clone();
    assert_eq!(
        default["settings"]["material"], "quartz",
        "{}",
        default["settings"]
    );
    assert_eq!(set(&default)["traced"], true, "{}", set(&default));
    assert_eq!(set(&flat)["optic_axis"]["tilt_deg"], 90.0, "{}", set(&flat));
    assert_eq!(set(&off)["traced"], false, "{}", set(&off));
    let b = |j: &Value| j["brilliance"].as_f64().unwrap();
    assert!((b(&flat) - b(&default)).abs() > 1e-6);

    // The same refusal as the command line's, the field for the flag.
    let r = s.post(
        "/api/score",
        &serde_json::json!({"cut": quartz, "format": "asc", "optic_axis": 120}).to_string(),
    );
    let web = assert_error(&r, "optic_axis");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("q.asc"), &quartz).unwrap();
    let out = crate::cli::run_in(dir.path(), &["score", "q.asc", "--optic-axis", "120"]);
    assert_eq!(out.status.code(), Some(2));
    let cli = String::from_utf8_lossy(&out.stderr);
    let message = web.strip_prefix("optic_axis: ").unwrap();
    assert!(
        cli.contains(&format!("--optic-axis: {message}")),
        "{cli} vs {web}"
    );
}
