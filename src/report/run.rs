//! An optimizer run's `report.html`: the start and the winners side by side, made from what
//! the run returned ([`Config`] and [`Outcome`]), not from inside the run: the binary hands
//! [`run_page`] to the run as its [`RunPage`](crate::optimize::RunPage).

use super::{html, measure, ReportOptions};
use crate::error::Result;
use crate::optimize::{Config, Outcome};
use crate::verify::Check;

/// `report.html` of a run: the start and the winners side by side, scored with the run's
/// score settings, with the photon tracer's checks when the run verified.
pub fn run_page(config: &Config, outcome: &Outcome) -> Result<String> {
    let o = ReportOptions {
        score: config.score.score_config(),
        size: 240,
        title: format!("facetlab optimize: {}", config.name),
        ..Default::default()
    };
    let mut cuts = Vec::new();
    for c in std::iter::once(&outcome.start).chain(&outcome.winners) {
        let cut = config.space.build(&c.label, &c.params)?;
        let mut r = measure(&c.label, &cut, &o)?;
        r.checks.clear();
        if let Some(v) = &c.verification {
            r.checks = v
                .report
                .rows
                .iter()
                .filter_map(|row| {
                    let beam = row.beam?;
                    Some(Check {
                        name: row.name.clone(),
                        beam,
                        photon: row.value,
                        stderr: row.stderr,
                        z: if row.stderr > 0.0 {
                            (beam - row.value) / row.stderr
                        } else {
                            0.0
                        },
                    })
                })
                .collect();
        }
        cuts.push(r);
    }
    html(&cuts, &o)
}
