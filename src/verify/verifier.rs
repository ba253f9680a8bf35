//! The interface of a check by an independent Monte Carlo photon tracer, as the optimizer
//! runs it on its winners.
//!
//! A [`Verifier`] re-scores a cut with photons and returns named rows ([`VerifyReport`], made
//! by [`photon_report`](super::photon_report) for the real verifier): a Monte Carlo value with
//! its standard error and, where the same quantity is known from the beam tracer, the beam
//! value. The thesis's metrics (top-45° and top-90° face shares under overhead and off-centre
//! undirected light, and under the directed light rotated 0–180°) have no beam value; the
//! Monte Carlo brilliance under the beam tracer's lighting does, and any row whose Monte Carlo
//! value is more than `sigma` (default 4) standard errors from its beam value is flagged.

use super::report::VerifyReport;
use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::ScoreName;
use serde::Serialize;
use std::collections::BTreeMap;

/// Re-scores a cut with photons. `seed` fixes every random number; the same seed gives the same
/// report.
pub trait Verifier: Sync {
    /// Trace `photons` photons per light through `cut`.
    fn verify(&self, cut: &Cut, photons: u64, seed: u64) -> Result<VerifyReport>;

    /// [`Verifier::verify`], given the beam scores the caller already has for `cut` (by name,
    /// computed under the verifier's own settings), so that a verifier needing them need not
    /// trace the cut again. The report must be the one `verify` gives; by default it is.
    fn verify_scored(
        &self,
        cut: &Cut,
        photons: u64,
        seed: u64,
        scores: Option<&BTreeMap<ScoreName, f64>>,
    ) -> Result<VerifyReport> {
        let _ = scores;
        self.verify(cut, photons, seed)
    }
}

impl<F> Verifier for F
where
    F: Fn(&Cut, u64, u64) -> Result<VerifyReport> + Sync,
{
    fn verify(&self, cut: &Cut, photons: u64, seed: u64) -> Result<VerifyReport> {
        self(cut, photons, seed)
    }
}

/// A verification as reported: the verifier's rows and the flagged names.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verification {
    /// The verifier's report.
    #[serde(flatten)]
    pub report: VerifyReport,
    /// Threshold used, in standard errors.
    pub sigma: f64,
    /// Rows that disagree beyond `sigma`.
    pub disagreements: Vec<String>,
    /// Seconds spent.
    pub seconds: f64,
    /// The verifier's error, when it failed on this cut.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl Verification {
    /// Verify `cut`, never failing: an error is kept in [`Verification::error`].
    pub fn run(verifier: &dyn Verifier, cut: &Cut, photons: u64, seed: u64, sigma: f64) -> Self {
        Verification::run_scored(verifier, cut, photons, seed, sigma, None)
    }

    /// [`Verification::run`] through [`Verifier::verify_scored`].
    pub fn run_scored(
        verifier: &dyn Verifier,
        cut: &Cut,
        photons: u64,
        seed: u64,
        sigma: f64,
        scores: Option<&BTreeMap<ScoreName, f64>>,
    ) -> Self {
        let t = std::time::Instant::now();
        let (report, error) = match verifier.verify_scored(cut, photons, seed, scores) {
            Ok(r) => (r, None),
            Err(e) => (
                VerifyReport {
                    photons,
                    rows: Vec::new(),
                },
                Some(e.to_string()),
            ),
        };
        Verification {
            disagreements: report.disagreements(sigma),
            report,
            sigma,
            seconds: t.elapsed().as_secs_f64(),
            error,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verification_keeps_errors() {
        let failing = |_: &Cut, _: u64, _: u64| -> Result<VerifyReport> {
            Err(crate::Error::Geometry("photons lost".into()))
        };
        let cut = Cut::from_family("r", "round-brilliant", &Default::default()).unwrap();
        let v = Verification::run(&failing, &cut, 100, 1, 4.0);
        assert!(v.error.as_deref().unwrap().contains("photons lost"));
        assert!(v.report.rows.is_empty() && v.disagreements.is_empty());
    }
}
