//! The trade-off between scores: `[objective] pareto = ["brilliance", "fire"]` traces the
//! non-dominated front (no other cut found is at least as good in every named score and
//! better in one) with argmin searches of weighted sums.
//!
//! **Method: weighted sums.** The weights run over an evenly spaced lattice of the simplex
//! ([`weight_grid`]: for two scores `(1, 0), (5/6, 1/6), …, (0, 1)` with the default 7
//! points); each weight vector is one ordinary search of the config (its method, budget,
//! constraints and seed). Every search's winners join one pool, and the front is the pool's
//! non-dominated cuts. Weighted sums find the convex part of the front; a concave stretch
//! between two of its points is bridged by them (the winners of nearby weights fill it in
//! partly). The scores are not rescaled: brilliance and fire are both about 0.5–1 for
//! diamond, so equal weights mean roughly equal importance.
//!
//! **Corners and knee.** The front's corners (the best cut in each score) and its knee (the
//! point nearest the ideal, every score at the front's best, after scaling each score to
//! [0, 1] over the front) are re-measured by the photon tracer, as winners are.

use super::config::{Config, ParetoSpec};
use super::evaluator::Evaluator;
use super::search::{search, Hooks};
use crate::error::Result;
use crate::io::write_atomic;
use crate::metrics::ScoreName;
use crate::verify::{Verification, Verifier};
use rayon::prelude::*;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::Path;

/// Draws `pareto.png` and `.svg`: the front and the reference cuts in the plane of the first
/// two scores.
pub type ParetoChart = fn(front: &ParetoOutcome, png: &Path, svg: &Path) -> Result<()>;

/// Weight vectors over the simplex of `k` scores with `points` steps per edge (each sums to
/// 1): every `(i₁, …, i_k)/(points − 1)` with the `i` adding up to `points − 1`.
pub fn weight_grid(k: usize, points: usize) -> Vec<Vec<f64>> {
    let d = points.max(2) - 1;
    let mut out = Vec::new();
    let mut cur = vec![0usize; k];
    fn rec(i: usize, left: usize, d: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<f64>>) {
        if i + 1 == cur.len() {
            cur[i] = left;
            out.push(cur.iter().map(|&c| c as f64 / d as f64).collect());
            return;
        }
        for c in (0..=left).rev() {
            cur[i] = c;
            rec(i + 1, left - c, d, cur, out);
        }
    }
    if k > 0 {
        rec(0, d, d, &mut cur, &mut out);
    }
    out
}

/// Indices of the non-dominated points (every coordinate to be maximised), in input order;
/// of identical points the first is kept.
pub fn non_dominated(points: &[Vec<f64>]) -> Vec<usize> {
    let dominates = |a: &[f64], b: &[f64]| {
        a.iter().zip(b).all(|(x, y)| x >= y) && a.iter().zip(b).any(|(x, y)| x > y)
    };
    (0..points.len())
        .filter(|&i| {
            !points
                .iter()
                .enumerate()
                .any(|(j, q)| dominates(q, &points[i]) || (j < i && q == &points[i]))
        })
        .collect()
}

/// One cut of the front.
#[derive(Clone, Debug, Serialize)]
pub struct FrontPoint {
    /// `weights a/b` of the search that found it, and its rank there.
    pub label: String,
    /// The weights of that search, in the order of the traded scores.
    pub weights: Vec<f64>,
    /// Free parameters.
    pub free: BTreeMap<String, f64>,
    /// Every family parameter.
    pub params: BTreeMap<String, f64>,
    /// Scores by name.
    pub scores: BTreeMap<ScoreName, f64>,
    /// `corner:SCORE` (best in that score), `knee`, or empty.
    pub roles: Vec<String>,
    /// The photon tracer's check (corners and knee, when a verifier ran).
    pub verification: Option<Verification>,
}

/// A traced trade-off.
#[derive(Clone, Debug, Serialize)]
pub struct ParetoOutcome {
    /// The traded scores.
    pub scores: Vec<ScoreName>,
    /// The front, sorted by the first score (best last).
    pub front: Vec<FrontPoint>,
    /// The bundled presets of the family, scored the same way: (name, scores).
    pub references: Vec<(String, BTreeMap<ScoreName, f64>)>,
    /// Searches run.
    pub searches: usize,
    /// Cuts evaluated in all.
    pub evaluations: u64,
    /// Seconds of the searches.
    pub seconds: f64,
}

