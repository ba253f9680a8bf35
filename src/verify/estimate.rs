//! The photon tracer's estimates of the beam tracer's figures: [`overhead_light_return_mc`]
//! and [`brilliance_mc`], each an [`Estimate`] with its standard error. Every call to the
//! photon tracer under the scores' settings is here.

use crate::error::Result;
use crate::geometry::{canonical, FacetPlane, Polyhedron};
use crate::metrics::lighting::Lighting;
use crate::metrics::ScoreConfig;
use crate::optics::OpticAxis;
use crate::photon::{self, Absorption, Light, TraceConfig, WavelengthSampling};
use serde::Serialize;

/// A Monte Carlo figure: value and standard error.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Estimate {
    /// The estimate.
    pub value: f64,
    /// Its standard error.
    pub stderr: f64,
}

impl Estimate {
    /// `(exact − value) / stderr`: how many standard errors `exact` lies from the estimate
    /// (infinite when the error is 0 and they differ).
    pub fn z(&self, exact: f64) -> f64 {
        let d = exact - self.value;
        if self.stderr > 0.0 {
            d / self.stderr
        } else if d.abs() < 1e-12 {
            0.0
        } else {
            f64::INFINITY
        }
    }
}

/// Photon-tracer settings matching the scores: no absorption, unlimited depth, the scores'
/// material, wavelength and polarization.
pub(super) fn photon_config(cfg: &ScoreConfig, photons: u64, seed: u64) -> TraceConfig {
    TraceConfig {
        photons,
        until_hit: false,
        depth: None,
        absorption: Absorption::None,
        polarization: cfg.trace.polarization,
        material: cfg.material.clone(),
        wavelengths: WavelengthSampling::Fixed(cfg.wavelength_nm),
        seed,
        record_paths: 0,
    }
}

/// Monte Carlo `overhead_light_return` with `photons` photons.
pub fn overhead_light_return_mc(
    solid: &Polyhedron,
    cfg: &ScoreConfig,
    photons: u64,
    seed: u64,
) -> Result<Estimate> {
    let t = photon::trace(
        solid,
        &Light::directed(0.0),
        &photon_config(cfg, photons, seed),
        None,
    )?;
    let (value, stderr) = t.light_return();
    Ok(Estimate { value, stderr })
}

/// Monte Carlo brilliance: ISO, COS and their mean, averaged over the poses as the beam
/// tracer does.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BrillianceMc {
    /// (ISO + COS) / 2.
    pub brilliance: Estimate,
    /// Under ISO lighting.
    pub brilliance_iso: Estimate,
    /// Under COS lighting.
    pub brilliance_cos: Estimate,
}

/// The solid turned by the rotation of a pose (stone → world).
fn turned(solid: &Polyhedron, rot: glam::DMat3) -> Result<Polyhedron> {
    let planes: Vec<FacetPlane> = solid
        .facets()
        .iter()
        .map(|f| {
            FacetPlane::new(
                rot * f.plane.normal,
                f.plane.offset,
                f.name.clone(),
                f.tier.clone(),
            )
        })
        .collect();
    Polyhedron::from_planes(&planes)
}

/// Monte Carlo brilliance with `photons` photons per pose (each pose gets its own seed).
pub fn brilliance_mc(
    solid: &Polyhedron,
    cfg: &ScoreConfig,
    photons: u64,
    seed: u64,
) -> Result<BrillianceMc> {
    let light = Lighting::new(cfg.head_shadow_deg, &cfg.spots);
    // The beam scores turn the stone's canonical placement into each pose, a birefringent
    // stone's optic axis carried into it (`geometry::canonical`): so do the photons.
    let axis = cfg
        .material
        .uniaxial
        .as_ref()
        .map(|u| canonical::canonical_axis(solid, u.axis.vector()));
    let solid = &canonical::canonical(solid);
    let n = cfg.tilts.len().max(1) as f64;
    let (mut iso, mut iso_var, mut cos, mut cos_var, mut both, mut both_var) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, tilt) in cfg.tilts.iter().enumerate() {
        let rot = tilt.rotation();
        let world = turned(solid, rot)?;
        let mut pc = photon_config(cfg, photons, seed.wrapping_add(k as u64 * 0x9E37_79B9));
        // A birefringent stone's optic axis turns with it: the photon tracer takes the axis
        // in the coordinates of the solid it traces.
        if let (Some(u), Some(axis)) = (pc.material.uniaxial.as_mut(), axis) {
            u.axis = OpticAxis::along(rot * axis);
        }
        let down = Light::directed(0.0);
        // ISO, COS and their mean summed over the same photons in one trace, so the mean's
        // error is its own (not a sum of independent errors).
        let t = photon::trace_weights(&world, &down, &pc, &|w| {
            let (i, c) = (light.iso(w), light.cos(w));
            [i, c, 0.5 * (i + c)]
        })?;
        let (m, se) = (t.mean, t.stderr);
        iso += m[0];
        iso_var += se[0] * se[0];
        cos += m[1];
        cos_var += se[1] * se[1];
        both += m[2];
        both_var += se[2] * se[2];
    }
    let e = |v: f64, var: f64| Estimate {
        value: v / n,
        stderr: var.sqrt() / n,
    };
    Ok(BrillianceMc {
        brilliance: e(both, both_var),
        brilliance_iso: e(iso, iso_var),
        brilliance_cos: e(cos, cos_var),
    })
}
