//! `[constraints]`: limits on the cut's measurements, enforced by penalties.

use super::fields::{defaults, finite, At};
use crate::cut::grade::Grade;
use crate::error::{shown, Error, Result};
use serde::{Deserialize, Serialize};

/// `[constraints]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawConstraints {
    /// Allowed total depth, [min, max], fractions of the girdle diameter.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub total_depth: Option<[f64; 2]>,
    /// Smallest allowed crown height.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_crown_height: Option<f64>,
    /// Smallest allowed girdle thickness.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_girdle: Option<f64>,
    /// Smallest allowed weight retention from a round rough (volume / containing cylinder).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_weight_retention: Option<f64>,
    /// Keep round brilliants inside a proportion grade estimate ([`crate::cut::grade`]):
    /// `excellent`, `very-good`, `good` or `fair`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grade: Option<String>,
    /// Largest allowed extinction of a coloured stone (share of its face-up picture whose
    /// light through the stone is darker than L* 20; needs a body colour in `[score]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_extinction: Option<f64>,
    /// Largest allowed windowing of a coloured stone (share of the face-up light seen from
    /// below the girdle plane; needs a body colour in `[score]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_windowing: Option<f64>,
    /// Cost added per percentage point (0.01) of violation; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
}

/// Constraints; `None` = not constrained.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Constraints {
    /// Allowed total depth.
    pub total_depth: Option<[f64; 2]>,
    /// Smallest crown height.
    pub min_crown_height: Option<f64>,
    /// Smallest girdle thickness.
    pub min_girdle: Option<f64>,
    /// Smallest weight retention.
    pub min_weight_retention: Option<f64>,
    /// Worst proportion grade estimate allowed (round brilliants).
    pub grade: Option<Grade>,
    /// Largest extinction of a coloured stone's face-up picture.
    pub max_extinction: Option<f64>,
    /// Largest windowing of a coloured stone's face-up picture.
    pub max_windowing: Option<f64>,
    /// Cost per percentage point of violation.
    pub penalty: f64,
}

/// Validate `[constraints]`.
pub(super) fn validate(rk: &RawConstraints, at: At) -> Result<Constraints> {
    let frac = |field: &str, v: Option<f64>, max: f64| -> Result<Option<f64>> {
        match v {
            None => Ok(None),
            Some(v) => {
                let v = finite(&at(field), v)?;
                if !(0.0..=max).contains(&v) {
                    let hint = if v > 1.0 {
                        " (fractions: 0.12, not 12)"
                    } else {
                        ""
                    };
                    return Err(Error::invalid(
                        at(field),
                        format!("{} is out of range; allowed [0, {max}]{hint}", shown(v)),
                    ));
                }
                Ok(Some(v))
            }
        }
    };
    let total_depth = match rk.total_depth {
        None => None,
        Some([lo, hi]) => {
            let f = "constraints.total_depth";
            frac(f, Some(lo), 2.0)?;
            frac(f, Some(hi), 2.0)?;
            if lo > hi {
                return Err(Error::invalid(
                    at(f),
                    format!(
                        "range [{}, {}] is reversed; write [min, max]",
                        shown(lo),
                        shown(hi)
                    ),
                ));
            }
            Some([lo, hi])
        }
    };
    let penalty = finite(
        &at("constraints.penalty"),
        rk.penalty.unwrap_or(defaults::PENALTY),
    )?;
    if penalty <= 0.0 {
        return Err(Error::invalid(
            at("constraints.penalty"),
            format!(
                "{penalty} is not allowed; give a positive cost per percentage point of violation"
            ),
        ));
    }
    let grade = match rk.grade.as_deref() {
        None => None,
        Some(g) => match Grade::parse(g) {
            Some(Grade::Poor) | None => {
                return Err(Error::invalid(
                    at("constraints.grade"),
                    format!(
                        "{g:?} is not a grade to keep to; allowed excellent, very-good, good, fair"
                    ),
                ))
            }
            Some(g) => Some(g),
        },
    };
    let constraints = Constraints {
        total_depth,
        min_crown_height: frac("constraints.min_crown_height", rk.min_crown_height, 1.0)?,
        min_girdle: frac("constraints.min_girdle", rk.min_girdle, 1.0)?,
        min_weight_retention: frac(
            "constraints.min_weight_retention",
            rk.min_weight_retention,
            1.0,
        )?,
        grade,
        max_extinction: frac("constraints.max_extinction", rk.max_extinction, 1.0)?,
        max_windowing: frac("constraints.max_windowing", rk.max_windowing, 1.0)?,
        penalty,
    };
    Ok(constraints)
}
