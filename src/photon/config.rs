//! [`TraceConfig`]: what the photon tracer traces and how (photons, depth, absorption,
//! polarization, material, wavelengths, seed), and its checks.

use crate::error::{shown, Error, Result};
use crate::geometry::DVec3;
use crate::optics::color::{LAMBDA_MAX, LAMBDA_MIN};
use crate::optics::{Absorption, Material};

/// Interaction cap of the "unlimited" depth mode.
pub const UNLIMITED_CAP: u32 = 100_000;
/// Most photons one run may shoot (or, with `until_hit`, need to hit): 1e11. At the few
/// million photons per second a core traces, that is already hours of work, and the standard
/// error of a share is below 2e-6, far under any difference between cuts that matters.
pub const MAX_PHOTONS: u64 = 100_000_000_000;

/// How each photon's wavelength is chosen.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WavelengthSampling {
    /// Uniform over 380–780 nm (the thesis).
    Uniform,
    /// Weighted by the CIE D65 illuminant over 380–780 nm.
    D65,
    /// Every photon at this wavelength, nm.
    Fixed(f64),
}

impl WavelengthSampling {
    /// `uniform`, `d65` or a wavelength in 380–780 nm (`550`, `550nm`); an error names
    /// `field`.
    ///
    /// ```
    /// use facetlab::photon::WavelengthSampling;
    /// assert_eq!(WavelengthSampling::parse("spectrum", "550nm").unwrap(), WavelengthSampling::Fixed(550.0));
    /// assert!(WavelengthSampling::parse("spectrum", "900").is_err());
    /// ```
    pub fn parse(field: &str, text: &str) -> crate::error::Result<WavelengthSampling> {
        match text.trim().to_ascii_lowercase().as_str() {
            "uniform" => Ok(WavelengthSampling::Uniform),
            "d65" => Ok(WavelengthSampling::D65),
            s => match s.trim_end_matches("nm").parse::<f64>() {
                Ok(l) if (380.0..=780.0).contains(&l) => Ok(WavelengthSampling::Fixed(l)),
                _ => Err(crate::error::Error::invalid(
                    field,
                    format!(
                        "`{text}` is not allowed; use uniform, d65, or a wavelength in 380–780 nm"
                    ),
                )),
            },
        }
    }
}

/// What to trace and how.
#[derive(Clone, Debug)]
pub struct TraceConfig {
    /// Photons to shoot, or (with `until_hit`) photons that must hit the stone.
    pub photons: u64,
    /// Shoot until exactly `photons` have hit the stone (the rotation sweep's rule).
    pub until_hit: bool,
    /// Surface interactions per photon (entry included); `None` is unlimited (capped at
    /// [`UNLIMITED_CAP`]).
    pub depth: Option<u32>,
    /// Absorption model.
    pub absorption: Absorption,
    /// Carry a Stokes vector and use Mueller matrices (true), or the unpolarized average.
    pub polarization: bool,
    /// The stone's material ([`Material::constant`] for a fixed index).
    pub material: Material,
    /// Wavelength sampling.
    pub wavelengths: WavelengthSampling,
    /// Seed of the random numbers.
    pub seed: u64,
    /// Record the paths of the first this-many photons that hit the stone (for pictures).
    pub record_paths: usize,
}

impl TraceConfig {
    /// The thesis's experiment: 1 000 000 photons, depth 6, the flat 0.1 absorption roulette,
    /// diamond with wavelengths uniform over 380–780 nm, seed 1 — with polarization on.
    pub fn thesis() -> TraceConfig {
        TraceConfig {
            photons: 1_000_000,
            until_hit: false,
            depth: Some(6),
            absorption: Absorption::Thesis,
            polarization: true,
            material: Material::diamond(),
            wavelengths: WavelengthSampling::Uniform,
            seed: 1,
            record_paths: 0,
        }
    }

    /// Check every number; errors name the setting (`photon count`, `trace depth`, …; the
    /// binary says which flag sets it).
    pub fn validate(&self) -> Result<()> {
        check_photons(self.photons)?;
        if let Some(d) = self.depth {
            if d == 0 || d > UNLIMITED_CAP {
                return Err(Error::invalid(
                    "trace depth",
                    format!("{d} is out of range; allowed 1..={UNLIMITED_CAP} or `unlimited`"),
                ));
            }
        }
        if let Absorption::Body { width_mm } = self.absorption {
            if !(width_mm.is_finite() && width_mm > 0.0) {
                return Err(Error::invalid(
                    "absorption model",
                    format!("colour:{width_mm}: the stone's width must be a number of mm > 0"),
                ));
            }
            if self.material.colour.is_none() {
                return Err(Error::invalid(
                    "absorption model",
                    format!(
                        "colour: {} has no body colour; choose a coloured material (allowed: a coloured variety such as ruby, emerald or blue-sapphire, `facetlab materials`)",
                        self.material.name
                    ),
                ));
            }
        }
        if let Absorption::Beer(k) = self.absorption {
            if !(k.is_finite() && k >= 0.0) {
                return Err(Error::invalid("absorption model", format!("beer:{k}: the coefficient must be a finite number >= 0 (per girdle diameter)")));
            }
        }
        if let WavelengthSampling::Fixed(l) = self.wavelengths {
            if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&l) {
                return Err(Error::invalid(
                    "fixed wavelength",
                    format!("{l} nm is out of range; allowed 380–780 nm"),
                ));
            }
        }
        for l in [LAMBDA_MIN, LAMBDA_MAX] {
            let n = self.material.ri(l);
            if !(n.is_finite() && n > 1.0 && n <= 10.0) {
                return Err(Error::invalid(
                    "refractive index",
                    format!(
                        "refractive index {} is out of range; allowed (1, 10]",
                        shown(n)
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Check a photon count: at least 1, at most [`MAX_PHOTONS`]; the error names the `photon
/// count` and says why.
pub fn check_photons(photons: u64) -> Result<()> {
    if photons == 0 {
        return Err(Error::invalid("photon count", "must be at least 1"));
    }
    if photons > MAX_PHOTONS {
        return Err(Error::invalid(
            "photon count",
            format!(
                "{photons} is too many; allowed at most {MAX_PHOTONS} (1e11): at a few million photons per second that is already hours, and shares are then known to ±2e-6"
            ),
        ));
    }
    Ok(())
}

/// Photons per deterministic chunk.
pub const CHUNK: u64 = 8192;

/// How many exit weights [`trace_weights`](super::trace_weights) sums at once.
pub const WEIGHTS: usize = 3;

/// Exit weights: [`WEIGHTS`] functions of the exit direction, computed together.
pub type ExitWeights<'a> = dyn Fn(DVec3) -> [f64; WEIGHTS] + Sync + 'a;
