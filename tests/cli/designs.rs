//! Issue 23: a design the user brings, optimized over its tier angles with its meets kept;
//! `--set` on a design; a config whose free angles would open a meet is refused.

use super::{bad, ok};
use tempfile::tempdir;

/// A design config over `t.asc` (tolkowsky written to `.asc` by the test): mains and lower
/// halves free, a small budget.
const CONFIG: &str = r#"
name = "design"
seed = 2
[cut]
file = "t.asc"
[free]
pavilion-main = [40.0, 42.0]
lower-half = [41.0, 43.5]
[method]
starts = 1
max_evaluations = 12
[verify]
winners = 0
"#;

fn brilliance(dir: &std::path::Path, cut: &str, set: &[&str]) -> f64 {
    let out = dir.join("scores.json");
    let out = out.to_str().unwrap();
    let mut args = vec!["score", cut, "--json", out];
    args.extend_from_slice(set);
    ok(dir, &args);
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
    let s = if j.is_array() { &j[0] } else { &j };
    s["scores"]["brilliance"]
        .as_f64()
        .or_else(|| s["brilliance"].as_f64())
        .unwrap_or_else(|| panic!("no brilliance in {s}"))
}

#[test]
fn a_design_is_optimized_and_its_winner_reads_back_to_the_same_scores() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    ok(p, &["generate", "tolkowsky", "-o", "t.asc"]);
    std::fs::write(p.join("design.toml"), CONFIG).unwrap();
    ok(p, &["optimize", "design.toml", "--out", "run", "--quiet"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/report.json")).unwrap()).unwrap();
    assert_eq!(report["design"]["file"], "t.asc");
    assert_eq!(report["design"]["opened"], serde_json::json!([]));
    let winner = &report["winners"][0];
    let start = &report["start"];
    let (w, s) = (
        winner["scores"]["brilliance"].as_f64().unwrap(),
        start["scores"]["brilliance"].as_f64().unwrap(),
    );
    assert!(w >= s, "the winner {w} is no better than the start {s}");
    // The winner's .asc is the design on its own gear, with a footnote of what changed …
    let asc = std::fs::read_to_string(p.join("run/best.asc")).unwrap();
    assert!(
        asc.lines()
            .any(|l| l.starts_with("F Angles changed by facetlab")),
        "{asc}"
    );
    assert!(asc.contains(" n pavilion-main "), "{asc}");
    // … and scores as the run scored it.
    let again = brilliance(&p.join("run"), "best.asc", &[]);
    assert!(
        (again - w).abs() < 1e-6,
        "best.asc scores {again}, the run {w}"
    );
    // `--set` on the design reaches the same cut.
    let angle = |k: &str| winner["params"][k].as_f64().unwrap();
    let mains = format!("pavilion-main={}", angle("pavilion-main"));
    let halves = format!("lower-half={}", angle("lower-half"));
    let set = brilliance(p, "t.asc", &["--set", &mains, "--set", &halves]);
    assert!((set - w).abs() < 1e-6, "--set scores {set}, the run {w}");
    // The config written to the run folder runs again as it is.
    let used = std::fs::read_to_string(p.join("run/config.toml")).unwrap();
    assert!(used.contains("open_meets = \"refuse\""), "{used}");
}

/// A square design: four girdle facets, a flat base, a crown of two tiers A (indices 96, 48)
/// and B (24, 72) cut to the girdle's top corners and meeting at one apex.
const PYRAMID: &str = "GemCad 5.0\ng 96 0.0\ny 4 n\nI 1.54\nH meets test\n\
                       a -90.000000 0.50000000 96 24 48 72 n G\n\
                       a 40.000000 0.35969603 96 48 n A\n\
                       a 40.000000 0.35969603 24 72 n B\n\
                       a 0.000000 -0.30000000 96 n U\n";

#[test]
fn free_angles_that_open_a_meet_are_refused_naming_the_tier_and_the_meet() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    std::fs::write(p.join("pyramid.asc"), PYRAMID).unwrap();
    let config = "[cut]\nfile = \"pyramid.asc\"\n[free]\nA = [38.0, 42.0]\n";
    std::fs::write(p.join("a.toml"), config).unwrap();
    // A alone cannot keep the apex where A and B meet.
    bad(
        p,
        &["optimize", "a.toml", "--out", "run"],
        &[
            "a.toml",
            "free.A",
            "turning A alone opens the meet A·B",
            "open_meets",
        ],
    );
    assert!(!p.join("run").exists());
    // Freeing B too does not help: turned independently, A and B still open the apex.
    std::fs::write(p.join("ab.toml"), format!("{config}B = [38.0, 42.0]\n")).unwrap();
    bad(
        p,
        &[
            "sweep",
            "ab.toml",
            "--x",
            "A:40:40.5:0.5",
            "--out",
            "ab.png",
        ],
        &["ab.toml", "free.A", "A·B"],
    );
    // With open meets allowed, A alone runs and the opened meet is reported.
    let allow = "[cut]\nfile = \"pyramid.asc\"\nopen_meets = \"allow\"\n[free]\nA = [38.0, 42.0]\n[method]\nstarts = 1\nmax_evaluations = 6\n[verify]\nwinners = 0\n";
    std::fs::write(p.join("allow.toml"), allow).unwrap();
    ok(p, &["optimize", "allow.toml", "--out", "run", "--quiet"]);
    let md = std::fs::read_to_string(p.join("run/report.md")).unwrap();
    assert!(md.contains("A·B at ("), "{md}");
    assert!(md.contains("opened by A"), "{md}");
    // `--set` of A alone is refused the same way; an unknown tier names the design's tiers.
    bad(
        p,
        &["score", "pyramid.asc", "--set", "A=41"],
        &["--set A", "A·B", "open_meets"],
    );
    bad(
        p,
        &["score", "pyramid.asc", "--set", "Z=41"],
        &["--set Z", "A, B"],
    );
}
