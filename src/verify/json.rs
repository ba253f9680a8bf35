//! The JSON of `facetlab score --json` with `--verify`: each cut's object of
//! [`crate::metrics::json`] plus `verify.{figure}.{beam, photon, stderr, z, photons}`, the
//! photon tracer's [`Check`]s.

use super::Check;
use crate::metrics::json::scores_json;
use crate::metrics::{ScoreConfig, Scores};
use serde::Serialize;

/// One [`Check`] as written: the beam tracer's value, the photon tracer's estimate and its
/// standard error, (beam − photon)/stderr, and the photons per figure and pose.
#[derive(Serialize)]
struct CheckJson {
    beam: f64,
    photon: f64,
    stderr: f64,
    z: f64,
    photons: u64,
}

/// The scores document ([`scores_json`]) with, per cut, its checks (`checks[i]` for cut `i`;
/// none when `checks` is empty) made with `photons` photons per figure.
pub fn score_json(
    config: &ScoreConfig,
    results: &[(String, Scores)],
    checks: &[Vec<Check>],
    photons: u64,
) -> serde_json::Result<String> {
    scores_json(config, results, |i| {
        checks.get(i).map(|cs| {
            cs.iter()
                .map(|c| {
                    (
                        c.name.as_str(),
                        CheckJson {
                            beam: c.beam,
                            photon: c.photon,
                            stderr: c.stderr,
                            z: c.z,
                            photons,
                        },
                    )
                })
                .collect()
        })
    })
}
