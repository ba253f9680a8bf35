//! `[score]`: how the cuts are scored (material, lighting).

use super::{finite, At};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// `[score]`: the scoring settings of the beam tracer (and of the photon-tracer checks).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScore {
    /// Material: a name from `facetlab materials` or `ri:N[:BG]`; default diamond.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// A fixed refractive index instead of a material (no dispersion, no fire).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ri: Option<f64>,
    /// Head-shadow half-angle in degrees, 0–60; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head_shadow: Option<f64>,
    /// Track polarization; default true.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polarization: Option<bool>,
}

/// Validated `[score]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ScoreSettings {
    /// The material (from `material` or `ri`).
    pub material: crate::optics::Material,
    /// Whether `ri` was given (for writing the config back).
    pub ri: Option<f64>,
    /// Head-shadow half-angle, degrees.
    pub head_shadow_deg: f64,
    /// Track polarization.
    pub polarization: bool,
}

impl ScoreSettings {
    /// The beam tracer's scoring configuration for these settings.
    pub fn score_config(&self) -> crate::metrics::ScoreConfig {
        crate::metrics::ScoreConfig {
            material: self.material.clone(),
            head_shadow_deg: self.head_shadow_deg,
            polarization: self.polarization,
            ..crate::metrics::ScoreConfig::default()
        }
    }
}

/// Validate `[score]`.
pub(super) fn validate(rs: &RawScore, at: At) -> Result<ScoreSettings> {
    let material = crate::optics::Material::choose(
        rs.material.as_deref(),
        rs.ri,
        crate::optics::MaterialFields {
            material: &at("score.material"),
            ri: &at("score.ri"),
        },
    )?;
    let head_shadow_deg = finite(&at("score.head_shadow"), rs.head_shadow.unwrap_or(0.0))?;
    if !(0.0..=60.0).contains(&head_shadow_deg) {
        return Err(Error::invalid(
            at("score.head_shadow"),
            format!("{head_shadow_deg} is out of range; allowed [0, 60] degrees (0 = none)"),
        ));
    }
    let score = ScoreSettings {
        material,
        ri: rs.ri,
        head_shadow_deg,
        polarization: rs.polarization.unwrap_or(true),
    };
    Ok(score)
}
