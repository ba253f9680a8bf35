//! `facetlab render`: its outputs checked, its progress bar and the stones' notes, and the one
//! library call that draws.

use super::{photo, settings, RenderArgs};
use crate::cli::flags;
use facetlab::error::{Error, Result};
use facetlab::io::guard::{cut_files, PictureFiles};
use facetlab::metrics::NoteKind;
use facetlab::plot::render::{draw, printed_line, Progress, RenderJob};
use facetlab::render::Pictures;

/// Check a laboratory picture's outputs before any work ([`PictureFiles::check_laboratory`]).
fn check_outputs(a: &RenderArgs) -> Result<()> {
    PictureFiles {
        picture: &a.output,
        json: a.json.as_deref(),
        hdr: None,
    }
    .check_laboratory(&cut_files(&a.cuts), a.force)
}

/// The progress bar of `render` (drawn once the stones' notes are said) and those notes.
struct Bar {
    quiet: bool,
    template: &'static str,
    bar: std::sync::OnceLock<indicatif::ProgressBar>,
}

impl Progress for Bar {
    fn note(&self, kind: NoteKind, line: String) {
        flags::say(kind, line)
    }
    fn start(&self, pictures: u64) {
        let _ = self.bar.set(crate::cli::progress::bar(
            pictures,
            self.quiet,
            self.template,
        ));
    }
    fn picture(&self) {
        if let Some(b) = self.bar.get() {
            b.inc(1)
        }
    }
    fn finish(&self) {
        if let Some(b) = self.bar.get() {
            b.finish_and_clear()
        }
    }
}

/// Run `facetlab render`.
pub fn run(a: &RenderArgs) -> Result<()> {
    if !a.light.is_photo() {
        if let Some(flag) = a.photo.first_given() {
            return Err(Error::invalid(
                flag,
                format!(
                    "is for photographs; give a photographic --light ({} or env:FILE)",
                    facetlab::render::photo::PhotoLight::names().join(", ")
                ),
            ));
        }
    }
    let (pictures, stone) = settings(a)?;
    match &pictures {
        Pictures::Photo(p) => {
            photo::check_outputs(a)?;
            if p.frames() > 1 && a.photo.hdr_out.is_some() && a.cuts.len() > 1 {
                eprintln!("note: --hdr-out writes frame 0 of the first cut");
            }
        }
        Pictures::Lab(_) => check_outputs(a)?,
    }
    let cuts = a
        .cuts
        .iter()
        .map(|c| crate::cli::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    let bar = Bar {
        quiet: a.quiet,
        template: match pictures {
            Pictures::Lab(_) => "{spinner} rendering [{bar:30}] {pos}/{len} pictures, eta {eta}",
            Pictures::Photo(_) => {
                "{spinner} photographing [{bar:30}] {pos}/{len} pictures, eta {eta}"
            }
        },
        bar: std::sync::OnceLock::new(),
    };
    let job = RenderJob {
        cuts: &cuts,
        inputs: &a.cuts,
        stone: &stone,
        fields: &flags::STONE_FIELDS,
        pictures: &pictures,
        bare: a.bare,
        output: &a.output,
        json: a.json.as_deref(),
        hdr_out: a.photo.hdr_out.as_deref(),
    };
    let drawn = draw(&job, &bar)?;
    for c in 0..drawn.len() {
        println!("{}", printed_line(&pictures, &drawn, c));
    }
    if let Some(h) = &a.photo.hdr_out {
        if matches!(pictures, Pictures::Photo(_)) {
            println!("linear picture → {}", h.display());
        }
    }
    if let Some(j) = &a.json {
        println!("statistics → {}", j.display());
    }
    Ok(())
}
