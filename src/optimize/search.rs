//! A search and its winners: run the configured method, pick distinct winners from the
//! history, score the start and the winners with every score, and (optionally) have the photon
//! tracer check them. Nothing here writes files: the run folder is `run.rs`'s.
//!
//! Ctrl-C (the stop flag in [`Hooks`]) ends the search after the current iteration; the
//! winners are still scored, and the check is skipped (and says so).

use super::config::{Config, Method, SearchBox};
use super::evaluator::Evaluator;
use super::guard::{Progress, Stop, Tracker};
use super::history::History;
use super::nelder_mead::MultiStart;
use super::problem::{Objective, FAILED_COST};
use super::pso::Swarm;
use super::summary::{Candidate, FoundAt};
use crate::cut::Cut;
use crate::error::Result;
use crate::verify::{Verification, Verifier};
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Optional connections to the outside: a stop flag (raised by Ctrl-C) and a progress display.
#[derive(Clone, Copy, Default)]
pub struct Hooks<'a> {
    /// When raised, the search stops after the current iteration.
    pub stop: Option<&'a AtomicBool>,
    /// Receives progress snapshots.
    pub progress: Option<&'a dyn Progress>,
}

impl Hooks<'_> {
    fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::SeqCst))
    }
}

/// What a search found.
pub struct Outcome {
    /// Every evaluated point.
    pub history: History,
    /// Why the search stopped.
    pub stop: Stop,
    /// Nelder–Mead: why each start stopped.
    pub start_stops: Vec<Stop>,
    /// Iterations (summed over starts).
    pub iterations: u64,
    /// Evaluations.
    pub evaluations: u64,
    /// Seconds of the search.
    pub seconds: f64,
    /// The start cut.
    pub start: Candidate,
    /// Distinct winners, best first (at least one, unless every cut failed).
    pub winners: Vec<Candidate>,
    /// The best cut.
    pub best_cut: Option<Cut>,
    /// Seconds of the verification.
    pub verify_seconds: f64,
    /// Why verification was skipped or cut short.
    pub verify_note: Option<String>,
    /// Whether a verifier ran.
    pub verified: bool,
}

impl Outcome {
    /// The best candidate (the start if every cut failed).
    pub fn best(&self) -> &Candidate {
        self.winners.first().unwrap_or(&self.start)
    }
}

/// Pick up to `n` distinct winners from the history: lowest cost first, each at least
/// `min_distance` (in the unit box of the free parameters) from those already picked. Failed
/// cuts are never winners. Returns row indices.
pub fn pick_winners(
    space: &SearchBox<'_>,
    history: &History,
    n: usize,
    min_distance: f64,
) -> Vec<usize> {
    let mut order: Vec<usize> = (0..history.rows.len())
        .filter(|&i| history.rows[i].cost < 0.5 * FAILED_COST)
        .collect();
    order.sort_by(|&a, &b| {
        history.rows[a]
            .cost
            .total_cmp(&history.rows[b].cost)
            .then(a.cmp(&b))
    });
    let mut picked: Vec<(usize, Vec<f64>)> = Vec::new();
    for i in order {
        if picked.len() >= n {
            break;
        }
        let u = space.unit_of(&history.rows[i].x);
        let far = picked.iter().all(|(_, p)| {
            let d2: f64 = p.iter().zip(&u).map(|(a, b)| (a - b) * (a - b)).sum();
            d2.sqrt() >= min_distance && d2 > 0.0
        });
        if far {
            picked.push((i, u));
        }
    }
    picked.into_iter().map(|(i, _)| i).collect()
}

