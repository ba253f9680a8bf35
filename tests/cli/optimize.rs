//! Issue 5: a short optimization on the real objective (beam-tracer brilliance), verified by
//! the photon tracer, writes every file and improves on its start.

use super::{bad, ok};
use tempfile::tempdir;

const CONFIG: &str = r#"
name = "short"
seed = 3
[cut]
family = "round-brilliant"
[cut.params]
table = 0.57
crown_angle = 36.0
pavilion_angle = 42.0
[free]
crown_angle = [30.0, 38.0]
pavilion_angle = [39.5, 42.5]
[objective]
brilliance = 1.0
[method]
name = "nelder-mead"
starts = 2
max_evaluations = 24
[verify]
winners = 1
photons = 4000
"#;

#[test]
fn short_real_run_improves_and_writes_every_file() {
    let d = tempdir().unwrap();
    let p = d.path();
    std::fs::write(p.join("short.toml"), CONFIG).unwrap();
    ok(p, &["optimize", "short.toml", "--out", "run", "--quiet"]);
    let run = p.join("run");
    for f in [
        "config.toml",
        "history.csv",
        "convergence.png",
        "convergence.svg",
        "best.toml",
        "best.asc",
        "best.obj",
        "best.svg",
        "report.md",
        "report.json",
        "report.html",
    ] {
        let meta = std::fs::metadata(run.join(f)).unwrap_or_else(|_| panic!("{f} missing"));
        assert!(meta.len() > 0, "{f} is empty");
    }
    // The HTML report shows the start and the winners, each with its pictures.
    let page = std::fs::read_to_string(run.join("report.html")).unwrap();
    assert!(page.contains("<h2>start</h2>") && page.contains("<h2>winner 1</h2>"));
    assert!(page.matches("data:image/png;base64,").count() >= 6);
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(run.join("report.json")).unwrap()).unwrap();
    let start = j["start"]["cost"].as_f64().unwrap();
    let best = j["winners"][0]["cost"].as_f64().unwrap();
    assert!(best < start - 1e-3, "best {best} vs start {start}");
    // The search left out what the objective does not weigh, but the reported cuts carry
    // every score.
    for c in std::iter::once(&j["start"]).chain(j["winners"].as_array().unwrap()) {
        for k in [
            "brilliance",
            "fire",
            "scintillation",
            "overhead_light_return",
        ] {
            let v = c["scores"][k].as_f64();
            assert!(v.is_some_and(|v| v > 0.0 && v.is_finite()), "{k}: {v:?}");
        }
    }
    // The winner was re-scored by the photon tracer, with beam values beside the estimates.
    let rows = j["winners"][0]["verification"]["rows"].as_array().unwrap();
    assert!(rows
        .iter()
        .any(|r| r["name"] == "brilliance_mc" && r["beam"].is_number()));
    // The best cut file is a valid cut of the family.
    let info: serde_json::Value =
        serde_json::from_str(&ok(&run, &["info", "best.toml", "--json"])).unwrap();
    assert_eq!(info["family"], "round-brilliant");
    // A bad config names the field.
    std::fs::write(
        p.join("bad.toml"),
        CONFIG.replace("crown_angle = [30.0, 38.0]", "crown_angle = [38.0, 30.0]"),
    )
    .unwrap();
    bad(
        p,
        &["optimize", "bad.toml", "--out", "run2"],
        &["bad.toml", "free.crown_angle"],
    );
    assert!(!p.join("run2").exists());
}

/// The fire and brilliance a one-cell sweep reports for `CONFIG` with `score` as its
/// `[score]` section.
fn swept_scores(p: &std::path::Path, tag: &str, score: &str) -> (f64, f64) {
    std::fs::write(
        p.join(format!("{tag}.toml")),
        format!("{CONFIG}\n[score]\n{score}\n"),
    )
    .unwrap();
    ok(
        p,
        &[
            "sweep",
            &format!("{tag}.toml"),
            "--x",
            "crown_angle:34:35:1",
            "--y",
            "pavilion_angle:40.8:41.8:1",
            "--out",
            &format!("{tag}.png"),
            "--quiet",
        ],
    );
    let csv = std::fs::read_to_string(p.join(format!("{tag}.csv"))).unwrap();
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    let col = |k: &str| row[head.iter().position(|h| *h == k).unwrap()];
    (col("brilliance"), col("fire"))
}

#[test]
fn score_section_reaches_the_scorer() {
    // Trust issue: `optimize`/`sweep` used to score with diamond whatever `[score]` said.
    let d = tempdir().unwrap();
    let p = d.path();
    let (b_diamond, f_diamond) = swept_scores(p, "diamond", "");
    let (b_fixed, f_fixed) = swept_scores(p, "fixed", "ri = 1.54");
    let (_, f_cz) = swept_scores(p, "cz", "material = \"cubic-zirconia\"");
    assert!(f_diamond > 0.1, "diamond fire {f_diamond}");
    assert!(
        f_fixed.abs() < 1e-12,
        "a fixed index has no dispersion: fire {f_fixed}"
    );
    assert!(
        (b_fixed - b_diamond).abs() > 0.01,
        "{b_fixed} vs {b_diamond}"
    );
    assert!(f_cz > f_diamond, "CZ fire {f_cz} vs diamond {f_diamond}");
}
