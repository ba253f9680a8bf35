//! `facetlab score` as one call ([`score_cuts`]): the stones chosen for the cuts, each cut
//! scored by the beam tracer in its own material, optionally checked by the photon tracer
//! ([`verify_scores`], seed [`VERIFY_SEED`]), and the score document ([`score_json`]) written
//! when asked. The caller sees the notes, the scores and each check as they come through
//! [`ScoreSink`], so what it prints keeps its order whatever stops the run.

use super::score::score_json;
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::metrics::{score, ColourNotes, NoteKind, ScoreConfig, Scores, StoneChoice, StoneFields};
use crate::verify::{verify_scores, Check};
use std::path::Path;

/// Seed of the photon tracer's checks.
pub const VERIFY_SEED: u64 = 1;

/// What hears of a scoring as it goes (the command line prints it).
pub trait ScoreSink {
    /// A stone's note ([`StoneChoice::stones`]), before any cut is scored.
    fn note(&mut self, _kind: NoteKind, _line: String) {}
    /// Every cut scored (`config` names the first cut's material).
    fn scored(&mut self, _config: &ScoreConfig, _results: &[(String, Scores)]) {}
    /// The photon tracer's checks start, with `photons` photons per figure and pose.
    fn checking(&mut self, _photons: u64) {}
    /// One cut checked.
    fn checked(&mut self, _name: &str, _checks: &[Check]) {}
}

/// What `score` scores and where it writes the document.
pub struct ScoreJob<'a> {
    /// The cuts, in this order.
    pub cuts: &'a [Cut],
    /// The stones' material, colour, size and crystal settings.
    pub stone: &'a StoneChoice,
    /// Where the stone's settings were given (named in errors and notes).
    pub fields: &'a StoneFields<'a>,
    /// The scores' settings (its material is each cut's stone's).
    pub config: &'a ScoreConfig,
    /// Photons per figure and pose of the photon tracer's checks, if asked.
    pub verify: Option<u64>,
    /// The score document's file. A failure to shape it names the setting `score document`.
    pub json: Option<&'a Path>,
}

/// What `score` found.
#[derive(Clone, Debug)]
pub struct Scored {
    /// The settings as the document names them: the first cut's material.
    pub config: ScoreConfig,
    /// Each cut's name and scores.
    pub results: Vec<(String, Scores)>,
    /// Each cut's checks (empty without `verify`).
    pub checks: Vec<Vec<Check>>,
}

/// Score the job's cuts ([`ScoreJob`]), check them and write the document.
pub fn score_cuts(job: &ScoreJob<'_>, sink: &mut dyn ScoreSink) -> Result<Scored> {
    // A design is traced in its own material unless the caller chose one; the table's header
    // and the document's settings name the first cut's.
    let stones = job
        .stone
        .stones(job.cuts, job.fields, ColourNotes::Traced, &mut |k, l| {
            sink.note(k, l)
        })?;
    let (config, configs) = stones.configs(job.config, |c, material| ScoreConfig {
        material,
        ..c.clone()
    });
    let results: Vec<(String, Scores)> = job
        .cuts
        .iter()
        .zip(&configs)
        .map(|(c, cfg)| (c.name.clone(), score(&c.solid, cfg)))
        .collect();
    sink.scored(&config, &results);
    let mut checks: Vec<Vec<Check>> = Vec::new();
    if let Some(photons) = job.verify {
        sink.checking(photons);
        for ((cut, (name, sc)), cfg) in job.cuts.iter().zip(&results).zip(&configs) {
            let cs = verify_scores(&cut.solid, cfg, sc, photons, VERIFY_SEED)?;
            sink.checked(name, &cs);
            checks.push(cs);
        }
    }
    if let Some(path) = job.json {
        let text = score_json(&config, &results, &checks, job.verify.unwrap_or(0))
            .map_err(|e| Error::invalid("score document", e.to_string()))?;
        crate::io::write_atomic(path, text.as_bytes())?;
    }
    Ok(Scored {
        config,
        results,
        checks,
    })
}