impl ParetoOutcome {
    /// `pareto.csv`: one row per cut of the front — label, roles, the weights, the free
    /// parameters, the scores.
    pub fn to_csv(&self) -> String {
        let mut keys: Vec<String> = Vec::new();
        let mut names: Vec<ScoreName> = Vec::new();
        for p in &self.front {
            for k in p.free.keys() {
                if !keys.contains(k) {
                    keys.push(k.clone());
                }
            }
            for k in p.scores.keys() {
                if !names.contains(k) {
                    names.push(*k);
                }
            }
        }
        let mut head = vec!["label".to_string(), "roles".to_string()];
        head.extend(self.scores.iter().map(|s| format!("weight_{s}")));
        head.extend(keys.iter().cloned());
        head.extend(names.iter().map(ScoreName::to_string));
        let mut out = head.join(",") + "\n";
        for p in &self.front {
            let mut row = vec![p.label.clone(), p.roles.join(" ")];
            row.extend(p.weights.iter().map(|w| format!("{w}")));
            row.extend(
                keys.iter()
                    .map(|k| p.free.get(k).map_or(String::new(), |v| format!("{v}"))),
            );
            row.extend(
                names
                    .iter()
                    .map(|k| p.scores.get(k).map_or(String::new(), |v| format!("{v}"))),
            );
            out += &(row.join(",") + "\n");
        }
        out
    }
}

fn config_with_weights(config: &Config, spec: &ParetoSpec, w: &[f64]) -> Config {
    let mut c = config.clone();
    c.weights.brilliance = 0.0;
    c.weights.fire = 0.0;
    c.weights.scintillation = 0.0;
    for (name, &x) in spec.scores.iter().zip(w) {
        match name {
            ScoreName::Brilliance => c.weights.brilliance = x,
            ScoreName::Fire => c.weights.fire = x,
            _ => c.weights.scintillation = x,
        }
    }
    c
}

