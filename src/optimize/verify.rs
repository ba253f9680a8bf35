//! Verification of the winners by an independent Monte Carlo photon tracer.
//!
//! A [`Verifier`] re-scores a cut with photons and returns named rows: a Monte Carlo value with
//! its standard error and, where the same quantity is known from the beam tracer, the beam
//! value. The thesis's metrics (top-45° and top-90° face shares under overhead and off-centre
//! undirected light, and under the directed light rotated 0–180°) have no beam value; the
//! Monte Carlo brilliance under the beam tracer's lighting does, and any row whose Monte Carlo
//! value is more than `sigma` (default 4) standard errors from its beam value is flagged.

use crate::cut::Cut;
use crate::error::Result;
use serde::Serialize;

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

/// Re-scores a cut with photons. `seed` fixes every random number; the same seed gives the same
/// report.
pub trait Verifier: Sync {
    /// Trace `photons` photons per light through `cut`.
    fn verify(&self, cut: &Cut, photons: u64, seed: u64) -> Result<VerifyReport>;
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
        let t = std::time::Instant::now();
        let (report, error) = match verifier.verify(cut, photons, seed) {
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
