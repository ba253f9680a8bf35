//! An optimizer run's `report.html`: the start and the winners side by side, made from what
//! the run returned ([`Config`] and [`Outcome`]), not from inside the run: the binary hands
//! [`run_page`] to the run as its [`RunPage`](crate::optimize::RunPage). Every cut shows its
//! tilt performance ([`TILTS`]); a design run (`[cut] file`) adds a section on the design: its
//! file, its meets and how many are kept, the tier angles the winners turned, and the footnote
//! each winner's `.asc` carries.

use super::{escape, html, measure_scored, CutReport, ReportOptions};
use crate::cut::Cut;
use crate::error::Result;
use crate::optimize::{design_json, Config, Outcome};
use crate::verify::Check;
use rayon::prelude::*;
use std::fmt::Write;

/// Tilts, degrees, of a run page's tilt pictures and chart.
pub const TILTS: [f64; 4] = [0.0, 10.0, 20.0, 30.0];

/// `report.html` of a run: the start and the winners side by side, scored with the run's
/// score settings, with the photon tracer's checks when the run verified, their tilt
/// performance, and (a design run) the design section.
pub fn run_page(config: &Config, outcome: &Outcome) -> Result<String> {
    let mut o = ReportOptions {
        score: config.score.score_config(),
        size: 240,
        title: format!("facetlab optimize: {}", config.name),
        tilts: TILTS.to_vec(),
        ..Default::default()
    };
    // The cuts are measured side by side and kept in candidate order.
    let cands: Vec<_> = std::iter::once(&outcome.start)
        .chain(&outcome.winners)
        .collect();
    let cuts = cands
        .par_iter()
        .map(|c| {
            let cut = config.build(&c.label, &c.params)?;
            // The run scored its start and winners in full with these settings already.
            let known = c.detail.as_deref().cloned();
            let mut r = measure_scored(&c.label, &cut, known, &o)?;
            r.checks.clear();
            if let Some(v) = &c.verification {
                r.checks = v
                    .report
                    .rows
                    .iter()
                    .filter_map(|row| {
                        let beam = row.beam?;
                        Some(Check {
                            name: row.name.clone(),
                            beam,
                            photon: row.value,
                            stderr: row.stderr,
                            z: if row.stderr > 0.0 {
                                (beam - row.value) / row.stderr
                            } else {
                                0.0
                            },
                        })
                    })
                    .collect();
            }
            Ok(r)
        })
        .collect::<Vec<Result<CutReport>>>()
        .into_iter()
        // The first error in candidate order, as when the cuts were measured in turn.
        .collect::<Result<Vec<CutReport>>>()?;
    // The checks came from the run; the page names their photons and flag (measure above
    // traced none).
    o.verify_photons = config.verify.photons;
    o.sigma = config.verify.sigma;
    if let Some(section) = design_section(config, outcome, &cuts) {
        o.sections.push(("Design".to_string(), section));
    }
    html(&cuts, &o)
}

