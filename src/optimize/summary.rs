//! `report.json` and `report.md`: the start and the winners side by side (free parameters,
//! proportions, every score, constraints, verification), and how the search went.
//!
//! `report.json` keys (stable):
//!
//! - `name`, `description`, `config` (the file it came from), `family`, `method`, `seed`;
//! - `free`: `[{key, min, max, start}]`; `objective`: the weights; `constraints`: the limits
//!   (absent ones `null`) and `penalty`;
//! - `search`: `evaluations`, `iterations`, `stop` (`max-iterations`, `max-evaluations`,
//!   `converged`, `interrupted`), `start_stops` (Nelder–Mead: per start), `seconds`,
//!   `evaluations_per_second`, `threads`;
//! - `verification`: `available`, `photons`, `sigma`, `seconds`, `note` (why it was skipped);
//! - `start` and `winners[]`, each a candidate: `label`, `free`, `params`, `proportions`,
//!   `weight_retention`, `scores` (by name), `weighted_score`, `penalty`, `cost`,
//!   `constraints[]` (`name`, `value`, `limit`, `violation`, `ok`), `error`, `found_at`
//!   (`track`, `iteration`, `evaluations`), `verification` (`photons`, `rows[]` of `name`,
//!   `value`, `stderr`, `beam`; `sigma`, `disagreements`, `seconds`, `error`);
//! - `files`: the files of the run folder.

use super::config::{Config, Constraints, Method, Weights};
use super::guard::Stop;
use super::problem::{weight_retention, ConstraintCheck, Evaluation};
use crate::cut::grade::GradeEstimate;
use crate::cut::Proportions;
use crate::metrics::ScoreName;
use crate::verify::Verification;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// Where in the history a winner was found.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FoundAt {
    /// Start or particle number.
    pub track: usize,
    /// Iteration.
    pub iteration: u64,
    /// Running evaluation count.
    pub evaluations: u64,
}

/// A cut in the report: the start or a winner.
#[derive(Clone, Debug, Serialize)]
pub struct Candidate {
    /// `start`, `winner 1`, …
    pub label: String,
    /// Free parameters.
    pub free: BTreeMap<String, f64>,
    /// Every family parameter.
    pub params: BTreeMap<String, f64>,
    /// Measured proportions (absent when the cut failed).
    pub proportions: Option<Proportions>,
    /// Volume over the containing upright cylinder.
    pub weight_retention: Option<f64>,
    /// Scores by name (absent when the cut failed).
    pub scores: Option<BTreeMap<ScoreName, f64>>,
    /// Σ weight · score.
    pub weighted_score: f64,
    /// Constraint penalty.
    pub penalty: f64,
    /// Cost = −weighted score + penalty.
    pub cost: f64,
    /// Constraints as measured.
    pub constraints: Vec<ConstraintCheck>,
    /// Why the cut failed, if it did.
    pub error: Option<String>,
    /// Where the search found it (winners only).
    pub found_at: Option<FoundAt>,
    /// The photon tracer's verification, when run.
    pub verification: Option<Verification>,
    /// Proportion grade estimate (round brilliants; [`crate::cut::grade`]).
    pub grade: Option<GradeEstimate>,
    /// Free parameters that ended within 1 % of their range from a bound: the optimum may
    /// lie beyond the range searched.
    pub at_bounds: Vec<AtBound>,
    /// Score names in display order (not serialised; JSON maps are sorted).
    #[serde(skip)]
    pub score_order: Vec<ScoreName>,
    /// The evaluator's whole scores of this cut ([`ScoreSet::detail`](super::ScoreSet::detail)),
    /// when it kept them. Not serialised.
    #[serde(skip)]
    pub detail: Option<std::sync::Arc<crate::metrics::Scores>>,
}

/// A free parameter at (within 1 % of its range from) one of its bounds.
#[derive(Clone, Debug, Serialize)]
pub struct AtBound {
    /// Key.
    pub key: String,
    /// Its value.
    pub value: f64,
    /// The bound it is at.
    pub bound: f64,
    /// `min` or `max`.
    pub side: &'static str,
}

