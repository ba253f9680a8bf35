//! [`ScoreSet`]: the scores of one cut, as the optimizer sees them.

use crate::metrics::ScoreName;
use serde::Serialize;

/// The scores of one cut, as the optimizer sees them.
///
/// `brilliance`, `fire` and `scintillation` are the objective's terms (each roughly in [0, 1],
/// higher is better). `extra` holds any further named scores the evaluator computes (ASET
/// shares, …); they are shown in the reports but not optimized.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ScoreSet {
    /// Light return under diffuse light.
    pub brilliance: f64,
    /// Colour seen under small light sources.
    pub fire: f64,
    /// How the face-up pattern changes as the stone tilts.
    pub scintillation: f64,
    /// Further named scores, shown in reports in this order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extra: Vec<(ScoreName, f64)>,
    /// The beam tracer's whole scores behind these, when the evaluator keeps them
    /// ([`BeamEvaluator`](super::BeamEvaluator)'s full evaluations do): a run's report draws its table and tilt chart
    /// from them instead of scoring the cut again. Not serialised.
    #[serde(skip)]
    pub detail: Option<std::sync::Arc<crate::metrics::Scores>>,
}

impl ScoreSet {
    /// The three objective scores, no extras.
    pub fn new(brilliance: f64, fire: f64, scintillation: f64) -> ScoreSet {
        ScoreSet {
            brilliance,
            fire,
            scintillation,
            extra: Vec::new(),
            detail: None,
        }
    }

    /// The score `name` (`brilliance`, `fire`, `scintillation` or an extra), if this set has it.
    pub fn get(&self, name: ScoreName) -> Option<f64> {
        match name {
            ScoreName::Brilliance => Some(self.brilliance),
            ScoreName::Fire => Some(self.fire),
            ScoreName::Scintillation => Some(self.scintillation),
            _ => self.extra.iter().find(|(k, _)| *k == name).map(|(_, v)| *v),
        }
    }

    /// Every score, name and value, the three objective scores first.
    pub fn all(&self) -> Vec<(ScoreName, f64)> {
        let mut out = vec![
            (ScoreName::Brilliance, self.brilliance),
            (ScoreName::Fire, self.fire),
            (ScoreName::Scintillation, self.scintillation),
        ];
        out.extend(self.extra.iter().cloned());
        out
    }
}