/// The design section of a design run (`None` for a family run): the file and its meets, a
/// table of the tier angles that changed from the start to a winner (before → after), and the
/// footnote each winner's `.asc` carries. `cuts` are the start's and the winners' reports.
fn design_section(config: &Config, outcome: &Outcome, cuts: &[CutReport]) -> Option<String> {
    let d = design_json(config, outcome)?;
    let space = config.design.as_ref()?;
    let mut h = String::new();
    let kept = d.meets - d.opened.len();
    let _ = writeln!(
        h,
        "<p>File <code>{}</code>: its tier angles turned, its depths solved so that its meets stay meets. {kept} of its {} meets (found within {:e} W) kept; open meets {}.</p>",
        escape(&d.file),
        d.meets,
        d.meet_tol,
        escape(&d.open_meets)
    );
    if !d.opened.is_empty() {
        h.push_str("<p class=\"warn\">Opened meets:</p><ul>");
        for m in &d.opened {
            let gap = m
                .gap_at_best
                .map_or("?".to_string(), |g| format!("{g:.2e} W"));
            let _ = write!(
                h,
                "<li>{} (by {}): {gap} in the best cut</li>",
                escape(&m.meet),
                escape(&if m.by.is_empty() {
                    "the free tiers together".to_string()
                } else {
                    m.by.join(", ")
                })
            );
        }
        h.push_str("</ul>");
    }
    let (start, winners) = cuts.split_first()?;
    // The tiers some winner turned away from the start.
    let angle = |c: &Cut, k: &str| c.params.get(k).copied();
    let changed: Vec<&str> = config
        .space
        .keys()
        .into_iter()
        .filter(|k| {
            winners.iter().any(|w| {
                matches!((angle(&start.cut, k), angle(&w.cut, k)), (Some(a), Some(b)) if (a - b).abs() > 5e-3)
            })
        })
        .collect();
    if changed.is_empty() {
        h.push_str("<p>No winner turned a tier angle away from the start.</p>");
    } else {
        let _ = write!(
            h,
            "<h3>Tier angles turned</h3><p class=\"sub\">From the {} to each winner, degrees to the girdle plane.</p><table><tr><th>tier</th>",
            escape(&start.label)
        );
        for w in winners {
            let _ = write!(h, "<th>{}</th>", escape(&w.label));
        }
        h.push_str("</tr>");
        for k in &changed {
            let a = angle(&start.cut, k).unwrap_or(f64::NAN);
            let _ = write!(h, "<tr><th>{}</th>", escape(k));
            for w in winners {
                let b = angle(&w.cut, k).unwrap_or(f64::NAN);
                let _ = write!(
                    h,
                    "<td class=\"num\">{a:.2}° → {b:.2}° ({:+.2}°)</td>",
                    b - a
                );
            }
            h.push_str("</tr>");
        }
        h.push_str("</table>\n");
    }
    // What each winner's .asc says of the change (its footnotes beyond the design's own).
    let own = space
        .base()
        .record
        .as_ref()
        .map_or(0, |r| r.footnotes.len());
    let mut notes = String::new();
    for w in winners {
        let added: Vec<&String> = w
            .cut
            .record
            .iter()
            .flat_map(|r| r.footnotes.iter().skip(own))
            .collect();
        for f in added {
            let _ = write!(notes, "<li><b>{}</b>: {}</li>", escape(&w.label), escape(f));
        }
    }
    if !notes.is_empty() {
        let _ = write!(
            h,
            "<h3>The winners' footnotes (in their .asc)</h3><ul>{notes}</ul>"
        );
    }
    Some(h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::{search, Hooks, ScoreSet};

    /// The run config `head` (its name, cut and free parameters) in `dir`, searched by one
    /// Nelder–Mead start of `evaluations`, one winner, scored coarsely.
    fn coarse_run(dir: &std::path::Path, head: &str, evaluations: usize) -> Config {
        let toml = format!(
            "{head}\n[method]\nname = \"nelder-mead\"\nstarts = 1\nmax_evaluations = \
             {evaluations}\n[verify]\nwinners = 1\n[score]\nsplit_threshold = 1e-2\n\
             fire_split_threshold = 1e-2\nray_floor = 0.5\n"
        );
        let path = dir.join("run.toml");
        std::fs::write(&path, toml).unwrap();
        Config::load(&path).unwrap()
    }

    /// A design run (the round brilliant preset written to `.asc` by the test, two tier
    /// angles free, scored by a made-up bump with its top away from the start): the page
    /// shows the tilt chart and each cut's tilted pictures, and a Design section naming the
    /// file, the meets, the tiers the winner turned (before → after) and its footnote.
    #[test]
    fn a_design_run_page_shows_tilts_and_the_tiers_turned() {
        let dir = tempfile::tempdir().unwrap();
        let preset = crate::io::load_cut("tolkowsky").unwrap();
        std::fs::write(
            dir.path().join("round.asc"),
            crate::io::asc::write(&preset, 0),
        )
        .unwrap();
        let toml = r#"
            name = "design-page"
            [cut]
            file = "round.asc"
            [free]
            "pavilion-main" = [40.0, 41.4]
            bezel = [33.0, 36.0]
        "#;
        let config = coarse_run(dir.path(), toml, 40);
        assert!(config.design.is_some());
        // The bump's top: pavilion mains at 41.2°, bezels at 35°.
        let bump = |cut: &Cut| -> Result<ScoreSet> {
            let p = &cut.params;
            let b = (-(p["pavilion-main"] - 41.2).powi(2) - (p["bezel"] - 35.0).powi(2)).exp();
            Ok(ScoreSet::new(b, 0.0, 0.0))
        };
        let outcome = search(&config, &bump, &Hooks::default()).unwrap();
        assert!(!outcome.winners.is_empty());
        let started = std::time::Instant::now();
        let page = run_page(&config, &outcome).unwrap();
        eprintln!("run page: {:.2} s", started.elapsed().as_secs_f64());
        let cuts = 1 + outcome.winners.len();
        // The chart, one line per cut, and a row of tilted pictures per cut.
        assert!(page.contains("<h2>Tilt performance</h2>"));
        assert_eq!(page.matches("<polyline").count(), cuts);
        for t in TILTS {
            let alt = format!(
                "alt=\"{} picture tilted {t}°\"",
                crate::report::brightness_caption()
            );
            assert_eq!(page.matches(&alt).count(), cuts, "{alt}");
        }
        // Brightness, ASET, fire and four tilts per cut, each embedded.
        assert_eq!(page.matches("data:image/png;base64,").count(), 7 * cuts);
        // The design section: the file, the meets, the tiers turned and the footnote.
        assert!(page.contains("<h2>Design</h2>"));
        assert!(page.contains("<code>round.asc</code>"));
        let meets = config.design.as_ref().unwrap().meets().len();
        assert!(meets > 0);
        assert!(page.contains(&format!("{meets} of its {meets} meets")));
        let start = outcome.start.params["pavilion-main"];
        let best = &outcome.winners[0].params;
        assert!((best["pavilion-main"] - start).abs() > 0.1, "{best:?}");
        let row = format!(
            "<tr><th>pavilion-main</th><td class=\"num\">{start:.2}° → {:.2}°",
            best["pavilion-main"]
        );
        assert!(page.contains(&row), "{row}");
        assert!(page.contains("<th>bezel</th>"));
        // Tiers not free are not listed as turned.
        assert!(!page.contains("<th>lower-half</th>"));
        assert!(page.contains("Angles changed by facetlab, meets kept: "));
        std::fs::write(dir.path().join("report.html"), &page).unwrap();
        if let Ok(keep) = std::env::var("FACETLAB_KEEP_PAGE") {
            std::fs::write(keep, &page).unwrap();
        }
    }

    /// A run scored by the beam tracer hands its start's and winners' whole scores to the
    /// page: the page made from them is the page made by scoring each cut again, byte for
    /// byte, and the kept scores are the ones the run reported.
    #[test]
    fn a_run_page_reuses_the_runs_scores() {
        let dir = tempfile::tempdir().unwrap();
        let toml = r#"
            name = "reuse"
            [cut]
            family = "round-brilliant"
            [free]
            pavilion_angle = [40.0, 42.0]
        "#;
        let config = coarse_run(dir.path(), toml, 8);
        let evaluator = crate::optimize::BeamEvaluator::new(&config);
        let mut outcome = search(&config, &evaluator, &Hooks::default()).unwrap();
        for c in std::iter::once(&outcome.start).chain(&outcome.winners) {
            let kept = c.detail.as_ref().expect("the run kept its full scores");
            let reported = c.scores.as_ref().expect("scores");
            assert_eq!(
                kept.brilliance,
                reported[&crate::metrics::ScoreName::Brilliance]
            );
            assert_eq!(kept.fire, reported[&crate::metrics::ScoreName::Fire]);
            assert_eq!(
                kept.scintillation,
                reported[&crate::metrics::ScoreName::Scintillation]
            );
        }
        let kept = run_page(&config, &outcome).unwrap();
        for c in std::iter::once(&mut outcome.start).chain(&mut outcome.winners) {
            c.detail = None;
        }
        let scored = run_page(&config, &outcome).unwrap();
        assert!(kept == scored, "the pages differ");
    }
}
