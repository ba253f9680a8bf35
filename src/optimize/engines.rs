//! The real objective and verifier: the beam tracer's scores ([`BeamEvaluator`]) and the photon
//! tracer's thesis metrics plus Monte Carlo brilliance ([`PhotonVerifier`]).

use super::verify::{VerifyReport, VerifyRow};
use super::{Config, Evaluator, ScoreSet, Verifier};
use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::verify::{brilliance_mc, overhead_light_return_mc};
use crate::metrics::{score, ScoreConfig, Scores};
use crate::photon::{self, Light, LightKind, Tally, TraceConfig, ROTATION_ANGLES};

/// Scores a cut with the beam tracer ([`crate::metrics::score`]). Brilliance, fire and
/// scintillation are the objective's terms; the other scores ride along as extras.
///
/// It is built from the optimization [`Config`] it serves (its `[score]` section), so the
/// scores an optimizer climbs are always those of the config's material and lighting.
#[derive(Clone, Debug)]
pub struct BeamEvaluator {
    config: ScoreConfig,
}

impl BeamEvaluator {
    /// The evaluator for a config: its `[score]` settings (material, head shadow, polarization).
    pub fn new(config: &Config) -> Self {
        BeamEvaluator {
            config: config.score.score_config(),
        }
    }

    /// The scoring settings in use.
    pub fn score_config(&self) -> &ScoreConfig {
        &self.config
    }

    /// The scores as the optimizer reports them.
    pub fn score_set(s: &Scores) -> ScoreSet {
        let mut set = ScoreSet::new(s.brilliance, s.fire, s.scintillation);
        set.extra = vec![
            ("brilliance_iso".into(), s.brilliance_iso),
            ("brilliance_cos".into(), s.brilliance_cos),
            ("overhead_light_return".into(), s.overhead_light_return),
            ("aset_blue".into(), s.aset.blue),
            ("aset_red".into(), s.aset.red),
            ("aset_green".into(), s.aset.green),
            ("aset_leak".into(), s.aset.leak),
        ];
        set
    }
}

impl Evaluator for BeamEvaluator {
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet> {
        Ok(Self::score_set(&score(&cut.solid, &self.config)))
    }
}

/// Re-scores a cut with the photon tracer: the thesis's top-45° and top-90° face shares under
/// overhead and off-centre undirected light and under the directed light rotated 0–180°
/// (thesis settings: depth 6, flat 0.1 absorption, 380–780 nm; shot until `photons` hit), and
/// Monte Carlo overhead light return and brilliance under the beam tracer's lighting, which
/// carry the beam tracer's value for comparison. Built, like [`BeamEvaluator`], from the
/// config it serves.
#[derive(Clone, Debug)]
pub struct PhotonVerifier {
    config: ScoreConfig,
}

impl PhotonVerifier {
    /// The verifier for a config: its `[score]` settings.
    pub fn new(config: &Config) -> Self {
        PhotonVerifier {
            config: config.score.score_config(),
        }
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

impl Verifier for PhotonVerifier {
    fn verify(&self, cut: &Cut, photons: u64, seed: u64) -> Result<VerifyReport> {
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
        let beam = score(&cut.solid, &self.config);
        let olr = overhead_light_return_mc(&cut.solid, &self.config, photons, seed)?;
        rows.push(
            VerifyRow::new("overhead_light_return_mc", olr.value, olr.stderr)
                .with_beam(beam.overhead_light_return),
        );
        // Brilliance averages many poses: a tenth of the photons per pose keeps the run short.
        let per_pose = (photons / 10).max(1000);
        let b = brilliance_mc(&cut.solid, &self.config, per_pose, seed.wrapping_add(1))?;
        rows.push(
            VerifyRow::new("brilliance_mc", b.brilliance.value, b.brilliance.stderr)
                .with_beam(beam.brilliance),
        );
        Ok(VerifyReport { photons, rows })
    }
}
