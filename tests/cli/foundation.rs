//! Issue 2: generate, info, presets and the bad-input contract.

use super::{bad, files, ok, run_in};
use tempfile::tempdir;

#[test]
fn info_gia_reference_shows_published_proportions() {
    let d = tempdir().unwrap();
    let j: serde_json::Value =
        serde_json::from_str(&ok(d.path(), &["info", "gia-reference", "--json"])).unwrap();
    let p = &j["proportions"];
    let close = |k: &str, v: f64, tol: f64| {
        let got = p[k].as_f64().unwrap();
        assert!((got - v).abs() < tol, "{k}: {got} vs {v}");
    };
    close("crown_height", 0.145, 0.0007);
    close("pavilion_depth", 0.430, 0.0007);
    close("total_depth", 0.600, 0.0007);
    close("table", 0.57, 1e-9);
    close("crown_angle", 34.0, 1e-9);
    close("pavilion_angle", 40.7, 1e-9);
    close("girdle", 0.025, 1e-9);
    let tier = |n: &str| {
        j["tiers"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["name"] == n)
            .unwrap()["angle"]
            .as_f64()
            .unwrap()
    };
    assert!((tier("star") - 21.1).abs() < 0.05);
    assert!((tier("upper-half") - 40.6).abs() < 0.05);
    assert!((tier("lower-half") - 41.8).abs() < 0.05);
    assert_eq!(j["facet_count"].as_u64(), Some(73));
    assert!(j["volume"].as_f64().unwrap() > 0.1);
    // A 6.5 mm round of 60 % depth weighs about one carat.
    let ct = j["carats"].as_f64().unwrap();
    assert!((0.9..1.1).contains(&ct), "{ct}");
    let text = ok(d.path(), &["info", "gia-reference"]);
    assert!(
        text.contains("14.5 %") && text.contains("43.0 %") && text.contains("60.0 %"),
        "{text}"
    );
}

/// `info` estimates a proportion grade for round brilliants and names what limits it.
#[test]
fn info_grade_estimate() {
    let d = tempdir().unwrap();
    for preset in ["gia-reference", "tolkowsky"] {
        let j: serde_json::Value =
            serde_json::from_str(&ok(d.path(), &["info", preset, "--json"])).unwrap();
        assert_eq!(j["grade"]["estimate"], "excellent", "{preset}");
        assert_eq!(j["grade"]["limiting"].as_array().map(Vec::len), Some(0));
    }
    let args = [
        "info",
        "gia-reference",
        "--set",
        "pavilion_angle=43",
        "--json",
    ];
    let j: serde_json::Value = serde_json::from_str(&ok(d.path(), &args)).unwrap();
    assert_ne!(j["grade"]["estimate"], "excellent");
    assert_eq!(j["grade"]["limiting"][0], "pavilion_angle");
    let text = ok(
        d.path(),
        &["info", "gia-reference", "--set", "pavilion_angle=43"],
    );
    assert!(
        text.contains("Grade estimate: good, limited by pavilion_angle")
            && text.contains("not a laboratory grade"),
        "{text}"
    );
    // Other shapes have no estimate.
    let j: serde_json::Value =
        serde_json::from_str(&ok(d.path(), &["info", "princess", "--json"])).unwrap();
    assert!(j.get("grade").is_none());
}

#[test]
fn generate_toml_round_trips_through_info() {
    let d = tempdir().unwrap();
    ok(
        d.path(),
        &[
            "generate",
            "tolkowsky",
            "--set",
            "crown_angle=33",
            "--set",
            "table=0.55",
            "-o",
            "t.toml",
        ],
    );
    let j: serde_json::Value =
        serde_json::from_str(&ok(d.path(), &["info", "t.toml", "--json"])).unwrap();
    assert!((j["proportions"]["crown_angle"].as_f64().unwrap() - 33.0).abs() < 1e-9);
    assert!((j["proportions"]["table"].as_f64().unwrap() - 0.55).abs() < 1e-9);
    assert_eq!(files(d.path()), vec!["t.toml".to_string()]);
}