/// Search: run the configured method and score the start and the winners. No files.
pub fn search(config: &Config, evaluator: &dyn Evaluator, hooks: &Hooks<'_>) -> Result<Outcome> {
    let objective = Objective::new(config, evaluator);
    let tracker = Tracker::new(hooks.progress, hooks.stop, config.budget.max_evaluations);
    let (budget, seed) = (config.budget, config.seed);
    let t = Instant::now();
    let (history, stop, start_stops, iterations) = match config.method {
        Method::NelderMead(settings) => {
            let method = MultiStart {
                settings,
                budget,
                seed,
            };
            let (h, runs) = method.search(&objective, &tracker)?;
            let stops: Vec<Stop> = runs.iter().map(|r| r.stop).collect();
            let stop = if stops.contains(&Stop::Interrupted) {
                Stop::Interrupted
            } else {
                // The most common reason, ties to the first in this order.
                let mut best = (Stop::Converged, 0);
                for s in [Stop::MaxEvaluations, Stop::MaxIterations, Stop::Converged] {
                    let n = stops.iter().filter(|x| **x == s).count();
                    if n > best.1 {
                        best = (s, n);
                    }
                }
                best.0
            };
            let iters = runs.iter().map(|r| r.iterations).sum();
            (h, stop, stops, iters)
        }
        Method::ParticleSwarm(settings) => {
            let method = Swarm {
                settings,
                budget,
                seed,
            };
            let (h, run) = method.search(&objective, &tracker)?;
            (h, run.stop, Vec::new(), run.iterations)
        }
    };
    let seconds = t.elapsed().as_secs_f64();
    let evaluations = history.rows.len() as u64;

    let picks = pick_winners(
        &objective.space,
        &history,
        config.verify.winners.max(1),
        config.verify.min_distance,
    );
    // The start and the winners are scored in full side by side, kept in this order.
    let points: Vec<Vec<f64>> = std::iter::once(config.start_x())
        .chain(picks.iter().map(|&i| history.rows[i].x.clone()))
        .collect();
    let mut evals = points
        .par_iter()
        .map(|x| objective.evaluate_full(x))
        .collect::<Vec<_>>()
        .into_iter();
    let start_eval = evals.next().expect("the start's evaluation");
    let start = Candidate::new("start", config, &start_eval, None);
    let mut winners = Vec::new();
    let mut best_cut = None;
    for ((k, &i), e) in picks.iter().enumerate().zip(evals) {
        let r = &history.rows[i];
        if k == 0 {
            best_cut = e.cut.clone();
        }
        winners.push(Candidate::new(
            &format!("winner {}", k + 1),
            config,
            &e,
            Some(FoundAt {
                track: r.track,
                iteration: r.iteration,
                evaluations: r.evaluations,
            }),
        ));
    }
    if let Some(c) = best_cut.as_mut() {
        c.name = format!("{} best", config.name);
    }
    Ok(Outcome {
        history,
        stop,
        start_stops,
        iterations,
        evaluations,
        seconds,
        start,
        winners,
        best_cut,
        verify_seconds: 0.0,
        verify_note: None,
        verified: false,
    })
}

/// Verify the start and the first `config.verify.winners` winners with the photon tracer.
/// Skipped after Ctrl-C; a failing verifier is noted per cut, never fatal. The cuts are
/// independent and verified in parallel (each verification is deterministic, so the results,
/// kept in candidate order, do not depend on the thread count).
pub fn verify(outcome: &mut Outcome, config: &Config, verifier: &dyn Verifier, hooks: &Hooks<'_>) {
    let v = &config.verify;
    if v.winners == 0 {
        outcome.verify_note = Some("verify.winners = 0".into());
        return;
    }
    if outcome.stop == Stop::Interrupted || hooks.stopped() {
        outcome.verify_note = Some("skipped: the run was interrupted".into());
        return;
    }
    outcome.verified = true;
    let t = Instant::now();
    let n = v.winners.min(outcome.winners.len());
    let mut cands: Vec<&mut Candidate> = std::iter::once(&mut outcome.start)
        .chain(outcome.winners.iter_mut().take(n))
        .collect();
    let stop = hooks.stop;
    let stopped = || stop.is_some_and(|s| s.load(Ordering::SeqCst));
    let cut_short = AtomicBool::new(false);
    cands.par_iter_mut().for_each(|c| {
        if stopped() {
            cut_short.store(true, Ordering::SeqCst);
            return;
        }
        match config.build(&c.label, &c.params) {
            Ok(cut) => {
                c.verification = Some(Verification::run_scored(
                    verifier,
                    &cut,
                    v.photons,
                    config.seed,
                    v.sigma,
                    c.scores.as_ref(),
                ))
            }
            Err(e) => {
                c.error.get_or_insert(e.to_string());
            }
        }
    });
    if cut_short.into_inner() {
        outcome.verify_note = Some("cut short: interrupted".into());
    }
    outcome.verify_seconds = t.elapsed().as_secs_f64();
}
