//! `[method]`: the search method, its settings and the budgets.

use super::fields::{defaults, finite, At};
use crate::error::{shown, Error, Result};
use serde::{Deserialize, Serialize};

/// `[method]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawMethod {
    /// `nelder-mead` (default) or `particle-swarm`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Iteration budget: per start (Nelder–Mead) or of the swarm.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_iterations: Option<u64>,
    /// Evaluation budget of the whole run (split evenly between Nelder–Mead starts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_evaluations: Option<u64>,
    /// Nelder–Mead: number of starts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub starts: Option<u64>,
    /// Nelder–Mead: `latin-hypercube` or `halton`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design: Option<String>,
    /// Nelder–Mead: whether the first start is the configured start cut.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub include_start: Option<bool>,
    /// Nelder–Mead: initial simplex edge as a fraction of each parameter's range.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simplex_step: Option<f64>,
    /// Nelder–Mead: a start ends when the standard deviation of its simplex's costs falls
    /// below this.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Particle swarm: number of particles.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub particles: Option<u64>,
    /// Particle swarm: inertia weight.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inertia: Option<f64>,
    /// Particle swarm: pull toward each particle's own best.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cognitive: Option<f64>,
    /// Particle swarm: pull toward the swarm's best.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub social: Option<f64>,
}

/// How Nelder–Mead starts are spread over the box (`method.design` in a config).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Sampling {
    /// Seeded Latin hypercube: one start per row and column stratum.
    LatinHypercube,
    /// Seeded (randomly shifted) Halton sequence.
    Halton,
}

impl Sampling {
    /// Name in configs.
    pub fn name(self) -> &'static str {
        match self {
            Sampling::LatinHypercube => "latin-hypercube",
            Sampling::Halton => "halton",
        }
    }
}

/// Nelder–Mead settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NelderMeadSettings {
    /// Number of starts.
    pub starts: usize,
    /// How the starts are spread (`method.design`).
    #[serde(rename = "design")]
    pub sampling: Sampling,
    /// Whether start 0 is the configured start cut.
    pub include_start: bool,
    /// Initial simplex edge as a fraction of each range.
    pub simplex_step: f64,
    /// Convergence: standard deviation of the simplex's costs.
    pub tolerance: f64,
}

/// Particle swarm settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SwarmSettings {
    /// Number of particles.
    pub particles: usize,
    /// Inertia weight.
    pub inertia: f64,
    /// Cognitive factor.
    pub cognitive: f64,
    /// Social factor.
    pub social: f64,
}

/// The search method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// Multi-start Nelder–Mead in the sigmoid reparametrisation.
    NelderMead(NelderMeadSettings),
    /// argmin's particle swarm in the bounds.
    ParticleSwarm(SwarmSettings),
}

impl Method {
    /// Name in configs.
    pub fn name(&self) -> &'static str {
        match self {
            Method::NelderMead(_) => "nelder-mead",
            Method::ParticleSwarm(_) => "particle-swarm",
        }
    }
}

/// Iteration and evaluation budgets.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Budget {
    /// Iterations per start (Nelder–Mead) or of the swarm.
    pub max_iterations: u64,
    /// Evaluations of the whole run.
    pub max_evaluations: u64,
}

