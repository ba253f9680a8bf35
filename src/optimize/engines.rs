//! The real objective and verifier: the beam tracer's scores ([`BeamEvaluator`]) and the photon
//! tracer's thesis metrics plus Monte Carlo brilliance ([`PhotonVerifier`]).

use super::config::Config;
use super::evaluator::Evaluator;
use super::score_set::ScoreSet;
use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::{score, Parts, ScoreConfig, ScoreName, Scores};
use crate::verify::Verifier;
use crate::verify::VerifyReport;
use std::collections::BTreeMap;

/// Scores a cut with the beam tracer ([`crate::metrics::score`]). Brilliance, fire and
/// scintillation are the objective's terms; the other scores ride along as extras.
///
/// It is built from the optimization [`Config`] it serves (its `[score]` section), so the
/// scores an optimizer climbs are always those of the config's material and lighting.
#[derive(Clone, Debug)]
pub struct BeamEvaluator {
    config: ScoreConfig,
    /// The same, computing only what the objective weighs (fire and scintillation are left
    /// out while the search does not need them).
    search: ScoreConfig,
}

impl BeamEvaluator {
    /// The evaluator for a config: its `[score]` settings (material, head shadow, polarization).
    /// While searching it computes fire and scintillation only when the objective weighs them
    /// (or trades them off in `pareto`).
    pub fn new(config: &Config) -> Self {
        let full = config.score.score_config();
        let needs = |name: ScoreName, weight: f64| {
            weight != 0.0
                || config
                    .pareto
                    .as_ref()
                    .is_some_and(|p| p.scores.contains(&name))
        };
        let search = ScoreConfig {
            parts: Parts {
                fire: needs(ScoreName::Fire, config.weights.fire),
                scintillation: needs(ScoreName::Scintillation, config.weights.scintillation),
            },
            ..full.clone()
        };
        BeamEvaluator {
            config: full,
            search,
        }
    }

    /// The scoring settings in use (for the reported cuts: every score).
    pub fn score_config(&self) -> &ScoreConfig {
        &self.config
    }

    /// What the search computes of fire and scintillation.
    pub fn search_parts(&self) -> Parts {
        self.search.parts
    }

    /// The scores as the optimizer reports them.
    pub fn score_set(s: &Scores) -> ScoreSet {
        let mut set = ScoreSet::new(s.brilliance, s.fire, s.scintillation);
        // Every further score in the table's order; a colourless stone has no colour scores.
        set.extra = crate::metrics::SCORES
            .iter()
            .map(|i| i.name)
            .filter(|n| !ScoreName::OBJECTIVE.contains(n))
            .filter_map(|n| Some((n, n.of(s)?)))
            .collect();
        set
    }
}

/// `config` with the cut's own optic axis (a free `optic_axis` the optimizer set on the
/// cut, degrees from the table's normal toward the configured azimuth), when it has one.
pub(crate) fn with_cut_axis<'a>(
    config: &'a ScoreConfig,
    cut: &Cut,
) -> std::borrow::Cow<'a, ScoreConfig> {
    match (
        cut.params.get(super::config::OPTIC_AXIS),
        &config.material.uniaxial,
    ) {
        (Some(&tilt), Some(_)) => {
            let mut c = config.clone();
            if let Some(u) = c.material.uniaxial.as_mut() {
                u.axis.tilt_deg = tilt;
            }
            std::borrow::Cow::Owned(c)
        }
        _ => std::borrow::Cow::Borrowed(config),
    }
}

impl Evaluator for BeamEvaluator {
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet> {
        let scores = score(&cut.solid, &with_cut_axis(&self.config, cut));
        Ok(ScoreSet {
            detail: Some(std::sync::Arc::new(scores.clone())),
            ..Self::score_set(&scores)
        })
    }
    fn evaluate_for_search(&self, cut: &Cut) -> Result<ScoreSet> {
        Ok(Self::score_set(&score(
            &cut.solid,
            &with_cut_axis(&self.search, cut),
        )))
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

impl Verifier for PhotonVerifier {
    fn verify(&self, cut: &Cut, photons: u64, seed: u64) -> Result<VerifyReport> {
        crate::verify::photon_report(cut, &with_cut_axis(&self.config, cut), photons, seed)
    }

    /// Reuses the beam scores a [`BeamEvaluator`] of the same config computed (its full
    /// scores: `overhead_light_return` and `brilliance`), instead of tracing the cut again.
    fn verify_scored(
        &self,
        cut: &Cut,
        photons: u64,
        seed: u64,
        scores: Option<&BTreeMap<ScoreName, f64>>,
    ) -> Result<VerifyReport> {
        let beam = scores.and_then(|s| {
            Some((
                *s.get(&ScoreName::OverheadLightReturn)?,
                *s.get(&ScoreName::Brilliance)?,
            ))
        });
        crate::verify::photon_report_given(
            cut,
            &with_cut_axis(&self.config, cut),
            photons,
            seed,
            beam,
        )
    }
}

/// The objective's scorer and the winners' verifier for a loaded config.
pub type Scorers = (Box<dyn Evaluator>, Option<Box<dyn Verifier>>);

/// The real scorers: the beam tracer ([`BeamEvaluator`]) and the photon tracer
/// ([`PhotonVerifier`]), both with the config's `[score]` settings. They can only be made from
/// a loaded config, so no command scores with defaults.
pub fn real_scorers(config: &Config) -> Scorers {
    (
        Box::new(BeamEvaluator::new(config)),
        Some(Box::new(PhotonVerifier::new(config))),
    )
}
