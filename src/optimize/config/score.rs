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
    /// Split threshold of the tilted poses' traces (brilliance, scintillation); default 1e-4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split_threshold: Option<f64>,
    /// Split threshold of fire's face-up traces; default 3e-6.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fire_split_threshold: Option<f64>,
    /// Share of its starting power below which a narrow beam's ray stops (its rest handed
    /// back with the narrow exits' mean); default 0.05, 0 = follow every ray to 1e-8.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ray_floor: Option<f64>,
    /// Follow narrow beams as discs that fork at facet edges (smoother scores, slower, and
    /// brilliance up to 4e-4 off); default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub narrow_forks: Option<bool>,
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
    /// Split threshold of the tilted poses' traces.
    pub split_threshold: f64,
    /// Split threshold of fire's face-up traces.
    pub fire_split_threshold: f64,
    /// The narrow beams' ray floor ([`crate::beam::TraceOptions::ray_floor`]).
    pub ray_floor: f64,
    /// Narrow beams as forking discs ([`crate::beam::TraceOptions::narrow_forks`]).
    pub narrow_forks: bool,
}

impl ScoreSettings {
    /// The beam tracer's scoring configuration for these settings.
    pub fn score_config(&self) -> crate::metrics::ScoreConfig {
        crate::metrics::ScoreConfig {
            material: self.material.clone(),
            head_shadow_deg: self.head_shadow_deg,
            polarization: self.polarization,
            fire_split_threshold: self.fire_split_threshold,
            trace: crate::beam::TraceOptions {
                split_threshold: self.split_threshold,
                ray_floor: self.ray_floor,
                narrow_forks: self.narrow_forks,
                ..crate::metrics::ScoreConfig::default().trace
            },
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
    // A finite number within `range`, or a one-line error naming the field and what is
    // allowed (`allowed`: the range as printed, and what it means).
    let ranged = |field: &str,
                  value: Option<f64>,
                  default: f64,
                  range: std::ops::RangeInclusive<f64>,
                  allowed: &str|
     -> Result<f64> {
        let x = finite(&at(field), value.unwrap_or(default))?;
        if !range.contains(&x) {
            return Err(Error::invalid(
                at(field),
                format!("{x} is out of range; allowed {allowed}"),
            ));
        }
        Ok(x)
    };
    let defaults = crate::metrics::ScoreConfig::default();
    let split = |field: &str, value: Option<f64>, default: f64| -> Result<f64> {
        ranged(
            field,
            value,
            default,
            1e-9..=1e-2,
            "[1e-9, 1e-2] (a share of the light; smaller is smoother and slower)",
        )
    };
    let score = ScoreSettings {
        material,
        ri: rs.ri,
        head_shadow_deg: ranged(
            "score.head_shadow",
            rs.head_shadow,
            0.0,
            0.0..=60.0,
            "[0, 60] degrees (0 = none)",
        )?,
        polarization: rs.polarization.unwrap_or(true),
        split_threshold: split(
            "score.split_threshold",
            rs.split_threshold,
            defaults.trace.split_threshold,
        )?,
        fire_split_threshold: split(
            "score.fire_split_threshold",
            rs.fire_split_threshold,
            defaults.fire_split_threshold,
        )?,
        ray_floor: ranged(
            "score.ray_floor",
            rs.ray_floor,
            defaults.trace.ray_floor,
            0.0..=0.5,
            "[0, 0.5] (a share of a narrow beam's power; 0 follows every ray to the end)",
        )?,
        narrow_forks: rs.narrow_forks.unwrap_or(defaults.trace.narrow_forks),
    };
    Ok(score)
}