/// The free parameters of `x` within 1 % of their range from a bound.
pub fn at_bounds(config: &Config, x: &[f64]) -> Vec<AtBound> {
    config
        .free
        .iter()
        .zip(x)
        .filter_map(|(f, &v)| {
            let tol = 0.01 * (f.hi - f.lo);
            if v - f.lo <= tol {
                Some(AtBound {
                    key: f.key.clone(),
                    value: v,
                    bound: f.lo,
                    side: "min",
                })
            } else if f.hi - v <= tol {
                Some(AtBound {
                    key: f.key.clone(),
                    value: v,
                    bound: f.hi,
                    side: "max",
                })
            } else {
                None
            }
        })
        .collect()
}

impl Candidate {
    /// A candidate from an evaluation.
    pub fn new(label: &str, config: &Config, e: &Evaluation, found_at: Option<FoundAt>) -> Self {
        let free = config
            .free
            .iter()
            .zip(&e.x)
            .map(|(f, v)| (f.key.clone(), *v))
            .collect();
        let all = e.scores.as_ref().map(|s| s.all()).unwrap_or_default();
        Candidate {
            label: label.to_string(),
            free,
            params: config.params_at(&e.x),
            proportions: e.cut.as_ref().map(|c| c.proportions()),
            weight_retention: e.cut.as_ref().map(weight_retention),
            scores: e.scores.as_ref().map(|_| all.iter().cloned().collect()),
            weighted_score: e.score,
            penalty: e.penalty,
            cost: e.cost,
            constraints: e.checks.clone(),
            error: e.error.clone(),
            found_at,
            verification: None,
            grade: e.cut.as_ref().and_then(crate::cut::grade::estimate),
            at_bounds: at_bounds(config, &e.x),
            score_order: all.into_iter().map(|(k, _)| k).collect(),
            detail: e.scores.as_ref().and_then(|s| s.detail.clone()),
        }
    }
}

/// A free parameter in the report.
#[derive(Clone, Debug, Serialize)]
pub struct FreeJson {
    /// Key.
    pub key: String,
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
    /// Start value.
    pub start: f64,
}

/// How the search went.
#[derive(Clone, Debug, Serialize)]
pub struct SearchJson {
    /// Evaluations.
    pub evaluations: u64,
    /// Iterations (summed over starts).
    pub iterations: u64,
    /// Why it stopped (the first interruption, else the most common reason).
    pub stop: Stop,
    /// Per Nelder–Mead start.
    pub start_stops: Vec<Stop>,
    /// Wall-clock seconds of the search.
    pub seconds: f64,
    /// Evaluations per second.
    pub evaluations_per_second: f64,
    /// Worker threads.
    pub threads: usize,
}

/// About the verification step.
#[derive(Clone, Debug, Serialize)]
pub struct VerificationJson {
    /// Whether a verifier ran.
    pub available: bool,
    /// Photons per cut and light.
    pub photons: u64,
    /// Disagreement threshold in standard errors.
    pub sigma: f64,
    /// Seconds spent verifying.
    pub seconds: f64,
    /// Why verification was skipped or cut short, if it was.
    pub note: Option<String>,
}

/// A run's summary, `report.json` (and `report.md`): not the `report` module's page.
#[derive(Clone, Debug, Serialize)]
pub struct RunReport {
    /// Run name.
    pub name: String,
    /// Free text from the config.
    pub description: Option<String>,
    /// Config file.
    pub config: String,
    /// Family.
    pub family: String,
    /// Method.
    pub method: String,
    /// Seed.
    pub seed: u64,
    /// Free parameters.
    pub free: Vec<FreeJson>,
    /// Objective weights.
    pub objective: Weights,
    /// Constraints.
    pub constraints: Constraints,
    /// The search.
    pub search: SearchJson,
    /// The verification.
    pub verification: VerificationJson,
    /// The start cut.
    pub start: Candidate,
    /// The winners, best first.
    pub winners: Vec<Candidate>,
    /// Files of the run folder.
    pub files: Vec<String>,
    /// Evaluations whose cut could not be built or scored (a design's facet that would
    /// vanish, an edge that would appear, a meet that would open; a cut the family refuses).
    pub failed: u64,
    /// The design, when the run turned a design's tier angles (`[cut] file`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<DesignJson>,
}

