//! The workbench's first picture shows the stone's pattern, not a near-uniform disc: the light,
//! head shadow and exposure the page opens on (read from page.js and the light table it is
//! served, so the test follows the page)
//! give tolkowsky a picture whose pixels spread widely, where the old opening (ISO at exposure
//! 0.7) was a nearly even grey disc. And every stone says the material it is traced in.

use super::*;

/// `NAME: VALUE` or `NAME = VALUE` of page.js, as written (the first occurrence).
fn page_value(js: &str, name: &str) -> String {
    let at = js
        .find(name)
        .unwrap_or_else(|| panic!("page.js has no {name}"));
    let rest = &js[at + name.len()..];
    let rest = rest.trim_start_matches([' ', ':', '=']);
    rest[..rest.find([',', ';', '\n']).unwrap()]
        .trim()
        .trim_matches('\'')
        .to_string()
}

/// The standard deviation of the luminance (0–255 sRGB, Rec. 709 weights) of a PNG's stone
/// pixels (those that differ from the corner's ground), and their mean.
fn stone_spread(b: &[u8]) -> (f64, f64) {
    let mut reader = png::Decoder::new(std::io::Cursor::new(b))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let px: Vec<&[u8]> = buf[..info.buffer_size()].chunks(3).collect();
    let ground = px[0];
    let y: Vec<f64> = px
        .iter()
        .filter(|p| *p != &ground)
        .map(|p| 0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64)
        .collect();
    assert!(y.len() > b.len() / 100, "a stone in the picture");
    let mean = y.iter().sum::<f64>() / y.len() as f64;
    let var = y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / y.len() as f64;
    (var.sqrt(), mean)
}

#[test]
fn the_workbench_opens_on_a_picture_with_contrast() {
    let js = include_str!("../../../src/cli/serve/page.js");
    let light = page_value(js, "const FIRST_LIGHT");
    let head = page_value(js, "headShadow");
    // The exposure the page starts the light at: its entry of the presets' light table.
    let s = Server::start();
    let table = s.get("/api/presets").json()["light_table"].clone();
    let exposure = table
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["name"] == light.as_str())
        .unwrap_or_else(|| panic!("{light} in {table}"))["exposure"]
        .as_f64()
        .unwrap();
    let first = s.post(
        "/api/render",
        &format!(
            r#"{{"cut": "tolkowsky", "light": "{light}", "head_shadow": {head}, "exposure": {exposure}, "size": 192}}"#
        ),
    );
    assert_eq!(
        first.status,
        200,
        "{}",
        String::from_utf8_lossy(&first.body)
    );
    let old = s.post(
        "/api/render",
        r#"{"cut": "tolkowsky", "light": "iso", "exposure": 0.7, "size": 192}"#,
    );
    assert_eq!(old.status, 200);
    let (spread, mean) = stone_spread(&first.body);
    let (old_spread, old_mean) = stone_spread(&old.body);
    eprintln!(
        "first picture ({light}, head shadow {head}°, exposure {exposure}): luminance {mean:.1} ± {spread:.1}; \
         ISO at 0.7: {old_mean:.1} ± {old_spread:.1}"
    );
    // The pattern shows: dark and bright facets, not one grey, and neither black nor white.
    assert!(spread > 40.0, "a near-uniform disc: spread {spread:.1}");
    assert!(
        spread > 1.5 * old_spread,
        "{spread:.1} against {old_spread:.1}"
    );
    assert!((40.0..215.0).contains(&mean), "mean luminance {mean:.1}");
}

#[test]
fn each_stone_names_the_material_it_is_traced_in() {
    let s = Server::start();
    let quartz = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/optim/quartz-brilliant.asc"
    ))
    .unwrap();
    let body =
        |text: &str| serde_json::json!({"cut": text, "format": "asc", "name": "q"}).to_string();
    let info = |text: &str| -> serde_json::Value {
        let r = s.post("/api/cut", &body(text));
        assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
        serde_json::from_slice(&r.body).unwrap()
    };
    assert_eq!(info(&quartz)["material"], "quartz");
    // GemCad's corundum index is sapphire's ε.
    let corundum = quartz.replace("\nI 1.544", "\nI 1.76");
    assert_ne!(corundum, quartz, "the design has an I 1.544 line");
    assert_eq!(info(&corundum)["material"], "sapphire");
    // A preset in diamond; a material sent wins.
    let r = s.post("/api/cut", r#"{"cut": "tolkowsky"}"#);
    let j: serde_json::Value = serde_json::from_slice(&r.body).unwrap();
    assert_eq!(j["material"], "diamond");
    let sent = serde_json::json!({"cut": quartz, "format": "asc", "material": "spinel"});
    let r = s.post("/api/cut", &sent.to_string());
    let j: serde_json::Value = serde_json::from_slice(&r.body).unwrap();
    assert_eq!(j["material"], "spinel");
}