/// Trace the trade-off of `config.pareto` (see the module documentation) and write, into
/// `dir`: `pareto.csv`, `pareto.json`, `config.toml` and, with a chart, `pareto.png`/`.svg`.
pub fn run_pareto(
    config: &Config,
    evaluator: &dyn Evaluator,
    verifier: Option<&dyn Verifier>,
    dir: &Path,
    chart: Option<ParetoChart>,
    hooks: &Hooks<'_>,
) -> Result<ParetoOutcome> {
    let spec = config.pareto.clone().unwrap_or(ParetoSpec {
        scores: vec![ScoreName::Brilliance, ScoreName::Fire],
        points: 7,
    });
    let weights = weight_grid(spec.scores.len(), spec.points);
    let t = std::time::Instant::now();
    let mut pool: Vec<FrontPoint> = Vec::new();
    let mut evaluations = 0;
    let mut searches = 0;
    for w in &weights {
        if hooks
            .stop
            .is_some_and(|s| s.load(std::sync::atomic::Ordering::SeqCst))
        {
            break;
        }
        let c = config_with_weights(config, &spec, w);
        let o = search(&c, evaluator, hooks)?;
        searches += 1;
        evaluations += o.evaluations;
        let wl = w
            .iter()
            .map(|x| format!("{x:.3}"))
            .collect::<Vec<_>>()
            .join("/");
        for (i, cand) in o.winners.iter().enumerate() {
            let Some(scores) = &cand.scores else { continue };
            pool.push(FrontPoint {
                label: format!("weights {wl} #{}", i + 1),
                weights: w.clone(),
                free: cand.free.clone(),
                params: cand.params.clone(),
                scores: scores.clone(),
                roles: Vec::new(),
                verification: None,
            });
        }
    }
    let value = |p: &FrontPoint| -> Vec<f64> {
        spec.scores
            .iter()
            .map(|s| p.scores.get(s).copied().unwrap_or(f64::NEG_INFINITY))
            .collect()
    };
    let vals: Vec<Vec<f64>> = pool.iter().map(value).collect();
    let keep = non_dominated(&vals);
    let mut front: Vec<FrontPoint> = keep.iter().map(|&i| pool[i].clone()).collect();
    front.sort_by(|a, b| value(a)[0].total_cmp(&value(b)[0]));
    // Corners and knee.
    if !front.is_empty() {
        let k = spec.scores.len();
        let vals: Vec<Vec<f64>> = front.iter().map(value).collect();
        let (mut lo, mut hi) = (vec![f64::INFINITY; k], vec![f64::NEG_INFINITY; k]);
        for v in &vals {
            for d in 0..k {
                lo[d] = lo[d].min(v[d]);
                hi[d] = hi[d].max(v[d]);
            }
        }
        for (d, name) in spec.scores.iter().enumerate() {
            let best = (0..front.len())
                .max_by(|&a, &b| vals[a][d].total_cmp(&vals[b][d]))
                .unwrap_or(0);
            front[best].roles.push(format!("corner:{name}"));
        }
        let dist = |v: &[f64]| -> f64 {
            (0..k)
                .map(|d| {
                    let span = hi[d] - lo[d];
                    let x = if span > 0.0 {
                        (hi[d] - v[d]) / span
                    } else {
                        0.0
                    };
                    x * x
                })
                .sum::<f64>()
        };
        let knee = (0..front.len())
            .min_by(|&a, &b| dist(&vals[a]).total_cmp(&dist(&vals[b])))
            .unwrap_or(0);
        front[knee].roles.push("knee".into());
        if let Some(v) = verifier {
            // Corners and knee in parallel (each check is deterministic), reusing the beam
            // scores their searches computed; the first error in front order is reported.
            let mut picked: Vec<&mut FrontPoint> =
                front.iter_mut().filter(|p| !p.roles.is_empty()).collect();
            let done: Vec<Result<()>> = picked
                .par_iter_mut()
                .map(|p| {
                    let cut = config.build(&p.label, &p.params)?;
                    p.verification = Some(Verification::run_scored(
                        v,
                        &cut,
                        config.verify.photons,
                        config.seed,
                        config.verify.sigma,
                        Some(&p.scores),
                    ));
                    Ok(())
                })
                .collect();
            done.into_iter().collect::<Result<()>>()?;
        }
    }
    // The family's presets on the same axes.
    let mut references = Vec::new();
    for name in crate::io::presets::names() {
        if let Some(Ok(cut)) = crate::io::presets::load(name) {
            if cut.family.as_deref() == Some(config.space.name()) {
                if let Ok(s) = evaluator.evaluate(&cut) {
                    references.push((name.to_string(), s.all().into_iter().collect()));
                }
            }
        }
    }
    let outcome = ParetoOutcome {
        scores: spec.scores.clone(),
        front,
        references,
        searches,
        evaluations,
        seconds: t.elapsed().as_secs_f64(),
    };
    std::fs::create_dir_all(dir).map_err(|e| crate::Error::io(dir.display().to_string(), e))?;
    write_atomic(&dir.join("pareto.csv"), outcome.to_csv().as_bytes())?;
    let json = serde_json::to_string_pretty(&outcome)
        .map_err(|e| crate::Error::invalid("pareto.json", e.to_string()))?;
    write_atomic(&dir.join("pareto.json"), json.as_bytes())?;
    let used = toml::to_string(&config.as_used())
        .map_err(|e| crate::Error::invalid("config.toml", e.to_string()))?;
    write_atomic(&dir.join("config.toml"), used.as_bytes())?;
    if let Some(draw) = chart {
        draw(&outcome, &dir.join("pareto.png"), &dir.join("pareto.svg"))?;
    }
    Ok(outcome)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weight_grid_covers_the_simplex() {
        let w = weight_grid(2, 7);
        assert_eq!(w.len(), 7);
        assert_eq!(w[0], vec![1.0, 0.0]);
        assert_eq!(w[6], vec![0.0, 1.0]);
        let w3 = weight_grid(3, 4);
        assert_eq!(w3.len(), 10);
        for v in w.iter().chain(&w3) {
            assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn non_dominated_keeps_the_front() {
        let p = vec![
            vec![1.0, 0.0],
            vec![0.8, 0.5],
            vec![0.7, 0.4], // dominated by the one above
            vec![0.0, 1.0],
            vec![0.8, 0.5], // a copy
        ];
        assert_eq!(non_dominated(&p), vec![0, 1, 3]);
    }
}
