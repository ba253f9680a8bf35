//! What every section's validator shares: the defaults, how a field is named in messages
//! ([`At`]), and the checks of a finite number and of a whole number in a range.

use crate::error::{shown, Error, Result};

/// Defaults (also in the config-file table of `docs/optimize.md`).
pub mod defaults {
    /// Seed.
    pub const SEED: u64 = 1;
    /// Penalty per percentage point of violation.
    pub const PENALTY: f64 = 1.0;
    /// Nelder–Mead starts.
    pub const STARTS: u64 = 4;
    /// Nelder–Mead iterations per start.
    pub const NM_MAX_ITERATIONS: u64 = 1000;
    /// Evaluation budget.
    pub const MAX_EVALUATIONS: u64 = 400;
    /// Simplex edge.
    pub const SIMPLEX_STEP: f64 = 0.15;
    /// Nelder–Mead convergence tolerance (standard deviation of the simplex's costs).
    pub const TOLERANCE: f64 = 1e-9;
    /// Particles.
    pub const PARTICLES: u64 = 16;
    /// Swarm iterations.
    pub const PSO_MAX_ITERATIONS: u64 = 25;
    /// Inertia (argmin's default, 1/(2 ln 2)).
    pub const INERTIA: f64 = 0.721_347_520_444_481_7;
    /// Cognitive and social factors (argmin's default, 1/2 + ln 2).
    pub const PULL: f64 = 1.193_147_180_559_945_3;
    /// Winners to verify.
    pub const WINNERS: u64 = 3;
    /// Photons per verified cut and light.
    pub const PHOTONS: u64 = 100_000;
    /// Distance between winners.
    pub const MIN_DISTANCE: f64 = 0.05;
    /// Disagreement threshold.
    pub const SIGMA: f64 = 4.0;
}

/// `v` if it is a finite number, else an error naming the field.
pub(super) fn finite(field: &str, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            field,
            format!("{} is not a finite number", shown(v)),
        ))
    }
}

/// A whole number in `[lo, hi]`, or an error naming the field.
pub(super) fn count(at: At, field: &str, v: u64, lo: u64, hi: u64) -> Result<u64> {
    if !(lo..=hi).contains(&v) {
        return Err(Error::invalid(
            at(field),
            format!("{v} is out of range; allowed {lo} to {hi}"),
        ));
    }
    Ok(v)
}

/// Names a field in messages: `SOURCE: FIELD`.
pub(super) type At<'a> = &'a dyn Fn(&str) -> String;
