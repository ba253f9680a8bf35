//! Issue 53: designs written tier by tier (`facetlab design`), read by every command that
//! takes a design, inferred from a design with `--from`, and refused in a faceter's words.

use super::{bad, files, ok, run_in};
use tempfile::tempdir;

/// A small brilliant for quartz as a faceter writes it.
const RECIPE: &str = r#"
[design]
name = "Test brilliant"
symmetry = 8
mirror = true
index = 1.54

[[tier]]
name = "P1"
angle = -42.5
indices = [3]
centre = true

[[tier]]
name = "G1"
angle = 90
indices = "3"
scale = 1.0

[[tier]]
name = "P2"
angle = "=P1-1"
side = "pavilion"
indices = "96"
meet = ["P1", "G1"]

[[tier]]
name = "C1"
angle = 34
indices = "3:6:93"
girdle = 0.03

[[tier]]
name = "T"
angle = 0
table = 0.55
"#;

fn json(dir: &std::path::Path, args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(dir, args)).unwrap()
}

#[test]
fn a_recipe_builds_and_every_command_reads_it() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    std::fs::write(p.join("r.toml"), RECIPE).unwrap();
    ok(p, &["design", "r.toml", "-o", "r.asc"]);
    let asc = std::fs::read_to_string(p.join("r.asc")).unwrap();
    assert!(
        asc.contains("G cut to centre point") && asc.contains("G meet P1-G1"),
        "{asc}"
    );
    // The recipe and the design written from it are one stone.
    let a = json(p, &["info", "r.toml", "--json"]);
    let b = json(p, &["info", "r.asc", "--json"]);
    // (The .asc file's distances have 8 decimals.)
    assert_eq!(a["facet_count"], b["facet_count"]);
    let (va, vb) = (a["volume"].as_f64().unwrap(), b["volume"].as_f64().unwrap());
    assert!((va / vb - 1.0).abs() < 1e-6, "{va} {vb}");
    let t_w = a["ratios"]["t_w"].as_f64().unwrap();
    assert!((t_w - 0.55).abs() < 1e-6, "{t_w}");
    ok(p, &["render", "r.toml", "-o", "r.png", "--size", "24"]);
    // `--set` turns a tier as the recipe places it: the halves (=P1-1) follow the mains.
    let set = json(p, &["info", "r.toml", "--set", "P1=43", "--json"]);
    let tier = |n: &str| {
        set["tiers"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["name"] == n)
            .unwrap()["angle"]
            .as_f64()
            .unwrap()
    };
    assert!(
        (tier("P1") - 43.0).abs() < 1e-9 && (tier("P2") - 42.0).abs() < 1e-9,
        "{set}"
    );
    bad(
        p,
        &["info", "r.toml", "--set", "P2=40"],
        &["--set P2", "not a free tier"],
    );
    // Its cutting sheet: the recipe's order and instructions, depths in mm at a size.
    ok(p, &["sheet", "r.toml", "--diameter-mm", "8", "-o", "s.svg"]);
    let svg = std::fs::read_to_string(p.join("s.svg")).unwrap();
    let at = |t: &str| {
        svg.find(t)
            .unwrap_or_else(|| panic!("{t} not on the sheet"))
    };
    assert!(at("cut to centre point") < at("meet P1-G1"));
    assert!(at("meet P1-G1") < at("leave a girdle of 3.00 % of the width"));
    assert!(at("leave a girdle") < at("cut the table to 55.00 % of the width"));
}

#[test]
fn from_a_design_and_back_is_the_same_stone_with_the_same_scores() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    ok(p, &["design", "--from", "tolkowsky", "-o", "t.toml"]);
    let text = std::fs::read_to_string(p.join("t.toml")).unwrap();
    assert!(
        text.contains("centre = true") && text.contains("meet = "),
        "{text}"
    );
    let a = json(p, &["info", "t.toml", "--json"]);
    let b = json(p, &["info", "tolkowsky", "--json"]);
    assert_eq!(a["facet_count"], b["facet_count"]);
    let (va, vb) = (a["volume"].as_f64().unwrap(), b["volume"].as_f64().unwrap());
    assert!((va - vb).abs() < 1e-9, "{va} {vb}");
    let score = |cut: &str| {
        ok(p, &["score", cut, "--json", "s.json", "--force"]);
        let j: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(p.join("s.json")).unwrap()).unwrap();
        let s = if j.is_array() { &j[0] } else { &j };
        s["scores"]["brilliance"]
            .as_f64()
            .or_else(|| s["brilliance"].as_f64())
            .unwrap_or_else(|| panic!("no brilliance in {s}"))
    };
    let (sa, sb) = (score("t.toml"), score("tolkowsky"));
    assert!((sa - sb).abs() < 1e-9, "{sa} {sb}");
}

