//! Body colour in the workbench's API: the material list, a user colour and a coloured
//! variety reaching the scores and the picture, and bad colour fields refused naming the field.

use super::*;

#[test]
fn serve_colours_the_stone() {
    let s = Server::start();
    // The materials, coloured varieties with their colour through the default width.
    let p = s.get("/api/presets").json();
    let mats = p["materials"].as_array().unwrap();
    let find = |n: &str| mats.iter().find(|m| m["name"] == n).cloned();
    assert!(find("diamond").unwrap()["colour"].is_null());
    let ruby = find("ruby").expect("ruby listed");
    assert!(ruby["colour"].as_str().unwrap().starts_with('#'), "{ruby}");

    // A user's colour: the scores carry the colour rows, at the stone's size.
    let body = |colour: &str, extra: &str| {
        format!(
            r#"{{"cut": "tolkowsky", "colour": "{colour}", "diameter_mm": 6.5, "quick": true{extra}}}"#
        )
    };
    let j = s.post("/api/score", &body("#2050c0@10mm", "")).json();
    let c = &j["colour"];
    for k in ["l", "c", "h_deg", "l_spread", "extinction", "windowing"] {
        assert!(c[k].as_f64().is_some(), "no colour.{k} in {j}");
    }
    assert!(
        c["c"].as_f64().unwrap() > 5.0,
        "a blue stone has chroma: {c}"
    );
    assert_eq!(j["settings"]["size_mm"]["width"], 6.5, "{}", j["settings"]);
    assert!(
        j["settings"]["colour"]["name"].is_string(),
        "{}",
        j["settings"]
    );
    // Colourless: no colour rows.
    let plain = s
        .post("/api/score", r#"{"cut": "tolkowsky", "quick": true}"#)
        .json();
    assert!(plain.get("colour").is_none(), "{plain}");
    // Darker at double density, and a bigger stone is darker too.
    let dark = s
        .post(
            "/api/score",
            &body("#2050c0@10mm", r#", "colour_density": 2"#),
        )
        .json();
    assert!(
        dark["colour"]["l"].as_f64().unwrap() < c["l"].as_f64().unwrap() - 1.0,
        "{} vs {c}",
        dark["colour"]
    );

    // The picture is in the colour asked: its mean hue follows the colour's.
    let render = |colour: &str| {
        let r = s.post(
            "/api/render",
            &format!(r#"{{"cut": "tolkowsky", "colour": "{colour}", "size": 64}}"#),
        );
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        let (mean, n) = stone_mean_rgb(&r.body);
        assert!(n > 64 * 64 / 3, "the stone fills the picture: {n} pixels");
        hue(mean)
    };
    for (colour, want) in [
        ("#2050c0@10mm", 223.0),
        ("#c03020@10mm", 5.0),
        ("#30a040@10mm", 129.0),
    ] {
        let (h, chroma) = render(colour);
        let off = ((h - want + 540.0).rem_euclid(360.0) - 180.0).abs();
        assert!(off < 30.0, "{colour}: mean hue {h:.0}° (want ~{want}°)");
        assert!(chroma > 10.0, "{colour}: chroma {chroma}");
    }
    // A coloured variety from the list: ruby is red.
    let r = s.post(
        "/api/render",
        r#"{"cut": "tolkowsky", "material": "ruby", "size": 64, "diameter_mm": 5}"#,
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    let (h, _) = hue(stone_mean_rgb(&r.body).0);
    assert!(!(60.0..300.0).contains(&h), "ruby's mean hue {h:.0}°");
    // Colourless: grey.
    let r = s.post("/api/render", r#"{"cut": "tolkowsky", "size": 64}"#);
    let (_, chroma) = hue(stone_mean_rgb(&r.body).0);
    assert!(chroma < 3.0, "a colourless stone's mean chroma {chroma}");
    // The carats follow the size and the material.
    let w = |b: &str| s.post("/api/cut", b).json()["carats"].as_f64().unwrap();
    let small = w(r#"{"cut": "tolkowsky", "diameter_mm": 6.5}"#);
    let big = w(r#"{"cut": "tolkowsky", "diameter_mm": 13}"#);
    assert!((big / small - 8.0).abs() < 1e-9, "{big} / {small}");

    // Bad colour fields: 422 (or 400 for a wrong JSON type), one line naming the field.
    let bad = |b: &str, field: &str, status: u16| score_refused(&s, b, field, status);
    let e = bad(r#"{"cut": "tolkowsky", "colour": "blue"}"#, "colour", 422);
    assert!(e.contains('#'), "says what is allowed: {e}");
    bad(r#"{"cut": "tolkowsky", "colour": 3}"#, "colour", 400);
    bad(
        r#"{"cut": "tolkowsky", "colour_density": 2}"#,
        "colour_density",
        422,
    );
    bad(
        r##"{"cut": "tolkowsky", "colour": "#2050c0", "colour_density": -1}"##,
        "colour_density",
        422,
    );
    bad(
        r#"{"cut": "tolkowsky", "material": "kryptonite"}"#,
        "material",
        422,
    );
    bad(
        r#"{"cut": "tolkowsky", "diameter_mm": 0}"#,
        "diameter_mm",
        422,
    );
    bad(r#"{"cut": "tolkowsky", "size_mm": "wide"}"#, "size_mm", 422);
    bad(
        r##"{"cut": "tolkowsky", "size_mm": "10x5", "colour": "#2050c0"}"##,
        "size_mm",
        422,
    );
    bad(
        r#"{"cut": "tolkowsky", "size_mm": "7", "diameter_mm": 7}"#,
        "size_mm",
        400,
    );
    let r = s.post(
        "/api/render",
        r#"{"cut": "tolkowsky", "colour": "lab(40, 30, -40)@0mm"}"#,
    );
    assert_error(&r, "colour");
}
