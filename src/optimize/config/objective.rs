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
