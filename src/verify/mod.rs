//! The photon tracer as referee of the beam tracer: the one place where both tracers meet.
//!
//! The tracers know nothing of scores and nothing of each other; this module sits above both
//! (and above [`metrics`](crate::metrics), whose scores it re-measures) and below the
//! optimizer and the command line, which only call it:
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
//! * [`verify_scores`]: those figures as [`Check`] rows against a cut's beam [`Scores`]
//!   (`facetlab score --verify`), flagged beyond [`SIGMA`] standard errors.
//! * [`photon_report`]: the optimizer's verification of a winner, a [`VerifyReport`]: the
//!   thesis's top-face shares ([`thesis_rows`]: top-45° and top-90° under overhead and
//!   off-centre undirected light, top-45° under the directed light rotated 0–180°), which have
//!   no beam value, and the Monte Carlo overhead light return and brilliance, which carry the
//!   beam value; [`VerifyReport::disagreements`] names the rows beyond a threshold.
//! * [`Verifier`] (in `verifier.rs`): what a check of one cut is, as the optimizer calls it on
//!   its winners (the real one is [`photon_report`] under a config's settings; tests pass
//!   functions), and [`Verification`], its result as a run reports it: the rows, the names
//!   flagged beyond a threshold, the time taken, the verifier's error.
//!
//! Each figure comes with its standard error, so a disagreement can be stated in standard
//! errors. Every call to the photon tracer is in `mod.rs`.

mod verifier;

pub use verifier::{Verification, Verifier};

use crate::cut::Cut;
use crate::error::Result;
use crate::geometry::{FacetPlane, Polyhedron};
use crate::metrics::lighting::Lighting;
use crate::metrics::{score, ScoreConfig, ScoreName, Scores};
use crate::photon::{
    self, Absorption, Light, LightKind, Tally, TraceConfig, WavelengthSampling, ROTATION_ANGLES,
};
use serde::Serialize;

/// The threshold, in standard errors, beyond which `facetlab score --verify` flags a check
/// (the optimizer's is `[verify] sigma`, default 4 too).
pub const SIGMA: f64 = 4.0;

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
    let n = cfg.tilts.len().max(1) as f64;
    let (mut iso, mut iso_var, mut cos, mut cos_var, mut both, mut both_var) =
        (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (k, tilt) in cfg.tilts.iter().enumerate() {
        let world = turned(solid, tilt.rotation())?;
        let pc = photon_config(cfg, photons, seed.wrapping_add(k as u64 * 0x9E37_79B9));
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

impl Check {
    /// Whether the beam value lies more than `sigma` standard errors from the estimate.
    pub fn beyond(&self, sigma: f64) -> bool {
        self.z.abs() > sigma
    }
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
    let row = |name: ScoreName, e: Estimate| {
        let beam = name.of(scores).unwrap_or(f64::NAN);
        Check {
            name: name.to_string(),
            beam,
            photon: e.value,
            stderr: e.stderr,
            z: e.z(beam),
        }
    };
    Ok(vec![
        row(ScoreName::OverheadLightReturn, olr),
        row(ScoreName::Brilliance, b.brilliance),
        row(ScoreName::BrillianceIso, b.brilliance_iso),
        row(ScoreName::BrillianceCos, b.brilliance_cos),
    ])
}

/// One verified quantity.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VerifyRow {
    /// Name, e.g. `top45_overhead_undirected`, `brilliance_mc`.
    pub name: String,
    /// Monte Carlo estimate.
    pub value: f64,
    /// Its standard error.
    pub stderr: f64,
    /// The beam tracer's exact value of the same quantity, when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beam: Option<f64>,
}

impl VerifyRow {
    /// A row without a beam value.
    pub fn new(name: impl Into<String>, value: f64, stderr: f64) -> VerifyRow {
        VerifyRow {
            name: name.into(),
            value,
            stderr,
            beam: None,
        }
    }

    /// The same row compared with a beam value.
    pub fn with_beam(mut self, beam: f64) -> VerifyRow {
        self.beam = Some(beam);
        self
    }

    /// `|value − beam| / stderr`, when there is a beam value. Differences within rounding
    /// (1e-12 relative) count as 0; a real difference with a zero standard error is infinite.
    pub fn z(&self) -> Option<f64> {
        let b = self.beam?;
        Some(z_score(self.value, self.stderr, b))
    }

    /// Whether the Monte Carlo value and the beam value disagree beyond `sigma` standard errors.
    pub fn disagrees(&self, sigma: f64) -> bool {
        self.z().is_some_and(|z| z.is_nan() || z > sigma)
    }
}

/// `|value − reference| / stderr` (see [`VerifyRow::z`]); NaN anywhere gives infinity.
pub fn z_score(value: f64, stderr: f64, reference: f64) -> f64 {
    let d = (value - reference).abs();
    if d.is_nan() || stderr.is_nan() {
        return f64::INFINITY;
    }
    if d <= 1e-12 * reference.abs().max(1.0) {
        return 0.0;
    }
    if stderr > 0.0 {
        d / stderr
    } else {
        f64::INFINITY
    }
}

/// What a verifier found for one cut.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct VerifyReport {
    /// Photons traced per light.
    pub photons: u64,
    /// The rows, in display order.
    pub rows: Vec<VerifyRow>,
}

