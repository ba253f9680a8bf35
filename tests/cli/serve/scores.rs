//! One number per name: every view that shows a score shows `score --json`'s value of it, and a
//! variant that is not that score carries its own name (render's one placement of the spot
//! lights is `placement_fire`; trace's photon count upward is the thesis's light return; the
//! server's quick scores say `quick`).

use super::Server;
use crate::cli::ok;
use serde_json::Value;

/// The numbers that follow `after` in `text` (up to the next `stop`), as written there.
fn numbers_after(text: &str, after: &str, stop: char) -> Vec<f64> {
    let i = text
        .find(after)
        .unwrap_or_else(|| panic!("{after:?} not in the text"));
    let rest = &text[i + after.len()..];
    let rest = &rest[..rest.find(stop).unwrap_or(rest.len())];
    rest.split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter(|w| !w.is_empty() && w.chars().any(|c| c.is_ascii_digit()))
        .map(|w| w.trim_matches('.').parse().unwrap())
        .collect()
}

fn close(what: &str, shown: f64, score: f64, tol: f64) {
    assert!(
        (shown - score).abs() <= tol,
        "{what}: shown {shown}, score --json {score} (tolerance {tol})"
    );
}

#[test]
fn every_view_shows_the_value_of_score_json() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    ok(d, &["score", "tolkowsky", "--json", "s.json"]);
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    // One cut: its scores at the top level (several: under `results`).
    assert!(doc.get("results").is_none(), "{doc}");
    let s = &doc;
    let num = |path: &str| -> f64 {
        path.split('.')
            .fold(s, |v, k| &v[k])
            .as_f64()
            .unwrap_or_else(|| panic!("{path} in score --json"))
    };
    let aset = ["blue", "red", "green", "leak", "port"].map(|k| num(&format!("aset.{k}")));
    assert!((aset.iter().sum::<f64>() - 1.0).abs() < 1e-9, "{aset:?}");
    assert!(
        aset[4] > 0.05,
        "the viewer's port is its own share: {aset:?}"
    );

    // The table `score` prints: the same numbers, rounded to 4 places, one name each.
    let table = ok(d, &["score", "tolkowsky"]);
    for (label, key) in [
        ("overhead light return", "overhead_light_return"),
        ("brilliance (ISO+COS)/2", "brilliance"),
        ("fire", "fire"),
        ("scintillation", "scintillation"),
        ("ASET blue", "aset.blue"),
        ("ASET port", "aset.port"),
    ] {
        let line = table
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap_or_else(|| panic!("no {label} row in:\n{table}"));
        let shown: f64 = line.split_whitespace().last().unwrap().parse().unwrap();
        close(label, shown, num(key), 5.1e-5);
    }

    // render: the face-up ISO and COS pictures' means, under the scores' head shadow (15° by
    // default; a picture's own default is none), are the face-up pose's light return,
    // the ASET picture's shares are the score's five (same port), and the fire picture's
    // number, one placement of the lights, is named so and not `fire`.
    for (light, key) in [("iso", "iso"), ("cos", "cos")] {
        let out = format!("{light}.json");
        ok(
            d,
            &[
                "render",
                "tolkowsky",
                "--light",
                light,
                "--head-shadow",
                "15",
                "--size",
                "96",
                "--quiet",
                "-o",
                &format!("{light}.png"),
                "--json",
                &out,
            ],
        );
        let j: Value =
            serde_json::from_str(&std::fs::read_to_string(d.join(&out)).unwrap()).unwrap();
        close(
            &format!("render --light {light} mean"),
            j["mean"].as_f64().unwrap(),
            s["poses"][0][key].as_f64().unwrap(),
            1e-3,
        );
    }
    let args = [
        "render",
        "tolkowsky",
        "--light",
        "aset",
        "--size",
        "96",
        "--quiet",
        "-o",
        "aset.png",
        "--json",
        "aset.json",
    ];
    let stdout = ok(d, &args);
    let j: Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("aset.json")).unwrap()).unwrap();
    for (k, v) in ["blue", "red", "green", "leak", "port"].iter().zip(aset) {
        close(
            &format!("render --light aset aset.{k}"),
            j["aset"][k].as_f64().unwrap(),
            v,
            1e-3,
        );
    }
    // Its printed line: blue and port as percentages.
    let shown = numbers_after(&stdout, "aset blue", ',');
    close("render's printed ASET blue", shown[0], 100.0 * aset[0], 0.1);
    close("render's printed ASET port", shown[4], 100.0 * aset[4], 0.1);
    // (render's fire picture names its number `placement_fire`, not `fire`: tests/cli/render.rs.)

    // trace: the photon tracer's count of photons leaving upward is the thesis's light return,
    // under its own name; no row of it is called the score's name.
    let t = ok(d, &["trace", "tolkowsky", "--photons", "20000", "--quiet"]);
    assert!(t.contains("thesis light return"), "{t}");
    assert!(!t.contains("overhead light return"), "{t}");

    // report: the score table's values, the ASET picture's shares and fire beside the
    // picture's one placement.
    ok(d, &["report", "tolkowsky", "--size", "96", "-o", "r.html"]);
    let page = std::fs::read_to_string(d.join("r.html")).unwrap();
    for key in [
        "brilliance",
        "brilliance_iso",
        "brilliance_cos",
        "fire",
        "scintillation",
        "overhead_light_return",
    ] {
        let shown = numbers_after(&page, &format!("<th>{key}</th><td class=\"num\">"), '<');
        close(&format!("report's {key}"), shown[0], num(key), 5.1e-5);
    }
    let shown = numbers_after(&page, "ASET: blue", '<');
    for (k, (x, v)) in ["blue", "red", "green", "leak", "port"]
        .iter()
        .zip(shown.iter().zip(aset))
    {
        close(&format!("report's ASET {k} %"), *x, 100.0 * v, 0.1);
    }
    let shown = numbers_after(&page, "placements: ", ')');
    close(
        "report's fire beside the fire picture",
        shown[0],
        num("fire"),
        0.0051,
    );

    // The server: the full score is `score --json`'s document, number for number; the quick
    // one says it is quick; the ASET picture's statistics are the score's shares.
    let server = Server::start();
    let full = server
        .post("/api/score", r#"{"cut": "tolkowsky", "quick": false}"#)
        .json();
    assert_eq!(full["quick"], false);
    for key in [
        "overhead_light_return",
        "brilliance",
        "brilliance_iso",
        "brilliance_cos",
        "fire",
        "scintillation",
        "aset",
        "poses",
    ] {
        assert_eq!(full[key], s[key], "server's full {key}");
    }
    let quick = server
        .post("/api/score", r#"{"cut": "tolkowsky", "quick": true}"#)
        .json();
    assert_eq!(quick["quick"], true);
    let r = server.post(
        "/api/render",
        r#"{"cut": "tolkowsky", "light": "aset", "size": 96}"#,
    );
    assert_eq!(r.status, 200);
    let st: Value = serde_json::from_str(r.header("x-facetlab-stats").unwrap()).unwrap();
    for (k, v) in ["blue", "red", "green", "leak", "port"].iter().zip(aset) {
        close(
            &format!("server's ASET picture aset.{k}"),
            st["aset"][k].as_f64().unwrap(),
            v,
            1e-3,
        );
    }
}

/// Extinction is one number: `score --json`'s `colour.extinction` is what the score table
/// prints, what `render --light iso --head-shadow 15` (face-up, the score's bands and head shadow) writes and
/// prints at any picture size (it is measured on its own grid, not the picture's pixels), and
/// what the server's full score returns. A coloured picture at another light (COS) shows its
/// share of dark outline under its own name, `dark_share`, not `extinction`.
#[test]
fn extinction_is_one_number_wherever_it_is_shown() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let stone = [
        "--material",
        "spinel",
        "--colour",
        "#1f5a36@8.5mm",
        "--size-mm",
        "9",
    ];
    let with = |args: &[&str]| -> Vec<String> {
        args.iter()
            .chain(stone.iter())
            .map(|s| s.to_string())
            .collect()
    };
    let run = |args: Vec<String>| {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        ok(d, &a)
    };
    run(with(&["score", "tolkowsky", "--json", "s.json"]));
    let read = |f: &str| -> Value {
        serde_json::from_str(&std::fs::read_to_string(d.join(f)).unwrap()).unwrap()
    };
    let s = read("s.json");
    let ext = s["colour"]["extinction"]
        .as_f64()
        .expect("colour.extinction");
    assert!(ext > 0.01 && ext < 0.99, "a dark green: {ext}");
    assert!(s["colour"].get("dark_share").is_none(), "{s}");
    let table = run(with(&["score", "tolkowsky"]));
    let row = table
        .lines()
        .find(|l| l.starts_with("extinction"))
        .unwrap_or_else(|| panic!("no extinction row in:\n{table}"));
    let shown: f64 = row.split_whitespace().last().unwrap().parse().unwrap();
    close("score's extinction row", shown, ext, 5.1e-5);

    for size in ["96", "200"] {
        let json = format!("iso-{size}.json");
        let png = format!("iso-{size}.png");
        let stdout = run(with(&[
            "render",
            "tolkowsky",
            "--light",
            "iso",
            "--head-shadow",
            "15",
            "--size",
            size,
            "--quiet",
            "-o",
            &png,
            "--json",
            &json,
        ]));
        let j = read(&json);
        assert_eq!(
            j["colour"]["extinction"].as_f64(),
            Some(ext),
            "render --light iso --size {size}: {}",
            j["colour"]
        );
        let printed = numbers_after(&stdout, "extinction ", '%');
        close(
            "render's printed extinction %",
            printed[0],
            100.0 * ext,
            0.051,
        );
    }
    let stdout = run(with(&[
        "render",
        "tolkowsky",
        "--light",
        "cos",
        "--size",
        "96",
        "--quiet",
        "-o",
        "cos.png",
        "--json",
        "cos.json",
    ]));
    let cos = read("cos.json");
    assert!(
        cos["colour"].get("extinction").is_none(),
        "{}",
        cos["colour"]
    );
    let dark = cos["colour"]["dark_share"].as_f64().expect("dark_share");
    assert!(
        (0.0..=1.0).contains(&dark) && dark != ext,
        "{dark} vs {ext}"
    );
    assert!(
        stdout.contains("dark share") && !stdout.contains("extinction"),
        "{stdout}"
    );

    let server = Server::start();
    let full = server
        .post(
            "/api/score",
            r##"{"cut": "tolkowsky", "material": "spinel", "colour": "#1f5a36@8.5mm", "diameter_mm": 9, "quick": false}"##,
        )
        .json();
    // Extinction to the bit; the colour's other figures to 1e-7 (measured: up to 1.1e-9
    // apart, 1e-10 relative: the server's colour comes through its own request path).
    assert_eq!(full["colour"]["extinction"], s["colour"]["extinction"]);
    for k in ["l", "c", "h_deg", "l_spread", "windowing"] {
        let (a, b) = (full["colour"][k].as_f64(), s["colour"][k].as_f64());
        close(
            &format!("server's colour.{k}"),
            a.unwrap(),
            b.unwrap(),
            1e-7,
        );
    }
}
