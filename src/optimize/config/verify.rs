//! `[verify]`: the winners — how many distinct ones, how far apart in the box, and the photons
//! and the threshold of their photon-tracer check.

use super::fields::{defaults, finite, At};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// `[verify]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawVerify {
    /// How many distinct winners to verify (0 = none); the start is verified too.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub winners: Option<u64>,
    /// Photons per verified cut and light.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub photons: Option<u64>,
    /// Smallest distance between two winners, in the unit box of the free parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_distance: Option<f64>,
    /// Disagreement threshold in standard errors; default 4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma: Option<f64>,
}

/// Verification settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct VerifySettings {
    /// Distinct winners to verify.
    pub winners: usize,
    /// Photons per cut and light.
    pub photons: u64,
    /// Smallest distance between winners in the unit box.
    pub min_distance: f64,
    /// Disagreement threshold in standard errors.
    pub sigma: f64,
}

/// Validate `[verify]`.
pub(super) fn validate(rv: &RawVerify, at: At) -> Result<VerifySettings> {
    let count = |field: &str, v: u64, lo: u64, hi: u64| super::fields::count(at, field, v, lo, hi);
    let min_distance = finite(
        &at("verify.min_distance"),
        rv.min_distance.unwrap_or(defaults::MIN_DISTANCE),
    )?;
    if !(0.0..=1.0).contains(&min_distance) {
        return Err(Error::invalid(
            at("verify.min_distance"),
            format!("{min_distance} is out of range; allowed [0, 1] (a distance in the unit box of the free parameters)"),
        ));
    }
    let sigma = finite(&at("verify.sigma"), rv.sigma.unwrap_or(defaults::SIGMA))?;
    if sigma <= 0.0 {
        return Err(Error::invalid(
            at("verify.sigma"),
            format!("{sigma} is not allowed; give a positive number of standard errors"),
        ));
    }
    let verify = VerifySettings {
        winners: count(
            "verify.winners",
            rv.winners.unwrap_or(defaults::WINNERS),
            0,
            100,
        )? as usize,
        photons: count(
            "verify.photons",
            rv.photons.unwrap_or(defaults::PHOTONS),
            1,
            10_000_000_000,
        )?,
        min_distance,
        sigma,
    };
    Ok(verify)
}