/// What a design run says of its design.
#[derive(Clone, Debug, Serialize)]
pub struct DesignJson {
    /// `[cut] file` as given.
    pub file: String,
    /// How many meets the design has (found within `meet_tol`).
    pub meets: usize,
    /// The tolerance (of W) the meets were found at.
    pub meet_tol: f64,
    /// `refuse` or `allow`.
    pub open_meets: String,
    /// The meets the free angles cannot keep (only when allowed).
    pub opened: Vec<OpenedJson>,
}

/// A meet the free angles cannot keep.
#[derive(Clone, Debug, Serialize)]
pub struct OpenedJson {
    /// Its tiers and point.
    pub meet: String,
    /// The free tiers that open it alone.
    pub by: Vec<String>,
    /// How far its planes are from one point in the best cut, in W.
    pub gap_at_best: Option<f64>,
}

impl RunReport {
    /// `report.json`.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
            + "\n"
    }

    /// `report.md`.
    pub fn to_markdown(&self, config: &Config) -> String {
        let mut o = String::new();
        let _ = writeln!(o, "# Optimization run: {}\n", self.name);
        if let Some(d) = &self.description {
            let _ = writeln!(o, "{d}\n");
        }
        let method = match config.method {
            Method::NelderMead(n) => format!(
                "Nelder–Mead, {} start{} ({}{}), sigmoid-mapped bounds",
                n.starts,
                if n.starts == 1 { "" } else { "s" },
                n.sampling.name(),
                if n.include_start {
                    ", start 0 = the configured start"
                } else {
                    ""
                }
            ),
            Method::ParticleSwarm(s) => format!("particle swarm, {} particles", s.particles),
        };
        let w = &self.objective;
        let _ = writeln!(
            o,
            "- config: `{}` ({} `{}`), seed {}\n- method: {method}\n- objective: score = {}·brilliance + {}·fire + {}·scintillation; cost = −score + penalties",
            self.config,
            if self.design.is_some() { "design" } else { "family" },
            self.family,
            self.seed,
            w.brilliance,
            w.fire,
            w.scintillation
        );
        if let Some(d) = &self.design {
            let kept = d.meets - d.opened.len();
            let _ = writeln!(
                o,
                "- design: `{}`, tier angles turned with the depths solved; {} of its {} meets (within {:e} W) kept{}",
                d.file,
                kept,
                d.meets,
                d.meet_tol,
                if d.opened.is_empty() { "" } else { "; opened (`open_meets = \"allow\"`):" }
            );
            for m in &d.opened {
                let gap = m
                    .gap_at_best
                    .map_or("?".to_string(), |g| format!("{g:.2e} W"));
                let by = if m.by.is_empty() {
                    "the free tiers together".to_string()
                } else {
                    m.by.join(", ")
                };
                let _ = writeln!(o, "  - {} (opened by {by}): {gap} in the best cut", m.meet);
            }
        }
        if self.failed > 0 {
            let _ = writeln!(
                o,
                "- {} of {} evaluations could not be built or scored (a design's facet would vanish, an edge appear or a meet open; a family refused the values): each cost a finite penalty",
                self.failed, self.search.evaluations
            );
        }
        let s = &self.search;
        let _ = writeln!(
            o,
            "- search: {} evaluations, {} iterations in {:.1} s ({:.1} evaluations/s on {} threads); stopped: {}",
            s.evaluations,
            s.iterations,
            s.seconds,
            s.evaluations_per_second,
            s.threads,
            s.stop.text()
        );
        let v = &self.verification;
        if v.available {
            let _ = writeln!(
                o,
                "- verification: photon tracer, {} photons per light, {:.1} s; a difference beyond {} standard errors is flagged ⚠{}",
                v.photons,
                v.seconds,
                v.sigma,
                v.note.as_ref().map(|n| format!(" ({n})")).unwrap_or_default()
            );
        } else {
            let _ = writeln!(
                o,
                "- verification: not run{}",
                v.note
                    .as_ref()
                    .map(|n| format!(" ({n})"))
                    .unwrap_or_default()
            );
        }

        let cands: Vec<&Candidate> = std::iter::once(&self.start).chain(&self.winners).collect();
        let _ = writeln!(o, "\n## Start and winners\n");
        let _ = write!(o, "| |");
        for c in &cands {
            let _ = write!(o, " {} |", c.label);
        }
        let _ = write!(o, "\n|---|");
        for _ in &cands {
            let _ = write!(o, "---:|");
        }
        o.push('\n');
        let row = |o: &mut String, name: &str, f: &dyn Fn(&Candidate) -> String| {
            let _ = write!(o, "| {name} |");
            for c in &cands {
                let _ = write!(o, " {} |", f(c));
            }
            o.push('\n');
        };
        let section = |o: &mut String, name: &str| {
            let _ = write!(o, "| **{name}** |");
            for _ in &cands {
                o.push_str(" |");
            }
            o.push('\n');
        };
        section(&mut o, "free parameters");
        for f in &config.free {
            row(&mut o, &f.label(), &|c| fmt_param(c.free[&f.key], f.unit));
        }
        section(&mut o, "proportions");
        let pr = |o: &mut String, name: &str, g: &dyn Fn(&Proportions) -> f64, pct: bool| {
            row(o, name, &|c| match &c.proportions {
                Some(p) if pct => format!("{:.1} %", 100.0 * g(p)),
                Some(p) => format!("{:.2}°", g(p)),
                None => "—".into(),
            })
        };
        pr(&mut o, "table", &|p| p.table, true);
        pr(&mut o, "crown angle", &|p| p.crown_angle, false);
        pr(&mut o, "pavilion angle", &|p| p.pavilion_angle, false);
        pr(&mut o, "crown height", &|p| p.crown_height, true);
        pr(&mut o, "pavilion depth", &|p| p.pavilion_depth, true);
        pr(&mut o, "total depth", &|p| p.total_depth, true);
        pr(&mut o, "girdle", &|p| p.girdle, true);
        row(&mut o, "weight retention", &|c| {
            c.weight_retention
                .map(|w| format!("{:.1} %", 100.0 * w))
                .unwrap_or("—".into())
        });
        if cands.iter().any(|c| c.grade.is_some()) {
            row(&mut o, "grade estimate", &|c| match &c.grade {
                Some(g) if g.limiting.is_empty() => g.estimate.name().to_string(),
                Some(g) => format!("{} ({})", g.estimate.name(), g.limiting.join(", ")),
                None => "—".into(),
            });
        }
        if cands.iter().any(|c| !c.at_bounds.is_empty()) {
            row(&mut o, "at a bound", &|c| {
                if c.at_bounds.is_empty() {
                    "—".into()
                } else {
                    c.at_bounds
                        .iter()
                        .map(|b| format!("{} at {} {}", b.key, b.side, b.bound))
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            });
        }
        section(&mut o, "scores");
        let mut names: Vec<ScoreName> = Vec::new();
        for c in &cands {
            for n in &c.score_order {
                if !names.contains(n) {
                    names.push(*n);
                }
            }
        }
        for n in &names {
            row(&mut o, n.as_str(), &|c| {
                c.scores
                    .as_ref()
                    .and_then(|s| s.get(n))
                    .map(|v| format!("{v:.4}"))
                    .unwrap_or("—".into())
            });
        }
        row(&mut o, "weighted score", &|c| {
            format!("{:.4}", c.weighted_score)
        });
        row(&mut o, "penalty", &|c| format!("{:.4}", c.penalty));
        row(&mut o, "**cost**", &|c| format!("**{:.4}**", c.cost));
        if !self.start.constraints.is_empty() {
            section(&mut o, "constraints");
            for (i, k) in self.start.constraints.iter().enumerate() {
                row(&mut o, &format!("{} {}", k.name, k.limit), &|c| {
                    c.constraints
                        .get(i)
                        .map(|k| format!("{:.4} {}", k.value, if k.ok { "✓" } else { "✗" }))
                        .unwrap_or("—".into())
                });
            }
        }
        row(&mut o, "found at", &|c| match &c.found_at {
            Some(f) => format!(
                "{} {}, iteration {}, evaluation {}",
                match config.method {
                    Method::NelderMead(_) => "start",
                    Method::ParticleSwarm(_) => "particle",
                },
                f.track,
                f.iteration,
                f.evaluations
            ),
            None => "—".into(),
        });
        if cands.iter().any(|c| c.error.is_some()) {
            row(&mut o, "error", &|c| c.error.clone().unwrap_or_default());
        }

        if cands.iter().any(|c| c.verification.is_some()) {
            let _ = writeln!(
                o,
                "\n## Verification by the photon tracer\n\nMonte Carlo value ± standard error; where the beam tracer gives the same quantity its value and the distance in standard errors (z) follow. ⚠ marks a disagreement beyond {} standard errors.\n",
                self.verification.sigma
            );
            let mut rows: Vec<String> = Vec::new();
            for c in &cands {
                if let Some(v) = &c.verification {
                    for r in &v.report.rows {
                        if !rows.contains(&r.name) {
                            rows.push(r.name.clone());
                        }
                    }
                }
            }
            let _ = write!(o, "| |");
            for c in &cands {
                let _ = write!(o, " {} |", c.label);
            }
            let _ = write!(o, "\n|---|");
            for _ in &cands {
                let _ = write!(o, "---:|");
            }
            o.push('\n');
            let sigma = self.verification.sigma;
            for name in &rows {
                row(&mut o, name, &|c| {
                    let Some(r) = c
                        .verification
                        .as_ref()
                        .and_then(|v| v.report.rows.iter().find(|r| &r.name == name))
                    else {
                        return "—".into();
                    };
                    let mut s = format!("{:.4} ± {:.4}", r.value, r.stderr);
                    if let (Some(b), Some(z)) = (r.beam, r.z()) {
                        // Signed as report.html's: (beam − photon) / stderr.
                        let z = z.copysign(b - r.value);
                        let _ = write!(s, " (beam {b:.4}, z {z:+.1})");
                        if r.disagrees(sigma) {
                            s.push_str(" ⚠");
                        }
                    }
                    s
                });
            }
            for c in &cands {
                if let Some(e) = c.verification.as_ref().and_then(|v| v.error.as_ref()) {
                    let _ = writeln!(o, "\n{}: the verifier failed: {e}", c.label);
                }
            }
            let flagged: Vec<String> = cands
                .iter()
                .filter_map(|c| {
                    let v = c.verification.as_ref()?;
                    (!v.disagreements.is_empty())
                        .then(|| format!("{}: {}", c.label, v.disagreements.join(", ")))
                })
                .collect();
            if flagged.is_empty() {
                let _ = writeln!(
                    o,
                    "\nNo disagreement between the tracers beyond {sigma} standard errors."
                );
            } else {
                let _ = writeln!(
                    o,
                    "\n**Disagreement beyond {sigma} standard errors** — {}",
                    flagged.join("; ")
                );
            }
        }

        let _ = writeln!(o, "\n## Files\n");
        for f in &self.files {
            let _ = writeln!(o, "- `{f}`");
        }
        o
    }
}

