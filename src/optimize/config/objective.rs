//! `[objective]`: the weights of the scores.

use super::{finite, At};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// `[objective]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObjective {
    /// Weight of brilliance (default 1 when no weight is given at all, else 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub brilliance: Option<f64>,
    /// Weight of fire (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fire: Option<f64>,
    /// Weight of scintillation (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scintillation: Option<f64>,
    /// Trace the trade-off between two or three scores instead of one weighted search:
    /// `pareto = ["brilliance", "fire"]` (see [`crate::optimize::run_pareto`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto: Option<Vec<String>>,
    /// Weight steps per edge of the trade-off (2 scores: that many runs; default 7).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto_points: Option<u64>,
}

/// The scores a trade-off may name.
pub const PARETO_SCORES: [&str; 3] = ["brilliance", "fire", "scintillation"];

/// A validated `[objective] pareto`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParetoSpec {
    /// The scores traded off (2 or 3 of [`PARETO_SCORES`]).
    pub scores: Vec<String>,
    /// Weight steps per edge (≥ 2).
    pub points: usize,
}

/// Validate `[objective] pareto` (None when absent).
pub(super) fn validate_pareto(ro: &RawObjective, at: At) -> Result<Option<ParetoSpec>> {
    let Some(names) = &ro.pareto else {
        return Ok(None);
    };
    let f = "objective.pareto";
    if !(2..=3).contains(&names.len()) {
        return Err(Error::invalid(
            at(f),
            format!(
                "{} scores given; trade off two or three of brilliance, fire, scintillation",
                names.len()
            ),
        ));
    }
    for (i, n) in names.iter().enumerate() {
        if !PARETO_SCORES.contains(&n.as_str()) {
            return Err(Error::invalid(
                at(f),
                format!("{n:?} is not a score; allowed brilliance, fire, scintillation"),
            ));
        }
        if names[..i].contains(n) {
            return Err(Error::invalid(at(f), format!("{n:?} is named twice")));
        }
    }
    let points = ro.pareto_points.unwrap_or(7);
    if !(2..=50).contains(&points) {
        return Err(Error::invalid(
            at("objective.pareto_points"),
            format!("{points} is out of range; allowed 2 to 50"),
        ));
    }
    Ok(Some(ParetoSpec {
        scores: names.clone(),
        points: points as usize,
    }))
}

/// Objective weights: score = Σ weight · score.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Weights {
    /// Weight of brilliance.
    pub brilliance: f64,
    /// Weight of fire.
    pub fire: f64,
    /// Weight of scintillation.
    pub scintillation: f64,
}

/// Validate `[objective]`.
pub(super) fn validate(ro: &RawObjective, at: At) -> Result<Weights> {
    let any = ro.brilliance.is_some() || ro.fire.is_some() || ro.scintillation.is_some();
    let w = |field: &str, v: Option<f64>, dflt: f64| -> Result<f64> {
        let v = finite(&at(field), v.unwrap_or(dflt))?;
        if v < 0.0 {
            return Err(Error::invalid(
                at(field),
                format!("{v} is negative; weights are >= 0 (higher scores are better)"),
            ));
        }
        Ok(v)
    };
    let weights = Weights {
        brilliance: w(
            "objective.brilliance",
            ro.brilliance,
            if any { 0.0 } else { 1.0 },
        )?,
        fire: w("objective.fire", ro.fire, 0.0)?,
        scintillation: w("objective.scintillation", ro.scintillation, 0.0)?,
    };
    if weights.brilliance + weights.fire + weights.scintillation <= 0.0 {
        return Err(Error::invalid(
            at("objective"),
            "every weight is 0; give brilliance, fire or scintillation a positive weight",
        ));
    }
    Ok(weights)
}
