//! Particle swarm (argmin's `ParticleSwarm`) inside the bounds.
//!
//! argmin draws the initial positions uniformly in the box and clamps every move to it, so the
//! bounds need no reparametrisation (particles that fly into a wall stay on it). The swarm's
//! random numbers come from a `StdRng` seeded with the config's seed, and argmin evaluates the
//! particles of an iteration in parallel (its `rayon` feature) and keeps them in order, so the
//! same seed gives the same history on any number of threads.
//!
//! Budget: `max_iterations`, and `max_evaluations` rounded down to whole swarms (the initial
//! swarm counts as one): `iterations ≤ max_evaluations / particles − 1`.

use super::config::{Budget, SwarmSettings};
use super::guard::{Guarded, Stop, Tracker};
use super::history::{History, SwarmObserver, Track};
use super::problem::{BoxProblem, Objective};
use crate::error::{Error, Result};
use argmin::core::observers::ObserverMode;
use argmin::core::{Executor, State};
use argmin::solver::particleswarm::ParticleSwarm;
use rand::rngs::StdRng;
use rand::SeedableRng;
use std::sync::{Arc, Mutex};

/// What the swarm did.
#[derive(Clone, Debug)]
pub struct SwarmRun {
    /// Why it stopped.
    pub stop: Stop,
    /// Iterations done (after the initial swarm).
    pub iterations: u64,
}

/// Particle swarm as configured: like argmin's solvers it holds its own settings, with the
/// run's budget and the seed of its random numbers.
#[derive(Clone, Copy, Debug)]
pub struct Swarm {
    /// Particles and their inertia, cognitive and social factors.
    pub settings: SwarmSettings,
    /// The iteration and evaluation budget.
    pub budget: Budget,
    /// Seeds the swarm's random numbers.
    pub seed: u64,
}

impl Swarm {
    /// Run the swarm.
    pub fn search(
        &self,
        objective: &Objective<'_>,
        tracker: &Tracker<'_>,
    ) -> Result<(History, SwarmRun)> {
        let (s, budget) = (&self.settings, &self.budget);
        let fail = |e: argmin::core::Error| Error::invalid("particle-swarm", e.to_string());
        let free = objective.space.free;
        let lo: Vec<f64> = free.iter().map(|f| f.lo).collect();
        let hi: Vec<f64> = free.iter().map(|f| f.hi).collect();
        let np = s.particles as u64;
        let by_evals = (budget.max_evaluations / np).saturating_sub(1);
        let max_iters = budget.max_iterations.min(by_evals);
        let solver = ParticleSwarm::new((lo, hi), s.particles)
            .with_inertia_factor(s.inertia)
            .and_then(|p| p.with_cognitive_factor(s.cognitive))
            .and_then(|p| p.with_social_factor(s.social))
            .map_err(fail)?
            .with_rng_generator(StdRng::seed_from_u64(self.seed));
        let history = Arc::new(Mutex::new(History::new(
            Track::Particle,
            objective.space.keys(),
        )));
        let observer = SwarmObserver {
            history: Arc::clone(&history),
        };
        let problem = BoxProblem::new(objective, tracker);
        let guarded = Guarded::new(solver, budget.max_evaluations, None, tracker);
        let res = Executor::new(problem, guarded)
            .configure(|st| st.max_iters(max_iters).counting(true))
            .add_observer(observer, ObserverMode::Always)
            .run()
            .map_err(fail)?;
        let mut stop = Stop::from_reason(res.state.get_termination_reason());
        if stop == Stop::MaxIterations && max_iters < budget.max_iterations {
            stop = Stop::MaxEvaluations;
        }
        let iterations = res.state.get_iter();
        drop(res);
        let h = match history.lock() {
            Ok(g) => g.clone(),
            Err(p) => p.into_inner().clone(),
        };
        Ok((h, SwarmRun { stop, iterations }))
    }
}
