//! Multi-start Nelder–Mead (argmin's `NelderMead`).
//!
//! - **Starts**: with `include_start` the first start is the configured start cut; the others
//!   come from a seeded Latin hypercube or Halton set over the box, pulled 5 % in from the walls
//!   (`f → 0.05 + 0.9·f` per axis) so no start sits where the sigmoid is flat.
//! - **Bounds**: argmin's Nelder–Mead has none. It works on `u` with
//!   `x = lo + (hi − lo)·sigmoid(u)` ([`SigmoidProblem`]), so every point is inside the box.
//! - **Initial simplex**: the start and, for each axis, the start moved by `simplex_step` of
//!   that axis's range (toward the middle when the step would leave 98 % of the box), both
//!   mapped to `u`.
//! - **Budget**: `max_iterations` per start; `max_evaluations` split evenly between the starts;
//!   the stop flag; and Nelder–Mead's own test, the standard deviation of the simplex's costs
//!   below `tolerance` (default 1e-9), which ends a start early only on a noiseless objective
//!   (Monte Carlo noise never meets it; set 0 to always run to the budget).
//! - **Parallel**: starts run on rayon's pool and are collected in start order, so the history
//!   does not depend on the thread count.

use super::config::{Budget, FreeParam, NelderMeadSettings, Sampling, SearchBox};
use super::guard::{Guarded, Stop, Tracker};
use super::history::{History, Row, Track};
use super::problem::{logit, Logged, Objective, SigmoidProblem};
use super::sampling::{halton, latin_hypercube};
use crate::error::{Error, Result};
use argmin::core::{Executor, State};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;
use std::sync::atomic::AtomicU64;

/// What one start did.
#[derive(Clone, Debug)]
pub struct StartRun {
    /// Every evaluation, in order.
    pub log: Vec<Logged>,
    /// Why it stopped.
    pub stop: Stop,
    /// Iterations done.
    pub iterations: u64,
}

/// Multi-start Nelder–Mead as configured: like argmin's solvers it holds its own settings,
/// with the run's budget and the seed of its start sample.
#[derive(Clone, Copy, Debug)]
pub struct MultiStart {
    /// Starts, their sampling, the simplex step and the tolerance.
    pub settings: NelderMeadSettings,
    /// The iteration budget per start and the evaluation budget shared by the starts.
    pub budget: Budget,
    /// Seeds the start sample.
    pub seed: u64,
}

impl MultiStart {
    /// The start points (parameter space) in `space`, start 0 first.
    pub fn start_points(&self, space: &SearchBox<'_>) -> Vec<Vec<f64>> {
        let nm = &self.settings;
        let d = space.free.len();
        let own = usize::from(nm.include_start);
        let n = nm.starts.saturating_sub(own);
        let samples = match nm.sampling {
            Sampling::LatinHypercube => latin_hypercube(n, d, self.seed),
            Sampling::Halton => halton(n, d, self.seed),
        };
        let mut out = Vec::with_capacity(nm.starts);
        if nm.include_start {
            out.push(space.start_x());
        }
        for p in samples {
            out.push(
                space
                    .free
                    .iter()
                    .zip(p)
                    .map(|(f, v)| f.at(0.05 + 0.9 * v))
                    .collect(),
            );
        }
        out
    }

    /// Run one start from `x0`, with its share `max_evaluations` of the budget.
    pub fn run_start(
        &self,
        objective: &Objective<'_>,
        x0: &[f64],
        max_evaluations: u64,
        tracker: &Tracker<'_>,
    ) -> Result<StartRun> {
        let fail = |e: argmin::core::Error| Error::invalid("nelder-mead", e.to_string());
        let iteration = AtomicU64::new(0);
        let problem = SigmoidProblem::new(objective, tracker, &iteration);
        let simplex = initial_simplex(objective.space.free, x0, self.settings.simplex_step);
        let solver = NelderMead::new(simplex)
            .with_sd_tolerance(self.settings.tolerance)
            .map_err(fail)?;
        let guarded = Guarded::new(solver, max_evaluations, Some(&iteration), tracker);
        let res = Executor::new(problem, guarded)
            .configure(|s| s.max_iters(self.budget.max_iterations).counting(true))
            .run()
            .map_err(fail)?;
        let stop = Stop::from_reason(res.state.get_termination_reason());
        let iterations = res.state.get_iter();
        let log = res
            .problem
            .problem
            .as_ref()
            .map(|p| p.take_log())
            .unwrap_or_default();
        Ok(StartRun {
            log,
            stop,
            iterations,
        })
    }

    /// Run every start (in parallel) and gather the history in start order.
    pub fn search(
        &self,
        objective: &Objective<'_>,
        tracker: &Tracker<'_>,
    ) -> Result<(History, Vec<StartRun>)> {
        let starts = self.start_points(&objective.space);
        let per_start = (self.budget.max_evaluations / starts.len().max(1) as u64).max(1);
        let runs: Vec<Result<StartRun>> = starts
            .par_iter()
            .map(|x0| self.run_start(objective, x0, per_start, tracker))
            .collect();
        let runs: Vec<StartRun> = runs.into_iter().collect::<Result<_>>()?;
        let mut h = History::new(Track::Start, objective.space.keys());
        let mut evals = 0;
        for (k, run) in runs.iter().enumerate() {
            let mut best = f64::INFINITY;
            for l in &run.log {
                evals += 1;
                best = best.min(l.cost);
                h.rows.push(Row {
                    track: k,
                    iteration: l.iteration,
                    evaluations: evals,
                    cost: l.cost,
                    best_cost: best,
                    x: l.x.clone(),
                });
            }
        }
        Ok((h, runs))
    }
}

/// The initial simplex around `x0` in the box of `free`, in `u` coordinates.
pub fn initial_simplex(free: &[FreeParam], x0: &[f64], step: f64) -> Vec<Vec<f64>> {
    let fs: Vec<f64> = free
        .iter()
        .zip(x0)
        .map(|(f, &x)| f.unit_of(x).clamp(1e-4, 1.0 - 1e-4))
        .collect();
    let u0: Vec<f64> = fs.iter().map(|&f| logit(f)).collect();
    let mut out = vec![u0.clone()];
    for i in 0..fs.len() {
        let f = fs[i];
        let moved = if f + step <= 0.98 { f + step } else { f - step };
        let mut u = u0.clone();
        u[i] = logit(moved.clamp(1e-4, 1.0 - 1e-4));
        out.push(u);
    }
    out
}
