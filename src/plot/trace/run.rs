//! `facetlab trace` as one call ([`trace`]): the stones chosen for the cuts (a coloured
//! stone's note said only when its colour is not traced, after the crystal's), each cut traced
//! by the photon tracer under the light or the rotation sweep, the document
//! ([`trace_json`]) written when asked, and the charts ([`trace_plots`]) drawn into a folder
//! when asked. The caller sees the notes, progress, the tallies and the files as they come
//! through [`TraceSink`].

use super::trace_plots;
use crate::cut::Cut;
use crate::document::trace::trace_json;
use crate::error::{Error, Result};
use crate::metrics::{ColourNotes, NoteKind, StoneChoice, StoneFields};
use crate::photon::{self, Absorption, LightChoice, Tally, TraceConfig};
use crate::plot::Camera;
use std::path::{Path, PathBuf};

/// What hears of a trace as it goes (the command line's bar and lines). Called from worker
/// threads.
pub trait TraceSink: Sync {
    /// A stone's note, before any photon is traced.
    fn note(&self, _kind: NoteKind, _line: String) {}
    /// The work ahead: `total` photons (`unit` "photons") or hits of a sweep (`unit` "hits").
    fn start(&self, _total: u64, _unit: &str) {}
    /// `n` more photons or hits traced.
    fn traced(&self, _n: u64) {}
    /// Every cut traced: `config` names the first cut's material; `results[cut]` holds one
    /// tally, or one per angle of the sweep.
    fn done(&self, _light: &LightChoice, _config: &TraceConfig, _results: &[Vec<Tally>]) {}
    /// The document was written to `path`.
    fn wrote_json(&self, _path: &Path) {}
}

/// What `trace` traces and where it writes.
pub struct TraceJob<'a> {
    /// The cuts, in this order.
    pub cuts: &'a [Cut],
    /// Each cut as the user gave it (the document's `cuts`).
    pub inputs: &'a [String],
    /// The stones' material (the tracer's settings' own, unless a design has its own) and
    /// crystal settings; a trace takes no colour or size of its own.
    pub stone: &'a StoneChoice,
    /// Where the stone's settings were given (named in errors and notes).
    pub fields: &'a StoneFields<'a>,
    /// The light or the rotation sweep.
    pub light: &'a LightChoice,
    /// The tracer's settings (its material is each cut's stone's).
    pub config: &'a TraceConfig,
    /// The camera of the charts.
    pub camera: Camera,
    /// The document's file.
    pub json: Option<&'a Path>,
    /// The charts' folder.
    pub plots: Option<&'a Path>,
}

/// Trace the job's cuts ([`TraceJob`]), write the document and draw the charts; returns the
/// charts' stems (each written as STEM.png and STEM.svg).
pub fn trace(job: &TraceJob<'_>, sink: &dyn TraceSink) -> Result<Vec<PathBuf>> {
    let mut colour_notes = Vec::new();
    let stones = job.stone.stones(
        job.cuts,
        job.fields,
        ColourNotes::NotTraced,
        &mut |kind, line| match kind {
            NoteKind::Colour => colour_notes.push(line),
            _ => sink.note(kind, line),
        },
    )?;
    // A coloured stone is traced in colour only with a body-colour absorption; otherwise say
    // that it is not, with the default width.
    if !matches!(job.config.absorption, Absorption::Body { .. }) {
        for line in colour_notes {
            sink.note(NoteKind::Colour, line);
        }
    }
    let (config, configs) = stones.configs(job.config, |c, material| TraceConfig {
        material,
        ..c.clone()
    });
    if let Some(dir) = job.plots {
        if dir.exists() && !dir.is_dir() {
            return Err(Error::io(
                dir.display().to_string(),
                "exists and is not a folder",
            ));
        }
        crate::io::check_writable(dir)?;
    }
    if let Some(j) = job.json {
        crate::io::guard::check_folder_of(j)?;
    }
    let (per_cut, unit) = match job.light {
        LightChoice::Single(_) => (config.photons, "photons"),
        LightChoice::Rotate(_) => (
            config.photons * photon::ROTATION_ANGLES.len() as u64,
            "hits",
        ),
    };
    sink.start(per_cut.saturating_mul(job.cuts.len() as u64), unit);
    let tick = |n: u64| sink.traced(n);
    let progress: Option<&(dyn Fn(u64) + Sync)> = Some(&tick);
    let mut results: Vec<Vec<Tally>> = Vec::with_capacity(job.cuts.len());
    for (cut, cfg) in job.cuts.iter().zip(&configs) {
        results.push(photon::trace_choice(
            &cut.solid, &cut.name, job.light, cfg, progress,
        )?);
    }
    sink.done(job.light, &config, &results);
    if let Some(j) = job.json {
        let text = trace_json(job.light, &config, job.inputs, &results)
            .and_then(|doc| serde_json::to_string_pretty(&doc))
            .map_err(|e| Error::io(j.display().to_string(), e))?;
        crate::io::write_atomic(j, text.as_bytes())?;
        sink.wrote_json(j);
    }
    match job.plots {
        Some(dir) => trace_plots(dir, job.light, job.camera, job.cuts, &results),
        None => Ok(Vec::new()),
    }
}
