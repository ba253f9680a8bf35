//! Stopping and progress: a wrapper around any argmin solver that ends the run on the
//! evaluation budget or when the stop flag is raised (Ctrl-C), and a tracker that counts
//! evaluations and reports progress.
//!
//! argmin's own Ctrl-C support installs one process-wide handler bound to the first executor,
//! which does not fit several Nelder–Mead starts; here the binary sets an `AtomicBool` from its
//! own handler and every solver checks it between iterations. A stopped solver returns its best
//! point as usual, so the run still writes what it found.

use argmin::core::{Problem, Solver, State, TerminationReason, TerminationStatus, KV};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Mutex;
use std::time::Instant;

/// A snapshot of a run's progress.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Status {
    /// Iterations finished (summed over Nelder–Mead starts).
    pub iterations: u64,
    /// Cost evaluations so far.
    pub evaluations: u64,
    /// The evaluation budget.
    pub budget: u64,
    /// Lowest cost so far (`+inf` before the first evaluation).
    pub best_cost: f64,
    /// Seconds since the run started.
    pub elapsed: f64,
}

/// Something that shows progress (a progress bar). Called from worker threads.
pub trait Progress: Sync {
    /// A new snapshot.
    fn update(&self, status: &Status);
}

/// A stop flag never raised: a run without Ctrl-C.
static NEVER: AtomicBool = AtomicBool::new(false);

/// Watches a run: counts evaluations and iterations, keeps the best cost, forwards snapshots,
/// and holds the stop flag every solver checks between iterations.
pub struct Tracker<'a> {
    stop: &'a AtomicBool,
    sink: Option<&'a dyn Progress>,
    budget: u64,
    evaluations: AtomicU64,
    iterations: AtomicU64,
    best: Mutex<f64>,
    started: Instant,
}

impl<'a> Tracker<'a> {
    /// A tracker reporting to `sink` (if any) against an evaluation `budget`, stopped by
    /// `stop` (if any) being raised.
    pub fn new(sink: Option<&'a dyn Progress>, stop: Option<&'a AtomicBool>, budget: u64) -> Self {
        Tracker {
            stop: stop.unwrap_or(&NEVER),
            sink,
            budget,
            evaluations: AtomicU64::new(0),
            iterations: AtomicU64::new(0),
            best: Mutex::new(f64::INFINITY),
            started: Instant::now(),
        }
    }

    /// Whether the stop flag is raised.
    pub fn stopped(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }

    fn best(&self) -> f64 {
        match self.best.lock() {
            Ok(g) => *g,
            Err(p) => *p.into_inner(),
        }
    }

    /// One evaluation with cost `c` is done.
    pub fn evaluated(&self, c: f64) {
        self.evaluations.fetch_add(1, Ordering::SeqCst);
        {
            let mut g = match self.best.lock() {
                Ok(g) => g,
                Err(p) => p.into_inner(),
            };
            if c < *g {
                *g = c;
            }
        }
        self.report();
    }

    /// One iteration is done.
    pub fn iterated(&self) {
        self.iterations.fetch_add(1, Ordering::SeqCst);
        self.report();
    }

    /// The current snapshot.
    pub fn status(&self) -> Status {
        Status {
            iterations: self.iterations.load(Ordering::SeqCst),
            evaluations: self.evaluations.load(Ordering::SeqCst),
            budget: self.budget,
            best_cost: self.best(),
            elapsed: self.started.elapsed().as_secs_f64(),
        }
    }

    fn report(&self) {
        if let Some(s) = self.sink {
            s.update(&self.status());
        }
    }
}

/// Why a search (or one Nelder–Mead start) stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stop {
    /// The iteration budget was used up.
    MaxIterations,
    /// The evaluation budget was used up.
    MaxEvaluations,
    /// The solver's own convergence test was met (Nelder–Mead: the simplex's costs agree).
    Converged,
    /// The stop flag was raised (Ctrl-C).
    Interrupted,
}

impl Stop {
    /// Text for reports.
    pub fn text(self) -> &'static str {
        match self {
            Stop::MaxIterations => "iteration budget used",
            Stop::MaxEvaluations => "evaluation budget used",
            Stop::Converged => "converged",
            Stop::Interrupted => "interrupted (Ctrl-C)",
        }
    }

    /// From argmin's termination reason.
    pub fn from_reason(r: Option<&TerminationReason>) -> Stop {
        match r {
            Some(TerminationReason::MaxItersReached) => Stop::MaxIterations,
            Some(TerminationReason::Interrupt) => Stop::Interrupted,
            Some(TerminationReason::SolverExit(s)) if s == EVALS_REACHED => Stop::MaxEvaluations,
            _ => Stop::Converged,
        }
    }
}

const EVALS_REACHED: &str = "evaluation budget reached";

/// A solver wrapped with the evaluation budget and the stop flag, both checked between
/// iterations (so a run may overshoot the budget by less than one iteration's evaluations).
pub struct Guarded<'g, S> {
    inner: S,
    max_evaluations: u64,
    iteration: Option<&'g AtomicU64>,
    tracker: &'g Tracker<'g>,
}

impl<'g, S> Guarded<'g, S> {
    /// Wrap `inner`. `iteration`, when given, is set to the number of the iteration about to
    /// run (so cost functions can log it).
    pub fn new(
        inner: S,
        max_evaluations: u64,
        iteration: Option<&'g AtomicU64>,
        tracker: &'g Tracker<'g>,
    ) -> Self {
        Guarded {
            inner,
            max_evaluations,
            iteration,
            tracker,
        }
    }
}

impl<O, I, S> Solver<O, I> for Guarded<'_, S>
where
    I: State,
    S: Solver<O, I>,
{
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn init(
        &mut self,
        problem: &mut Problem<O>,
        state: I,
    ) -> Result<(I, Option<KV>), argmin::core::Error> {
        if let Some(it) = self.iteration {
            it.store(0, Ordering::SeqCst);
        }
        self.inner.init(problem, state)
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        state: I,
    ) -> Result<(I, Option<KV>), argmin::core::Error> {
        if let Some(it) = self.iteration {
            it.store(state.get_iter() + 1, Ordering::SeqCst);
        }
        let out = self.inner.next_iter(problem, state);
        self.tracker.iterated();
        out
    }

    fn terminate(&mut self, state: &I) -> TerminationStatus {
        if self.tracker.stopped() {
            return TerminationStatus::Terminated(TerminationReason::Interrupt);
        }
        let evals = state
            .get_func_counts()
            .get("cost_count")
            .copied()
            .unwrap_or(0);
        if evals >= self.max_evaluations {
            return TerminationStatus::Terminated(TerminationReason::SolverExit(
                EVALS_REACHED.to_string(),
            ));
        }
        self.inner.terminate(state)
    }
}