#[test]
fn a_bad_recipe_is_one_line_naming_the_file_and_the_tier() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    let case = |text: &str, needles: &[&str]| {
        std::fs::write(p.join("bad.toml"), text).unwrap();
        bad(p, &["design", "bad.toml", "-o", "out.asc"], needles);
        assert!(!p.join("out.asc").exists());
    };
    case(
        &RECIPE.replace("indices = \"96\"", "indices = \"6.5\""),
        &["bad.toml", "tier P2", "off the 96 gear"],
    );
    case(
        &RECIPE.replace("meet = [\"P1\", \"G1\"]", "meet = [\"P1\", \"C1\"]"),
        &[
            "bad.toml",
            "tier P2",
            "C1, which is not a tier cut before P2",
        ],
    );
    case(
        &RECIPE.replace("girdle = 0.03", "girdle = 0.03\ndepth = 1"),
        &["bad.toml", "tier C1", "exactly one of"],
    );
    case(
        &RECIPE.replace("table = 0.55", "table = 0.55\ncolour = 1"),
        &["bad.toml", "tier T", "unknown key `colour`"],
    );
    case(
        &RECIPE.replace("angle = \"=P1-1\"", "angle = \"=Q1-1\""),
        &["tier P2", "Q1"],
    );
    let open = &RECIPE[..RECIPE.find("[[tier]]\nname = \"C1\"").unwrap()];
    case(open, &["bad.toml", "open above"]);
    // A pavilion below quartz's critical angle: refused, with the fix; written with --lenient.
    let leaky = RECIPE.replace("angle = -42.5", "angle = -38");
    std::fs::write(p.join("leak.toml"), &leaky).unwrap();
    bad(
        p,
        &["design", "leak.toml", "-o", "out.asc"],
        &[
            "tier P1",
            "critical angle",
            "steepen P1 to 40.5°",
            "--lenient",
        ],
    );
    let out = run_in(p, &["design", "leak.toml", "-o", "out.asc", "--lenient"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("warning: tier P1"));
    // The recipe is an input: never replaced, even with --force; --from writes only a recipe.
    bad(
        p,
        &["design", "leak.toml", "-o", "leak.toml", "--force"],
        &["leak.toml"],
    );
    bad(
        p,
        &["design", "--from", "tolkowsky", "-o", "t.asc"],
        &["--from writes a recipe"],
    );
    bad(p, &["design", "-o", "t.asc"], &["RECIPE"]);
    assert!(
        files(p).iter().all(|f| !f.contains(".tmp")),
        "{:?}",
        files(p)
    );
}

/// A recipe optimized with its tiers free keeps its own placements: the winner's pavilion
/// halves are still one degree flatter than its mains (`=P1-1`) and still meet P1-G1.
#[test]
fn a_recipe_is_optimized_with_its_own_meets() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    std::fs::write(p.join("r.toml"), RECIPE).unwrap();
    std::fs::write(
        p.join("opt.toml"),
        "name = \"r\"\nseed = 1\n[cut]\nfile = \"r.toml\"\n[free]\nP1 = [40.6, 43.5]\nC1 = [30.0, 40.0]\n\
         [method]\nstarts = 1\nmax_evaluations = 8\n[verify]\nwinners = 0\n",
    )
    .unwrap();
    ok(p, &["optimize", "opt.toml", "--out", "run", "--quiet"]);
    let asc = std::fs::read_to_string(p.join("run/best.asc")).unwrap();
    let angle = |name: &str| -> f64 {
        let line = asc
            .lines()
            .find(|l| l.contains(&format!(" n {name} ")))
            .unwrap_or_else(|| panic!("{name} in {asc}"));
        line.split_whitespace().nth(1).unwrap().parse().unwrap()
    };
    assert!((angle("P2") - (angle("P1") + 1.0)).abs() < 1e-5, "{asc}");
    assert!(asc.contains("G meet P1-G1"), "{asc}");
    // A recipe's meets are its own: the design-only keys are refused.
    std::fs::write(
        p.join("bad.toml"),
        "name = \"r\"\n[cut]\nfile = \"r.toml\"\nopen_meets = \"allow\"\n[free]\nP1 = [40.6, 43.5]\n",
    )
    .unwrap();
    super::bad(
        p,
        &["optimize", "bad.toml", "--out", "run2"],
        &["cut.open_meets", "recipe keeps its own meets"],
    );
}
