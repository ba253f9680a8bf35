//! [`Evaluator`]: the objective's scorer, a cut in, its [`ScoreSet`] out.

use super::score_set::ScoreSet;
use crate::cut::Cut;
use crate::error::Result;

/// The objective's scorer: a cut in, its scores out.
///
/// It must be deterministic (same cut, same scores) so that runs repeat, and `Sync`, because
/// particle swarms and multi-start searches evaluate cuts on several threads. An `Err` is not
/// fatal: the optimizer gives that cut a finite penalty cost and moves on.
pub trait Evaluator: Sync {
    /// Score one cut, every score.
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet>;

    /// Score one cut for the search: the scores the objective weighs must be right; the
    /// others may be left out as NaN (they weigh 0). The start and the winners are scored
    /// again with [`Evaluator::evaluate`] for the reports. By default the same as `evaluate`.
    fn evaluate_for_search(&self, cut: &Cut) -> Result<ScoreSet> {
        self.evaluate(cut)
    }
}

impl<F> Evaluator for F
where
    F: Fn(&Cut) -> Result<ScoreSet> + Sync,
{
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet> {
        self(cut)
    }
}