impl VerifyReport {
    /// Names of the rows that disagree with the beam tracer beyond `sigma`.
    pub fn disagreements(&self, sigma: f64) -> Vec<String> {
        self.rows
            .iter()
            .filter(|r| r.disagrees(sigma))
            .map(|r| r.name.clone())
            .collect()
    }
}

fn top_rows(rows: &mut Vec<VerifyRow>, t: &Tally, label: &str) {
    let n = t.counts.hit;
    let c = &t.counts.categories;
    let s45 = photon::share(c[0], n);
    let s90 = photon::share(c[0] + c[1], n);
    rows.push(VerifyRow::new(format!("top45_{label}"), s45.0, s45.1));
    rows.push(VerifyRow::new(format!("top90_{label}"), s90.0, s90.1));
}

/// The thesis's top-face shares of `cut` (thesis settings: depth 6, flat 0.1 absorption,
/// 380–780 nm; shot until `photons` hit): `top45_`/`top90_` under overhead and off-centre
/// undirected light, and `top45_directed_A` under the directed light rotated to each angle
/// `A` of [`ROTATION_ANGLES`]. No beam value: the beam tracer has no such light.
pub fn thesis_rows(cut: &Cut, photons: u64, seed: u64) -> Result<Vec<VerifyRow>> {
    let thesis = TraceConfig {
        photons,
        until_hit: true,
        seed,
        ..TraceConfig::thesis()
    };
    let mut rows = Vec::new();
    for (light, label) in [(Light::overhead(), "overhead"), (Light::offset(), "offset")] {
        let t = photon::trace_cut(&cut.solid, &cut.name, &light, &thesis, None)?;
        top_rows(&mut rows, &t, label);
    }
    for &a in ROTATION_ANGLES.iter() {
        let t = photon::trace_cut(
            &cut.solid,
            &cut.name,
            &Light::rotated(LightKind::Directed, a),
            &thesis,
            None,
        )?;
        let s45 = photon::share(t.counts.categories[0], t.counts.hit);
        rows.push(VerifyRow::new(
            format!("top45_directed_{a:.0}"),
            s45.0,
            s45.1,
        ));
    }
    Ok(rows)
}

/// The optimizer's photon-tracer report on `cut` under the scoring settings `cfg`: the
/// [`thesis_rows`], then the Monte Carlo overhead light return (`photons` photons) and
/// brilliance (a tenth of them per pose, at least 1000), each with the beam tracer's value.
pub fn photon_report(
    cut: &Cut,
    cfg: &ScoreConfig,
    photons: u64,
    seed: u64,
) -> Result<VerifyReport> {
    photon_report_given(cut, cfg, photons, seed, None)
}

