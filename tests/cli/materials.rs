//! Faceters' workflow: `facetlab materials [--json]` and `--material ri:N[:BG]`.

use super::{bad, ok};
use tempfile::tempdir;

#[test]
fn materials_json_lists_every_stone_with_its_formula_and_source() {
    let d = tempdir().unwrap();
    let j: serde_json::Value =
        serde_json::from_str(&ok(d.path(), &["materials", "--json"])).unwrap();
    let rows = j.as_array().unwrap();
    assert!(rows.len() >= 17, "{}", rows.len());
    for r in rows {
        for k in [
            "name",
            "nd",
            "dispersion",
            "formula",
            "source",
            "ordinary_ray",
            "density",
        ] {
            assert!(r.get(k).is_some(), "{k} missing in {r}");
        }
        assert!(r["nd"].as_f64().unwrap() > 1.4 && r["dispersion"].as_f64().unwrap() > 0.0);
    }
    let quartz = rows.iter().find(|r| r["name"] == "quartz").unwrap();
    // Handbook: quartz n_ω 1.544, B–G 0.013, ordinary ray.
    let nd = quartz["nd"].as_f64().unwrap();
    assert!((nd - 1.544).abs() < 0.003, "{nd}");
    assert!((quartz["dispersion"].as_f64().unwrap() - 0.013).abs() < 0.0013);
    assert_eq!(quartz["ordinary_ray"], true);
    assert!(quartz["source"].as_str().unwrap().contains("Ghosh"));
    assert!(quartz["formula"].as_str().unwrap().starts_with("Sellmeier"));
    let text = ok(d.path(), &["materials"]);
    assert!(
        text.contains("quartz") && text.contains("ordinary ray"),
        "{text}"
    );
}

#[test]
fn ri_n_bg_reaches_the_commands_and_bad_names_list_the_allowed_ones() {
    let d = tempdir().unwrap();
    let j: serde_json::Value = serde_json::from_str(&ok(
        d.path(),
        &["info", "tolkowsky", "--material", "ri:1.54:0.013", "--json"],
    ))
    .unwrap();
    assert_eq!(j["material"], "ri:1.54:0.013");
    bad(
        d.path(),
        &["info", "tolkowsky", "--material", "kryptonite"],
        &["--material", "quartz", "moissanite", "ri:N[:BG]"],
    );
    bad(
        d.path(),
        &["info", "tolkowsky", "--material", "ri:1.5:x"],
        &["--material", "BG `x` is not a number"],
    );
}

/// A small quartz design of our own (gear 80, index 1.54) with titles, notes and instructions.
const QUARTZ_STAR: &str = "GemCad 5.0
g 80 0.0
y 5 y
I 1.54
H Test Star 80
a -41.000000 0.66000000 80 n P 16 32 48 64 G Cut to a point
a -90.000000 1.00000000 80 n G 16 32 48 64 8 24 40 56 72 G Size stone
a -43.000000 0.68000000 8 n Q 24 40 56 72 G Meet P, G
a 40.000000 0.80000000 80 n A 16 32 48 64 8 24 40 56 72
a 0.000000 0.55000000 80 n T
F Leave the table polished
";

#[test]
fn a_design_is_traced_in_its_own_material_unless_told_otherwise() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("star.asc"), QUARTZ_STAR).unwrap();
    let out = super::run_in(p, &["info", "star.asc", "--json"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("traced as quartz (the design's index 1.54)"),
        "{err}"
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["material"], "quartz");
    assert_eq!(j["design"]["ri"], 1.54);
    assert_eq!(j["design"]["gear"], 80.0);
    assert_eq!(j["design"]["title"][0], "Test Star 80");
    let quartz_ct = j["carats"].as_f64().unwrap();
    // --material overrides, silently.
    let out = super::run_in(p, &["info", "star.asc", "--material", "diamond", "--json"]);
    assert!(!String::from_utf8_lossy(&out.stderr).contains("traced as"));
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["material"], "diamond");
    // Weight scales with density: diamond 3.52, quartz 2.65 g/cm³.
    let ratio = j["carats"].as_f64().unwrap() / quartz_ct;
    assert!((ratio - 3.52 / 2.65).abs() < 0.02, "{ratio}");
    // trace says which material, and uses it.
    let out = super::run_in(p, &["trace", "star.asc", "--photons", "2000"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("traced as quartz"), "{err}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("material quartz"));
    // render's record names the material the design is traced in, as info's does.
    ok(
        p,
        &[
            "render", "star.asc", "--size", "32", "--json", "r.json", "-o", "r.png",
        ],
    );
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("r.json")).unwrap()).unwrap();
    assert_eq!(j["material"], "quartz", "{j}");
    // An index without a listed stone: ri:N with generic dispersion.
    std::fs::write(p.join("t161.asc"), QUARTZ_STAR.replace("I 1.54", "I 1.61")).unwrap();
    let j: serde_json::Value =
        serde_json::from_str(&ok(p, &["info", "t161.asc", "--json"])).unwrap();
    assert_eq!(j["material"], "ri:1.61");
    // GemCad's corundum, 1.76: sapphire's ε (1.7600; its ω 1.7681 is 0.008 away), so sapphire,
    // and the note says which index it matched.
    std::fs::write(p.join("t176.asc"), QUARTZ_STAR.replace("I 1.54", "I 1.76")).unwrap();
    let out = super::run_in(p, &["info", "t176.asc", "--json"]);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("traced as sapphire (the design's index 1.76: sapphire's ε 1.7600; ω 1.768"),
        "{err}"
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["material"], "sapphire");
    // The design's record survives .asc export.
    ok(p, &["generate", "star.asc", "-o", "again.asc"]);
    assert_eq!(
        std::fs::read_to_string(p.join("again.asc")).unwrap(),
        QUARTZ_STAR
    );
}

