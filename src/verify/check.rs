//! [`verify_scores`]: a cut's beam scores re-measured by the photon tracer, as [`Check`] rows
//! flagged beyond [`SIGMA`] standard errors (`facetlab score --verify`).

use super::estimate::{brilliance_mc, overhead_light_return_mc, Estimate};
use crate::error::Result;
use crate::geometry::Polyhedron;
use crate::metrics::{ScoreConfig, ScoreName, Scores};
use serde::Serialize;

/// The threshold, in standard errors, beyond which `facetlab score --verify` flags a check
/// (the optimizer's is `[verify] sigma`, default 4 too).
pub const SIGMA: f64 = 4.0;

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
