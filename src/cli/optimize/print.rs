//! The lines `facetlab optimize` prints when a run ends: the best cut, the search and its
//! verification, or a trade-off's front.

use facetlab::optimize::{Config, ParetoOutcome, RunSummary};
use std::path::Path;

/// What a trade-off (`[objective] pareto`) found, written to `dir`: the front's size and the cut
/// of each role with its scores and the photon tracer's verdict.
pub(super) fn print_front(dir: &Path, front: &ParetoOutcome) {
    println!("wrote {}/", dir.display());
    println!(
        "trade-off {}: {} searches, {} evaluations in {:.1} s; {} non-dominated cuts",
        facetlab::metrics::score_name::joined(&front.scores, " / "),
        front.searches,
        front.evaluations,
        front.seconds,
        front.front.len()
    );
    for p in front.front.iter().filter(|p| !p.roles.is_empty()) {
        let scores: Vec<String> = front
            .scores
            .iter()
            .filter_map(|k| p.scores.get(k).map(|v| format!("{k} {v:.4}")))
            .collect();
        let check = match &p.verification {
            Some(v) if v.disagreements.is_empty() && v.error.is_none() => {
                "; photon tracer agrees".to_string()
            }
            Some(v) => format!("; photon tracer DISAGREES: {}", v.disagreements.join(", ")),
            None => String::new(),
        };
        println!("  {}: {}{check}", p.roles.join(", "), scores.join(", "));
    }
}

/// What a run found: the folder, the best cut with its scores, free parameters, grade estimate
/// and parameters at a bound, the search's figures and the verification's verdict.
pub(super) fn print_run(s: &RunSummary, config: &Config) {
    let o = &s.outcome;
    let r = &s.report;
    println!("wrote {}/", s.dir.display());
    let best = o.best();
    let scores = best
        .scores
        .as_ref()
        .map(|m| {
            best.score_order
                .iter()
                .filter_map(|k| m.get(k).map(|v| format!("{k} {v:.4}")))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default();
    println!(
        "best: cost {:.4} (start {:.4}); {scores}",
        best.cost, o.start.cost
    );
    let free: Vec<String> = best
        .free
        .iter()
        .map(|(k, v)| format!("{k} = {v:.4}"))
        .collect();
    println!("      {}", free.join(", "));
    if let Some(g) = &best.grade {
        let limit = if g.limiting.is_empty() {
            String::new()
        } else {
            format!(", limited by {}", g.limiting.join(", "))
        };
        println!(
            "      grade estimate {}{limit} (published proportion ranges; not a laboratory grade)",
            g.estimate.name()
        );
    }
    for b in &best.at_bounds {
        println!(
            "      {} = {:.4} is at its {} bound {}: the optimum may lie beyond the range searched",
            b.key, b.value, b.side, b.bound
        );
    }
    println!(
        "search: {} evaluations in {:.1} s ({:.1}/s); {}",
        r.search.evaluations,
        r.search.seconds,
        r.search.evaluations_per_second,
        r.search.stop.text()
    );
    if o.verified {
        let flagged: Vec<String> = std::iter::once(&o.start)
            .chain(&o.winners)
            .filter_map(|c| {
                let v = c.verification.as_ref()?;
                (!v.disagreements.is_empty())
                    .then(|| format!("{} ({})", c.label, v.disagreements.join(", ")))
            })
            .collect();
        println!(
            "verification: {:.1} s; {}",
            o.verify_seconds,
            if flagged.is_empty() {
                format!(
                    "photon and beam tracer agree within {} standard errors",
                    config.verify.sigma
                )
            } else {
                format!(
                    "DISAGREEMENT beyond {} standard errors: {}",
                    config.verify.sigma,
                    flagged.join("; ")
                )
            }
        );
    } else if let Some(n) = &o.verify_note {
        println!("verification: {n}");
    }
}