/// [`photon_report`] given the beam tracer's `(overhead_light_return, brilliance)` of `cut`
/// under `cfg` when the caller has them (the beam tracer is then not run again; with `None`
/// it is).
pub fn photon_report_given(
    cut: &Cut,
    cfg: &ScoreConfig,
    photons: u64,
    seed: u64,
    beam: Option<(f64, f64)>,
) -> Result<VerifyReport> {
    let mut rows = thesis_rows(cut, photons, seed)?;
    let (beam_olr, beam_brilliance) = beam.unwrap_or_else(|| {
        let s = score(&cut.solid, cfg);
        (s.overhead_light_return, s.brilliance)
    });
    let olr = overhead_light_return_mc(&cut.solid, cfg, photons, seed)?;
    rows.push(
        VerifyRow::new("overhead_light_return_mc", olr.value, olr.stderr).with_beam(beam_olr),
    );
    // Brilliance averages many poses: a tenth of the photons per pose keeps the run short.
    let per_pose = (photons / 10).max(1000);
    let b = brilliance_mc(&cut.solid, cfg, per_pose, seed.wrapping_add(1))?;
    rows.push(
        VerifyRow::new("brilliance_mc", b.brilliance.value, b.brilliance.stderr)
            .with_beam(beam_brilliance),
    );
    Ok(VerifyReport { photons, rows })
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
                    &crate::beam::Medium::Isotropic(cfg.material.ri(cfg.wavelength_nm)),
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

    /// Coloured stones (issue 25's check 3): the beam tracer's exact absorption and the photon
    /// tracer's per-photon Beer–Lambert agree on the light returned upward in every band —
    /// the face-up colour is a sum of these, band by band — within 4 standard errors, on
    /// three cuts in three published colours (6.5 mm wide).
    #[test]
    fn beam_and_photon_tracers_agree_on_coloured_light_return() {
        let cuts = [
            ("round", "ruby"),
            ("princess", "emerald"),
            ("octahedron", "blue-sapphire"),
        ];
        for ((name, solid), (_, variety)) in solids().into_iter().zip(cuts) {
            let material = Material::by_name(variety).unwrap();
            let colour = material.colour.clone().unwrap();
            let mm_per_unit = 6.5 / crate::cut::units::outline_size(solid.vertices()).1;
            let stone = Stone::new(&solid);
            for nm in [450.0, 550.0, 650.0] {
                let opts = crate::beam::TraceOptions {
                    split_threshold: 1e-5,
                    absorption: colour.alpha(nm) * mm_per_unit,
                    ..Default::default()
                };
                // Birefringent by default (ruby and sapphire, emerald): the crystal with
                // its absorption per mode; the photons take the same material.
                let axis = material.uniaxial.as_ref().unwrap().axis.vector();
                let medium = crate::beam::Medium::of(&material, nm, axis, mm_per_unit, true);
                let beam = overhead_light_return_with(&stone, &medium, &opts);
                let t = photon::trace(
                    &solid,
                    &Light::directed(0.0),
                    &TraceConfig {
                        absorption: Absorption::Body {
                            width_mm: mm_per_unit,
                        },
                        material: material.clone(),
                        wavelengths: WavelengthSampling::Fixed(nm),
                        polarization: true,
                        ..photon_config(&ScoreConfig::default(), 60_000, 5)
                    },
                    None,
                )
                .unwrap();
                let (value, stderr) = t.light_return();
                let z = (value - beam) / stderr;
                eprintln!("{name} {variety} {nm} nm: beam {beam:.5} photon {value:.5} ± {stderr:.5} ({z:.2} se)");
                assert!(
                    z.abs() < 4.0,
                    "{name} {variety} {nm} nm: {beam} vs {value} ± {stderr}"
                );
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

    /// The report given the beam scores is the report that computes them, row for row, and
    /// the optimizer's verifier finds them in an evaluator's score map.
    #[test]
    fn a_report_given_the_beam_scores_is_the_same_report() {
        let cut = crate::io::load_cut("tolkowsky").unwrap();
        let cfg = ScoreConfig {
            tilts: vec![Tilt::FACE_UP],
            ..ScoreConfig::default()
        };
        let s = score(&cut.solid, &cfg);
        let full = photon_report(&cut, &cfg, 1500, 3).unwrap();
        let given = photon_report_given(
            &cut,
            &cfg,
            1500,
            3,
            Some((s.overhead_light_return, s.brilliance)),
        )
        .unwrap();
        assert_eq!(full, given);
        assert_eq!(full.rows.last().unwrap().beam, Some(s.brilliance));
        // Other beam values would show: the given ones are used.
        let other = photon_report_given(&cut, &cfg, 1500, 3, Some((0.5, 0.25))).unwrap();
        assert_eq!(other.rows.last().unwrap().beam, Some(0.25));
    }

    #[test]
    fn flags_beyond_four_standard_errors() {
        let r = VerifyRow::new("brilliance_mc", 0.50, 0.01);
        assert_eq!(r.z(), None);
        assert!(!r.disagrees(4.0), "no beam value, nothing to compare");
        let ok = r.clone().with_beam(0.539);
        assert!((ok.z().unwrap() - 3.9).abs() < 1e-9);
        assert!(!ok.disagrees(4.0));
        let edge = r.clone().with_beam(0.54);
        assert!(!edge.disagrees(4.0 + 1e-9) && edge.disagrees(3.99));
        let bad = r.clone().with_beam(0.46 - 1e-6);
        assert!(bad.disagrees(4.0));
        // Zero standard error: equal (within rounding) is fine, different is flagged.
        let exact = VerifyRow::new("x", 0.3, 0.0).with_beam(0.1 + 0.2);
        assert_eq!(exact.z(), Some(0.0));
        assert!(!exact.disagrees(4.0));
        assert!(VerifyRow::new("x", 0.3, 0.0).with_beam(0.31).disagrees(4.0));
        // NaN never passes.
        assert!(VerifyRow::new("x", f64::NAN, 0.1)
            .with_beam(0.3)
            .disagrees(4.0));
        assert!(VerifyRow::new("x", 0.3, f64::NAN)
            .with_beam(0.3 + 1e-3)
            .disagrees(4.0));
        let rep = VerifyReport {
            photons: 10,
            rows: vec![ok, bad, VerifyRow::new("top45", 0.7, 0.01)],
        };
        assert_eq!(rep.disagreements(4.0), vec!["brilliance_mc".to_string()]);
    }
}
