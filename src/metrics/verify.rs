//! The photon tracer as referee of the beam tracer's scores.
//!
//! * [`overhead_light_return_mc`]: directed light straight down over the whole stone, no
//!   absorption, unlimited depth, the scores' wavelength and polarization: the share of photons
//!   that hit the stone and leave upward. The beam tracer's `overhead_light_return` measures
//!   the same thing exactly.
//! * [`brilliance_mc`]: for each pose of [`ScoreConfig::tilts`] the stone is turned into the
//!   world, photons come straight down from the viewer's side over the whole stone, and each
//!   photon that leaves in direction `w` scores the environment's radiance from `w`
//!   ([`Lighting::iso`], [`Lighting::cos`], head shadow included). By reciprocity this is the
//!   light the viewer sees, the quantity the beam tracer's brilliance computes exactly.
//!
//! Each figure comes with its standard error, so a disagreement can be stated in standard
//! errors.

use super::lighting::Lighting;
use super::{ScoreConfig, Scores};
use crate::error::Result;
use crate::geometry::{FacetPlane, Polyhedron};
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
fn photon_config(cfg: &ScoreConfig, photons: u64, seed: u64) -> TraceConfig {
    TraceConfig {
        photons,
        until_hit: false,
        depth: None,
        absorption: Absorption::None,
        polarization: cfg.polarization,
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
        .facets
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
    let n = cfg.tilts.len().max(1) as f64;
    let (mut iso, mut iso_var, mut cos, mut cos_var, mut both, mut both_var) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, tilt) in cfg.tilts.iter().enumerate() {
        let world = turned(solid, tilt.rotation())?;
        let pc = photon_config(cfg, photons, seed.wrapping_add(k as u64 * 0x9E37_79B9));
        let down = Light::directed(0.0);
        // One trace with the mean of the two environments as its weight, and one each for
        // ISO and COS: the same seed makes them the same photons, so the mean's error is
        // its own (not a sum of independent errors).
        let i = photon::trace_weighted(&world, &down, &pc, &|w| light.iso(w))?;
        let c = photon::trace_weighted(&world, &down, &pc, &|w| light.cos(w))?;
        let b =
            photon::trace_weighted(&world, &down, &pc, &|w| 0.5 * (light.iso(w) + light.cos(w)))?;
        iso += i.mean;
        iso_var += i.stderr * i.stderr;
        cos += c.mean;
        cos_var += c.stderr * c.stderr;
        both += b.mean;
        both_var += b.stderr * b.stderr;
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

/// One row of a verification: a beam-tracer figure, its Monte Carlo estimate, and the distance
/// in standard errors.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Check {
    /// What is compared (`overhead_light_return`, `brilliance`, …).
    pub name: String,
    /// The beam tracer's value.
    pub beam: f64,
    /// The photon tracer's estimate.
    pub photon: f64,
    /// Its standard error.
    pub stderr: f64,
    /// (beam − photon) / stderr.
    pub z: f64,
}

/// Re-measure `overhead_light_return` and brilliance (ISO, COS, mean) of `scores` with the
/// photon tracer.
pub fn verify_scores(
    solid: &Polyhedron,
    cfg: &ScoreConfig,
    scores: &Scores,
    photons: u64,
    seed: u64,
) -> Result<Vec<Check>> {
    let olr = overhead_light_return_mc(solid, cfg, photons, seed)?;
    let b = brilliance_mc(solid, cfg, photons, seed.wrapping_add(1))?;
    let row = |name: &str, beam: f64, e: Estimate| Check {
        name: name.to_string(),
        beam,
        photon: e.value,
        stderr: e.stderr,
        z: e.z(beam),
    };
    Ok(vec![
        row("overhead_light_return", scores.overhead_light_return, olr),
        row("brilliance", scores.brilliance, b.brilliance),
        row("brilliance_iso", scores.brilliance_iso, b.brilliance_iso),
        row("brilliance_cos", scores.brilliance_cos, b.brilliance_cos),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::Stone;
    use crate::metrics::{overhead_light_return_with, score, Tilt};
    use crate::optics::Material;

    fn octahedron() -> Polyhedron {
        crate::testkit::octahedron_of(0.5)
    }

    fn solids() -> Vec<(&'static str, Polyhedron)> {
        vec![
            ("round", crate::io::load_cut("tolkowsky").unwrap().solid),
            ("princess", crate::io::load_cut("princess").unwrap().solid),
            ("octahedron", octahedron()),
        ]
    }

    /// The two tracers agree on the primitive figure within 4 standard errors: three solids,
    /// polarization on and off.
    #[test]
    fn beam_and_photon_tracers_agree_on_overhead_light_return() {
        for (name, solid) in solids() {
            for polarization in [true, false] {
                let cfg = ScoreConfig {
                    polarization,
                    ..ScoreConfig::default()
                };
                let opts = crate::beam::TraceOptions {
                    polarization,
                    split_threshold: 1e-5,
                    ..Default::default()
                };
                let beam = overhead_light_return_with(
                    &Stone::new(&solid),
                    cfg.material.ri(cfg.wavelength_nm),
                    &opts,
                );
                let mc = overhead_light_return_mc(&solid, &cfg, 150_000, 11).unwrap();
                let z = mc.z(beam);
                eprintln!(
                    "{name} pol {polarization}: beam {beam:.5} photon {:.5} ± {:.5} ({z:.2} se)",
                    mc.value, mc.stderr
                );
                assert!(
                    z.abs() < 4.0,
                    "{name} pol {polarization}: beam {beam} vs photon {} ± {} ({z:.2} se)",
                    mc.value,
                    mc.stderr
                );
                assert!(mc.stderr < 2e-3);
            }
        }
    }

    /// Monte Carlo brilliance under the same lighting and poses agrees with the beam tracer's.
    #[test]
    fn beam_and_photon_brilliance_agree() {
        let solid = crate::io::load_cut("tolkowsky").unwrap().solid;
        let cfg = ScoreConfig {
            tilts: vec![
                Tilt::FACE_UP,
                Tilt {
                    tilt_deg: 15.0,
                    azimuth_deg: 30.0,
                },
            ],
            head_shadow_deg: 10.0,
            ..ScoreConfig::default()
        };
        let s = score(&solid, &cfg);
        let checks = verify_scores(&solid, &cfg, &s, 60_000, 5).unwrap();
        for c in &checks {
            eprintln!(
                "{}: beam {:.5} photon {:.5} ± {:.5} ({:.2} se)",
                c.name, c.beam, c.photon, c.stderr, c.z
            );
            assert!(c.z.abs() < 4.0, "{c:?}");
        }
        // A different material changes the figures: the check is not vacuous.
        let glass = ScoreConfig {
            material: Material::glass(),
            ..cfg.clone()
        };
        let g = brilliance_mc(&solid, &glass, 20_000, 5).unwrap();
        assert!(
            g.brilliance.value < s.brilliance - 10.0 * g.brilliance.stderr,
            "{g:?}"
        );
    }
}