/// Validate `[method]`; `n_free` (the number of free parameters) sizes Nelder–Mead's simplexes.
pub(super) fn validate(rm: &RawMethod, n_free: usize, at: At) -> Result<(Method, Budget)> {
    let mname = rm.name.as_deref().unwrap_or("nelder-mead");
    let nm_only: [(&str, bool); 5] = [
        ("starts", rm.starts.is_some()),
        ("design", rm.design.is_some()),
        ("include_start", rm.include_start.is_some()),
        ("simplex_step", rm.simplex_step.is_some()),
        ("tolerance", rm.tolerance.is_some()),
    ];
    let pso_only: [(&str, bool); 4] = [
        ("particles", rm.particles.is_some()),
        ("inertia", rm.inertia.is_some()),
        ("cognitive", rm.cognitive.is_some()),
        ("social", rm.social.is_some()),
    ];
    let refuse = |keys: &[(&str, bool)], only: &str| -> Result<()> {
        if let Some((k, _)) = keys.iter().find(|(_, given)| *given) {
            return Err(Error::invalid(
                at(&format!("method.{k}")),
                format!("only for method `{only}`, not `{mname}`"),
            ));
        }
        Ok(())
    };
    let count = |field: &str, v: u64, lo: u64, hi: u64| super::fields::count(at, field, v, lo, hi);
    let (method, default_iters) = match mname {
        "nelder-mead" => {
            refuse(&pso_only, "particle-swarm")?;
            let sampling = match rm.design.as_deref().unwrap_or("latin-hypercube") {
                "latin-hypercube" => Sampling::LatinHypercube,
                "halton" => Sampling::Halton,
                other => {
                    return Err(Error::invalid(
                        at("method.design"),
                        format!("unknown design `{other}`; allowed: latin-hypercube, halton"),
                    ))
                }
            };
            let step = finite(
                &at("method.simplex_step"),
                rm.simplex_step.unwrap_or(defaults::SIMPLEX_STEP),
            )?;
            if !(step > 0.0 && step <= 0.5) {
                return Err(Error::invalid(
                    at("method.simplex_step"),
                    format!("{step} is out of range; allowed (0, 0.5] (a fraction of each parameter's range)"),
                ));
            }
            let tolerance = finite(
                &at("method.tolerance"),
                rm.tolerance.unwrap_or(defaults::TOLERANCE),
            )?;
            if tolerance < 0.0 {
                return Err(Error::invalid(
                    at("method.tolerance"),
                    format!("{tolerance} is negative; give 0 (never converge: run to the budget) or a small positive number"),
                ));
            }
            (
                Method::NelderMead(NelderMeadSettings {
                    tolerance,
                    starts: count(
                        "method.starts",
                        rm.starts.unwrap_or(defaults::STARTS),
                        1,
                        1000,
                    )? as usize,
                    sampling,
                    include_start: rm.include_start.unwrap_or(true),
                    simplex_step: step,
                }),
                defaults::NM_MAX_ITERATIONS,
            )
        }
        "particle-swarm" => {
            refuse(&nm_only, "nelder-mead")?;
            let factor = |field: &str, v: Option<f64>, dflt: f64| -> Result<f64> {
                let v = finite(&at(field), v.unwrap_or(dflt))?;
                if !(0.0..=4.0).contains(&v) {
                    return Err(Error::invalid(
                        at(field),
                        format!("{} is out of range; allowed [0, 4]", shown(v)),
                    ));
                }
                Ok(v)
            };
            (
                Method::ParticleSwarm(SwarmSettings {
                    particles: count(
                        "method.particles",
                        rm.particles.unwrap_or(defaults::PARTICLES),
                        2,
                        10_000,
                    )? as usize,
                    inertia: factor("method.inertia", rm.inertia, defaults::INERTIA)?,
                    cognitive: factor("method.cognitive", rm.cognitive, defaults::PULL)?,
                    social: factor("method.social", rm.social, defaults::PULL)?,
                }),
                defaults::PSO_MAX_ITERATIONS,
            )
        }
        other => {
            return Err(Error::invalid(
                at("method.name"),
                format!("unknown method `{other}`; allowed: nelder-mead, particle-swarm"),
            ))
        }
    };
    let budget = Budget {
        max_iterations: count(
            "method.max_iterations",
            rm.max_iterations.unwrap_or(default_iters),
            1,
            1_000_000,
        )?,
        max_evaluations: count(
            "method.max_evaluations",
            rm.max_evaluations.unwrap_or(defaults::MAX_EVALUATIONS),
            1,
            100_000_000,
        )?,
    };
    match method {
        Method::NelderMead(nm) => {
            let need = (nm.starts * (n_free + 1)) as u64;
            if budget.max_evaluations < need {
                return Err(Error::invalid(
                    at("method.max_evaluations"),
                    format!(
                        "{} cannot even build the {} starting simplexes ({need} evaluations); raise it or lower method.starts",
                        budget.max_evaluations, nm.starts
                    ),
                ));
            }
        }
        Method::ParticleSwarm(s) => {
            if budget.max_evaluations < s.particles as u64 {
                return Err(Error::invalid(
                    at("method.max_evaluations"),
                    format!(
                        "{} is less than one swarm of {} particles",
                        budget.max_evaluations, s.particles
                    ),
                ));
            }
        }
    }
    Ok((method, budget))
}
