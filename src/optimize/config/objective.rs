//! `[objective]`: the weights of the scores.

use super::fields::{finite, At};
use crate::error::{shown, Error, Result};
use crate::metrics::score_name::list;
use crate::metrics::ScoreName;
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
    /// Weight of a coloured stone's face-up lightness L* (0–100; needs a body colour).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour_l: Option<f64>,
    /// Weight of a coloured stone's face-up chroma C* (needs a body colour).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour_c: Option<f64>,
    /// Weight of a coloured stone's extinction (0–1; negative to avoid it; needs a body colour).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extinction: Option<f64>,
    /// Weight of a coloured stone's windowing (0–1; negative to avoid it; needs a body colour).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windowing: Option<f64>,
    /// Trace the trade-off between two or three scores instead of one weighted search:
    /// `pareto = ["brilliance", "fire"]` (see [`crate::optimize::run_pareto`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto: Option<Vec<String>>,
    /// Weight steps per edge of the trade-off (2 scores: that many runs; default 7).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pareto_points: Option<u64>,
}

/// A validated `[objective] pareto`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ParetoSpec {
    /// The scores traded off (2 or 3 of [`ScoreName::OBJECTIVE`]).
    pub scores: Vec<ScoreName>,
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
                "{} scores given; trade off two or three of {}",
                names.len(),
                list(&ScoreName::OBJECTIVE)
            ),
        ));
    }
    let mut scores = Vec::new();
    for (i, n) in names.iter().enumerate() {
        let Some(score) = ScoreName::from_key(n).filter(|s| ScoreName::OBJECTIVE.contains(s))
        else {
            return Err(Error::invalid(
                at(f),
                format!(
                    "{n:?} is not a score; allowed {}",
                    list(&ScoreName::OBJECTIVE)
                ),
            ));
        };
        if names[..i].contains(n) {
            return Err(Error::invalid(at(f), format!("{n:?} is named twice")));
        }
        scores.push(score);
    }
    let points = ro.pareto_points.unwrap_or(7);
    if !(2..=50).contains(&points) {
        return Err(Error::invalid(
            at("objective.pareto_points"),
            format!("{points} is out of range; allowed 2 to 50"),
        ));
    }
    Ok(Some(ParetoSpec {
        scores,
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
    /// Weights of a coloured stone's colour scores, in the order of [`ScoreName::COLOUR`]
    /// (any sign: a negative weight on extinction or windowing avoids them); all 0 for a
    /// colourless stone. Left out of the JSON when all 0.
    #[serde(skip_serializing_if = "all_zero")]
    pub colour: [f64; 4],
}

fn all_zero(w: &[f64; 4]) -> bool {
    w.iter().all(|x| *x == 0.0)
}

impl Weights {
    /// Whether any colour score is weighed.
    pub fn weighs_colour(&self) -> bool {
        !all_zero(&self.colour)
    }
}

impl RawObjective {
    /// The colour weights given, in the order of [`ScoreName::COLOUR`].
    pub fn colour(&self) -> [Option<f64>; 4] {
        [
            self.colour_l,
            self.colour_c,
            self.extinction,
            self.windowing,
        ]
    }
}

/// Validate `[objective]` (a colour weight's need of a body colour is checked with `[score]`).
pub(super) fn validate(ro: &RawObjective, at: At) -> Result<Weights> {
    let colour_given = ro.colour();
    let any = ro.brilliance.is_some()
        || ro.fire.is_some()
        || ro.scintillation.is_some()
        || colour_given.iter().any(Option::is_some);
    let w = |field: &str, v: Option<f64>, dflt: f64| -> Result<f64> {
        let v = finite(&at(field), v.unwrap_or(dflt))?;
        if v < 0.0 {
            return Err(Error::invalid(
                at(field),
                format!(
                    "{} is negative; weights are >= 0 (higher scores are better)",
                    shown(v)
                ),
            ));
        }
        Ok(v)
    };
    let mut weights = Weights {
        brilliance: w(
            "objective.brilliance",
            ro.brilliance,
            if any { 0.0 } else { 1.0 },
        )?,
        fire: w("objective.fire", ro.fire, 0.0)?,
        scintillation: w("objective.scintillation", ro.scintillation, 0.0)?,
        colour: [0.0; 4],
    };
    for (k, (name, v)) in ScoreName::COLOUR.iter().zip(colour_given).enumerate() {
        weights.colour[k] = finite(&at(&format!("objective.{name}")), v.unwrap_or(0.0))?;
    }
    if weights.brilliance + weights.fire + weights.scintillation <= 0.0 && !weights.weighs_colour()
    {
        return Err(Error::invalid(
            at("objective"),
            "every weight is 0; give brilliance, fire or scintillation a positive weight",
        ));
    }
    Ok(weights)
}