#[test]
fn bad_input_is_one_line_exit_2_and_leaves_no_file() {
    let d = tempdir().unwrap();
    let p = d.path();
    bad(
        p,
        &["info", "nosuchcut"],
        &["nosuchcut", "unknown preset", "tolkowsky"],
    );
    bad(
        p,
        &["info", "missing.toml"],
        &["missing.toml", "no such file"],
    );
    std::fs::write(
        p.join("broken.toml"),
        "family = \"round-brilliant\"\n[params]\ntable = = 3\n",
    )
    .unwrap();
    bad(p, &["info", "broken.toml"], &["broken.toml:3"]);
    std::fs::write(
        p.join("unknown.toml"),
        "family = \"round-brilliant\"\n[params]\ntabel = 0.5\n",
    )
    .unwrap();
    bad(
        p,
        &["info", "unknown.toml"],
        &["unknown.toml", "tabel", "allowed"],
    );
    bad(
        p,
        &[
            "generate",
            "tolkowsky",
            "--set",
            "crown_angle=75",
            "-o",
            "x.toml",
        ],
        &["crown_angle", "[5, 60]"],
    );
    bad(
        p,
        &[
            "generate",
            "tolkowsky",
            "--set",
            "pavilion_angle=NaN",
            "-o",
            "x.toml",
        ],
        &["pavilion_angle", "not a number"],
    );
    bad(
        p,
        &[
            "generate",
            "tolkowsky",
            "--set",
            "table=1.2",
            "-o",
            "x.toml",
        ],
        &["table", "allowed"],
    );
    bad(
        p,
        &["generate", "tolkowsky", "--set", "star=0", "-o", "x.toml"],
        &["star", "(0, 1)"],
    );
    bad(
        p,
        &[
            "generate",
            "tolkowsky",
            "--set",
            "lower_half=1.5",
            "-o",
            "x.toml",
        ],
        &["lower_half", "(0, 1)"],
    );
    bad(
        p,
        &["generate", "tolkowsky", "--set", "crown", "-o", "x.toml"],
        &["--set", "KEY=VALUE"],
    );
    bad(
        p,
        &["generate", "tolkowsky", "-o", "x.docx"],
        &["-o", ".docx", ".obj"],
    );
    bad(
        p,
        &["generate", "tolkowsky", "-o", "nodir/x.toml"],
        &["nodir"],
    );
    // An explicit design whose table plane lies above the crown: it swallows the crown.
    let swallow = "name = \"tall table\"\n\
        [[facets]]\nname = \"table\"\nnormal = [0, 0, 1]\noffset = 0.9\n\
        [[facets]]\nname = \"c1\"\nnormal = [1, 0, 1]\noffset = 0.3\n\
        [[facets]]\nname = \"c2\"\nnormal = [-1, 0, 1]\noffset = 0.3\n\
        [[facets]]\nname = \"c3\"\nnormal = [0, 1, 1]\noffset = 0.3\n\
        [[facets]]\nname = \"c4\"\nnormal = [0, -1, 1]\noffset = 0.3\n\
        [[facets]]\nname = \"p\"\nnormal = [0, 0, -1]\noffset = 0.3\n";
    std::fs::write(p.join("swallow.toml"), swallow).unwrap();
    bad(
        p,
        &["generate", "swallow.toml", "-o", "y.toml"],
        &["swallow.toml", "table", "never touches"],
    );
    let left = files(p);
    assert!(
        !left
            .iter()
            .any(|f| f.starts_with('x') || f.starts_with('y') || f.contains(".tmp")),
        "{left:?}"
    );
}

#[test]
fn asc_round_trip_and_broken_line() {
    let d = tempdir().unwrap();
    let p = d.path();
    ok(p, &["generate", "gia-reference", "-o", "g.asc"]);
    let text = std::fs::read_to_string(p.join("g.asc")).unwrap();
    assert!(
        text.starts_with("GemCad") && text.contains("\na "),
        "{text}"
    );
    let j: serde_json::Value = serde_json::from_str(&ok(p, &["info", "g.asc", "--json"])).unwrap();
    assert_eq!(j["facet_count"].as_u64(), Some(73));
    assert!((j["proportions"]["total_depth"].as_f64().unwrap() - 0.600).abs() < 0.0007);
    assert!((j["proportions"]["crown_angle"].as_f64().unwrap() - 34.0).abs() < 1e-6);
    let broken = text.replacen("\na ", "\na x3 ", 1);
    std::fs::write(p.join("broken.asc"), broken).unwrap();
    let line = bad(
        p,
        &["generate", "broken.asc", "-o", "out.obj"],
        &["broken.asc:", "x3"],
    );
    assert!(line.contains("not a number"), "{line}");
    assert!(!files(p).iter().any(|f| f.starts_with("out")));
}

#[test]
fn mesh_and_svg_outputs_and_non_convex_mesh() {
    let d = tempdir().unwrap();
    let p = d.path();
    for ext in ["obj", "stl"] {
        let name = format!("t.{ext}");
        ok(p, &["generate", "tolkowsky", "-o", &name]);
        let j: serde_json::Value =
            serde_json::from_str(&ok(p, &["info", &name, "--json"])).unwrap();
        assert_eq!(j["facet_count"].as_u64(), Some(73), "{ext}");
        assert!(
            (j["proportions"]["total_depth"].as_f64().unwrap() - 0.612).abs() < 0.002,
            "{ext}"
        );
    }
    ok(p, &["generate", "princess", "-o", "p.svg"]);
    let svg = std::fs::read_to_string(p.join("p.svg")).unwrap();
    assert!(
        svg.starts_with("<svg") || svg.starts_with("<?xml"),
        "{}",
        &svg[..40]
    );
    assert!(svg.trim_end().ends_with("</svg>"));
    // A cube with one vertex pushed deep inside: not convex.
    let dented = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nv 0.5 0.5 0.6\n\
        f 1 2 3 4\nf 5 6 9\nf 6 7 9\nf 7 8 9\nf 8 5 9\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    std::fs::write(p.join("dented.obj"), dented).unwrap();
    bad(
        p,
        &["generate", "dented.obj", "-o", "out.toml"],
        &["dented.obj", "not convex", "%"],
    );
    assert!(!files(p).iter().any(|f| f.starts_with("out")));
}

