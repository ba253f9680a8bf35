//! [`photon_report`]: the optimizer's verification of a winner, a [`VerifyReport`] of
//! [`VerifyRow`]s: the thesis's top-face shares ([`thesis_rows`]) and the Monte Carlo overhead
//! light return and brilliance beside the beam tracer's values.

use super::estimate::{brilliance_mc, overhead_light_return_mc};
use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::{score, ScoreConfig};
use crate::photon::{self, Light, LightKind, Tally, TraceConfig, ROTATION_ANGLES};
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