#[test]
fn fancy_shapes_keep_their_size_through_every_format_and_info_gives_mm_and_ratios() {
    let d = tempdir().unwrap();
    let p = d.path();
    let info = |cut: &str, extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["info", cut, "--json"];
        args.extend_from_slice(extra);
        serde_json::from_str(&ok(p, &args)).unwrap()
    };
    for preset in ["marquise", "princess"] {
        let want = info(preset, &[]);
        for ext in ["asc", "obj", "stl"] {
            let file = format!("{preset}.{ext}");
            ok(p, &["generate", preset, "-o", &file]);
            let got = info(&file, &["--material", "diamond"]);
            let (a, b) = (
                want["carats"].as_f64().unwrap(),
                got["carats"].as_f64().unwrap(),
            );
            assert!((b / a - 1.0).abs() < 0.005, "{file}: {a} ct vs {b} ct");
            for (k, tol) in [
                ("total_depth", 0.002),
                ("crown_angle", 0.05),
                ("pavilion_angle", 0.05),
            ] {
                let (a, b) = (
                    want["proportions"][k].as_f64().unwrap(),
                    got["proportions"][k].as_f64().unwrap(),
                );
                assert!((a - b).abs() < tol, "{file}: {k} {a} vs {b}");
            }
        }
    }
    // The marquise preset: L/W 2, table 57 % of the width; 10 mm long is 5 mm wide.
    let j = info("marquise", &["--size-mm", "10"]);
    assert!((j["ratios"]["l_w"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    assert!((j["ratios"]["t_w"].as_f64().unwrap() - 0.57).abs() < 1e-9);
    assert!((j["size_mm"]["length"].as_f64().unwrap() - 10.0).abs() < 1e-9);
    assert!((j["size_mm"]["width"].as_f64().unwrap() - 5.0).abs() < 1e-9);
    let h_w = j["ratios"]["h_w"].as_f64().unwrap();
    assert!((j["size_mm"]["depth"].as_f64().unwrap() - 5.0 * h_w).abs() < 1e-9);
    let j2 = info("marquise", &["--size-mm", "10x5"]);
    let (a, b) = (
        j["carats"].as_f64().unwrap(),
        j2["carats"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-9, "{a} vs {b}");
    let text = ok(p, &["info", "marquise", "--size-mm", "10"]);
    assert!(
        text.contains("10.00 × 5.00 ×") && text.contains("L/W 2.000"),
        "{text}"
    );
    bad(
        p,
        &["info", "marquise", "--size-mm", "10x7"],
        &["--size-mm", "L/W", "2.000"],
    );
    bad(p, &["info", "marquise", "--size-mm", "ten"], &["--size-mm"]);
}

#[test]
fn info_lists_cutting_instructions_pavilion_first() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("star.asc"), QUARTZ_STAR).unwrap();
    let text = ok(p, &["info", "star.asc", "--instructions"]);
    assert!(
        text.contains("  Test Star 80\n")
            && text.contains(
                "GemCad design: gear 80 (offset 0), 5-fold symmetry with mirror, index 1.54"
            )
            && text.contains("note: Leave the table polished"),
        "{text}"
    );
    let pav = text.find("PAVILION").unwrap();
    let crown = text.find("CROWN").unwrap();
    assert!(pav < crown, "{text}");
    assert!(
        text.contains("gear 80 (offset 0), index 1.54")
            && text.contains("  43.00°  08-24-40-56-72  Meet P, G"),
        "{text}"
    );
    let j: serde_json::Value =
        serde_json::from_str(&ok(p, &["info", "star.asc", "--instructions", "--json"])).unwrap();
    let steps = j["instructions"]["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 5);
    assert_eq!(steps[0]["side"], "pavilion");
    assert_eq!(steps[0]["note"], "Cut to a point");
    assert_eq!(steps[4]["tier"], "T");
    // Without the flag, no instructions key.
    let j: serde_json::Value =
        serde_json::from_str(&ok(p, &["info", "star.asc", "--json"])).unwrap();
    assert!(j.get("instructions").is_none());
}

/// `retarget` adapts a diamond design to quartz: the report lists the design, the
/// tangent-ratio rule and the optimized variant, the optimized one returns at least the
/// design's light at quartz's index, and the written `.asc` carries the new index.
#[test]
fn retarget_a_diamond_design_to_quartz() {
    let d = tempdir().unwrap();
    let p = d.path();
    let out = ok(
        p,
        &[
            "retarget",
            "tolkowsky",
            "--material",
            "quartz",
            "-o",
            "q.asc",
        ],
    );
    let b = |label: &str| -> f64 {
        let line = out
            .lines()
            .find(|l| l.trim_start().starts_with(label))
            .unwrap();
        line.split_whitespace().last().unwrap().parse().unwrap()
    };
    assert!(
        b("optimized") >= b("design") && b("optimized") >= b("tangent-ratio"),
        "{out}"
    );
    let asc = std::fs::read_to_string(p.join("q.asc")).unwrap();
    assert!(asc.lines().any(|l| l.starts_with("I 1.54")), "{asc}");
    bad(p, &["retarget", "tolkowsky", "-o", "x.asc"], &["--ri"]);
    bad(
        p,
        &["retarget", "tolkowsky", "--ri", "0.5", "-o", "x.asc"],
        &["--ri"],
    );
    bad(
        p,
        &["retarget", "q.asc", "--ri", "1.7", "-o", "q.asc"],
        &["-o"],
    );
}

/// Body colour reaches `score` from a design's note and from `--colour`: the note names it
/// with the stone's width, the colourless scores stay as they are (brilliance and the rest
/// are the colourless stone's, row for row), and the face-up colour rows follow them; bad
/// colours are one-line errors.
#[test]
fn a_coloured_material_is_named_and_scored_in_colour() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("star.asc"), QUARTZ_STAR).unwrap();
    std::fs::write(
        p.join("amethyst.asc"),
        QUARTZ_STAR.replace("F Leave", "F Material: amethyst\nF Leave"),
    )
    .unwrap();
    let plain = super::run_in(p, &["score", "star.asc"]);
    let coloured = super::run_in(p, &["score", "amethyst.asc", "--diameter-mm", "8"]);
    assert!(plain.status.success() && coloured.status.success());
    let err = String::from_utf8_lossy(&coloured.stderr);
    assert!(
        err.contains("traced as amethyst (the design's notes)")
            && err.contains("stone width 8 mm")
            && !err.contains("not yet traced"),
        "{err}"
    );
    let rows = |o: &std::process::Output| {
        String::from_utf8_lossy(&o.stdout)
            .lines()
            .skip(2)
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    // The same numbers, row for row, under the material's name, then the colour's rows.
    let (plain_rows, coloured_rows) = (rows(&plain), rows(&coloured));
    assert_eq!(coloured_rows[..plain_rows.len()], plain_rows[..]);
    assert!(coloured_rows[plain_rows.len()].starts_with("colour L*"));
    assert!(!plain_rows.iter().any(|r| r.starts_with("colour")));
    assert!(String::from_utf8_lossy(&coloured.stdout).starts_with("amethyst, "));
    let out = super::run_in(p, &["score", "star.asc", "--colour", "#7a3fa0@10mm"]);
    assert!(out.status.success());
    assert_eq!(rows(&out)[..plain_rows.len()], plain_rows[..]);
    bad(
        p,
        &["score", "star.asc", "--colour", "mauve"],
        &["--colour: `mauve` is not a colour", "lab(L,a,b)"],
    );
    bad(
        p,
        &["score", "star.asc", "--colour-density", "2"],
        &["--colour-density: there is no colour to scale"],
    );
}

/// `render` draws a coloured stone in its colour: the note names the colour and width without
/// "not yet traced", the JSON has the colour statistics and the width, and a stone twice as
/// wide comes out darker.
#[test]
fn render_draws_a_coloured_stone_in_its_colour() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("star.asc"), QUARTZ_STAR).unwrap();
    let l_star = |width: &str| -> f64 {
        let json = format!("w{width}.json");
        let out = super::run_in(
            p,
            &[
                "render",
                "star.asc",
                "--material",
                "amethyst",
                "--size",
                "48",
                "--light",
                "cos",
                "--diameter-mm",
                width,
                "-o",
                &format!("w{width}.png"),
                "--json",
                &json,
            ],
        );
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{err}");
        assert!(
            err.contains(&format!("stone width {width} mm")) && !err.contains("not yet traced"),
            "{err}"
        );
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(p.join(&json)).unwrap()).unwrap();
        assert_eq!(v["width_mm"].as_f64(), Some(width.parse().unwrap()));
        v["colour"]["l"].as_f64().expect("colour statistics")
    };
    let (small, big) = (l_star("6"), l_star("12"));
    assert!(big < small, "L* {big} at 12 mm vs {small} at 6 mm");
}