#[test]
fn usage_errors_are_one_line_too() {
    // clap's own errors used to print seven lines (tip, usage, blank lines).
    let d = tempfile::tempdir().unwrap();
    let p = d.path();
    bad(
        p,
        &["info", "tolkowsky", "--diameter-mm", "-3"],
        &["--diameter-mm", "-3"],
    );
    bad(
        p,
        &["info", "tolkowsky", "--bogus"],
        &["--bogus", "facetlab info --help"],
    );
    bad(p, &["score"], &["<CUT>", "facetlab score --help"]);
    bad(p, &["frobnicate"], &["frobnicate"]);
    // Help and version still print in full, to stdout, and succeed.
    let help = ok(p, &["score", "--help"]);
    assert!(help.contains("--verify"), "{help}");
}

/// No-panic test of the file readers through the command line: garbage and empty files of every
/// input kind end with exit 2 and one line naming the file; every prefix of a valid file either
/// loads or ends the same way.
#[test]
fn input_files_no_panic_errors_are_one_line_naming_the_file() {
    let d = tempdir().unwrap();
    let p = d.path();
    let mut failed_prefixes = 0;
    for ext in ["toml", "asc", "obj", "stl"] {
        let junk = format!("junk.{ext}");
        std::fs::write(p.join(&junk), b"\x00\xff{[ garbage \x81\n a 1 2 x\nv 1\n").unwrap();
        bad(p, &["info", &junk], &[&junk]);
        let empty = format!("empty.{ext}");
        std::fs::write(p.join(&empty), b"").unwrap();
        bad(p, &["info", &empty], &[&empty]);
        // Prefixes of a valid file, at eight cut points.
        let good = format!("good.{ext}");
        ok(p, &["generate", "gia-reference", "-o", &good]);
        let bytes = std::fs::read(p.join(&good)).unwrap();
        for k in 1..8 {
            let cut = format!("cut{k}.{ext}");
            std::fs::write(p.join(&cut), &bytes[..bytes.len() * k / 8]).unwrap();
            let out = run_in(p, &["info", &cut]);
            if !out.status.success() {
                bad(p, &["info", &cut], &[&cut]);
                failed_prefixes += 1;
            }
        }
    }
    // Most prefixes are broken files: the error path was exercised, not skipped.
    assert!(failed_prefixes >= 8, "{failed_prefixes}");
}

#[test]
fn info_meets_lists_a_designs_meets_from_its_file() {
    // A pyramid-topped square design written here: four girdle facets, a flat base, a crown of
    // two tiers cut to the girdle's top corners and to one apex. Meets: four corners (two
    // girdle facets and two crown facets each) and the apex (four crown facets).
    let dir = tempfile::tempdir().unwrap();
    let asc = "GemCad 5.0\ng 96 0.0\ny 4 n\nI 1.54\nH meets test\n\
               a -90.000000 0.50000000 96 24 48 72 n G\n\
               a 40.000000 0.35969603 96 48 n A\n\
               a 40.000000 0.35969603 24 72 n B\n\
               a 0.000000 -0.30000000 96 n U\n";
    std::fs::write(dir.path().join("pyramid.asc"), asc).unwrap();
    let j: serde_json::Value = serde_json::from_str(&ok(
        dir.path(),
        &["info", "pyramid.asc", "--meets", "--json"],
    ))
    .unwrap();
    let meets = j["meets"].as_array().expect("meets listed");
    assert_eq!(meets.len(), 5, "{meets:?}");
    let apex: Vec<&serde_json::Value> = meets
        .iter()
        .filter(|m| m["tiers"] == serde_json::json!(["A", "B"]))
        .collect();
    assert_eq!(apex.len(), 1, "one meet of A and B alone: {meets:?}");
    for m in meets {
        assert_eq!(m["facets"].as_array().unwrap().len(), 4);
        // Depths written to 8 decimals: every meet within 1e-7 W.
        assert!(m["off"].as_f64().unwrap() < 1e-7, "{m}");
    }
    // Without the flag, no key; a tolerance out of range is one line naming the flag.
    let plain = ok(dir.path(), &["info", "pyramid.asc", "--json"]);
    assert!(!plain.contains("\"meets\""));
    bad(
        dir.path(),
        &["info", "pyramid.asc", "--meets", "--meet-tol", "0"],
        &["--meet-tol", "(0, 0.01]"],
    );
    let text = ok(dir.path(), &["info", "pyramid.asc", "--meets"]);
    assert!(
        text.contains("Meets (5 where four or more facets"),
        "{text}"
    );
}
