//! Issue 23: a design the user brings, optimized over its tier angles with its meets kept;
//! `--set` on a design; a config whose free angles would open a meet is refused. Issue 39:
//! GemCad's binary `.gem` wherever a design is read, tiers tied, free ranges walked.

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
pavilion-main = [40.0, 41.4]
lower-half = [41.35, 43.5]
[method]
starts = 1
max_evaluations = 12
[verify]
winners = 0
"#;

fn brilliance(dir: &std::path::Path, cut: &str, set: &[&str]) -> f64 {
    let out = dir.join("scores.json");
    let out = out.to_str().unwrap();
    let mut args = vec!["score", cut, "--json", out, "--force"];
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
            // What lists the meets, as the command line spells it.
            "(`facetlab info DESIGN --meets` lists the meets)",
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
    // `--set` of A alone is refused the same way, offering the tie (not a config key); an
    // unknown tier names the design's tiers.
    bad(
        p,
        &["score", "pyramid.asc", "--set", "A=41"],
        &["--set A", "A·B", "A+B"],
    );
    bad(
        p,
        &["score", "pyramid.asc", "--set", "Z=41"],
        &["--set Z", "A, B"],
    );
}

/// The bundled split brilliant (`optim/quartz-split.asc`): pavilion mains cut as two tiers,
/// P1 and P1b, meeting at the culet, so that neither turns alone.
fn split(dir: &std::path::Path) {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/optim/quartz-split.asc"
    ))
    .unwrap();
    std::fs::write(dir.join("split.asc"), text).unwrap();
}

/// The meets `info --meets --json` finds within `tol` (of W).
fn meets(dir: &std::path::Path, cut: &str, tol: &str) -> usize {
    let j: serde_json::Value = serde_json::from_str(&ok(
        dir,
        &["info", cut, "--meets", "--meet-tol", tol, "--json"],
    ))
    .unwrap();
    j["meets"].as_array().unwrap().len()
}

#[test]
fn a_tied_rigid_design_from_a_gem_is_optimized_brighter_with_every_meet_kept() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    split(p);
    // The design as GemCad's binary file, written by facetlab and read back.
    ok(p, &["generate", "split.asc", "-o", "split.gem"]);
    let (a, g) = (
        brilliance(p, "split.asc", &[]),
        brilliance(p, "split.gem", &[]),
    );
    assert!((a - g).abs() < 1e-9, ".asc {a}, .gem {g}");
    // Neither main tier turns alone; the refusal names the tie that does.
    bad(
        p,
        &["score", "split.gem", "--set", "P1=42"],
        &["--set P1", "P1·P1b", "tie it: `P1+P1b`"],
    );
    let together = brilliance(p, "split.gem", &["--set", "P1+P1b=-1"]);
    let equal = brilliance(p, "split.gem", &["--set", "P1=P1b=42"]);
    assert!((together - equal).abs() < 1e-12, "{together} {equal}");
    assert!(
        together > g,
        "the tie's turn moves brilliance: {g} → {together}"
    );
    // A config freeing P1 alone is refused with the tie and its bounds; the tie is optimized.
    let config = |free: &str| {
        format!("name = \"tied\"\nseed = 3\n[cut]\nfile = \"split.gem\"\n[free]\n{free}\n[method]\nstarts = 1\nmax_evaluations = 12\n[verify]\nwinners = 0\n")
    };
    std::fs::write(p.join("alone.toml"), config("P1 = [40.5, 43.7]")).unwrap();
    bad(
        p,
        &["optimize", "alone.toml", "--out", "run"],
        &[
            "free.P1",
            "turning P1 alone opens the meet P1·P1b",
            "\"P1+P1b\" = [-2.50, 0.70]",
        ],
    );
    std::fs::write(p.join("tied.toml"), config("\"P1+P1b\" = [-2.5, 0.7]")).unwrap();
    ok(p, &["optimize", "tied.toml", "--out", "run", "--quiet"]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(p.join("run/report.json")).unwrap()).unwrap();
    let (start, winner) = (&report["start"], &report["winners"][0]);
    let score = |c: &serde_json::Value| c["scores"]["brilliance"].as_f64().unwrap();
    assert!(
        score(winner) > score(start),
        "{} → {}",
        score(start),
        score(winner)
    );
    assert_eq!(winner["params"]["P1"], winner["params"]["P1b"]);
    assert_eq!(report["design"]["opened"], serde_json::json!([]));
    // The winner, written as .gem (its planes kept to 1e-12), has every meet of the design,
    // each within 1e-9 of W.
    let want = meets(p, "split.gem", "1e-4");
    assert!(want > 10, "{want} meets");
    assert_eq!(meets(&p.join("run"), "best.gem", "1e-9"), want);
    let again = brilliance(&p.join("run"), "best.gem", &[]);
    assert!(
        (again - score(winner)).abs() < 1e-6,
        "best.gem {again}, the run {}",
        score(winner)
    );
    let history = std::fs::read_to_string(p.join("run/history.csv")).unwrap();
    assert!(
        history.lines().next().unwrap().ends_with(",P1+P1b"),
        "{history}"
    );
}

#[test]
fn a_free_range_where_the_design_changes_is_refused_with_its_angle() {
    let dir = tempdir().unwrap();
    let p = dir.path();
    ok(p, &["generate", "tolkowsky", "-o", "t.gem"]);
    // Tolkowsky's mains turned alone past its lower halves' angle: the mains vanish.
    let config = "[cut]\nfile = \"t.gem\"\n[free]\npavilion-main = [40.0, 42.0]\n[method]\nstarts = 1\nmax_evaluations = 4\n[verify]\nwinners = 0\n";
    std::fs::write(p.join("wide.toml"), config).unwrap();
    let line = bad(
        p,
        &["optimize", "wide.toml", "--out", "run"],
        &[
            "free.pavilion-main: at 41.",
            "never touches",
            "holds from 40.00° to 41.",
            "facet_changes",
        ],
    );
    assert!(!p.join("run").exists(), "{line}");
    // Searched anyway when asked.
    let skip = config.replace("[free]", "facet_changes = \"skip\"\n[free]");
    std::fs::write(p.join("skip.toml"), skip).unwrap();
    ok(p, &["optimize", "skip.toml", "--out", "run", "--quiet"]);
    // A .gem cut short is one line naming the file and the byte.
    let bytes = std::fs::read(p.join("t.gem")).unwrap();
    std::fs::write(p.join("short.gem"), &bytes[..bytes.len() / 2]).unwrap();
    bad(
        p,
        &["info", "short.gem"],
        &["short.gem: byte ", "cut short"],
    );
}