fn fmt_param(v: f64, unit: crate::cut::Unit) -> String {
    match unit {
        crate::cut::Unit::Degrees => format!("{v:.3}°"),
        crate::cut::Unit::Fraction => format!("{v:.4}"),
        _ => format!("{v}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A winner within 1 % of a bound is reported at it, on the right side; one inside is not.
    #[test]
    fn at_bounds_flags_values_near_a_bound() {
        let text = "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 36.0]\ntable = [0.5, 0.6]\n";
        let c = Config::from_str(text, "b.toml").unwrap();
        let keys: Vec<&str> = c.free.iter().map(|f| f.key.as_str()).collect();
        let x: Vec<f64> = keys
            .iter()
            .map(|k| if *k == "crown_angle" { 30.05 } else { 0.55 })
            .collect();
        let b = at_bounds(&c, &x);
        assert_eq!(b.len(), 1, "{b:?}");
        assert_eq!(
            (b[0].key.as_str(), b[0].side, b[0].bound),
            ("crown_angle", "min", 30.0)
        );
        let x: Vec<f64> = keys
            .iter()
            .map(|k| if *k == "crown_angle" { 33.0 } else { 0.5995 })
            .collect();
        let b = at_bounds(&c, &x);
        assert_eq!(b.len(), 1);
        assert_eq!((b[0].key.as_str(), b[0].side), ("table", "max"));
    }
}
