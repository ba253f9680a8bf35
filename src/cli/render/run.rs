//! `facetlab render`: its outputs checked, its progress bar and the stones' notes, and the one
//! library call that draws.

use super::{photo, settings, RenderArgs};
use crate::cli::flags;
use crate::cli::outputs::{cut_files, refuse_overwrite};
use facetlab::error::{Error, Result};
use facetlab::metrics::NoteKind;
use facetlab::plot::render::{draw, printed_line, Pictures, Progress, RenderJob};

/// Check the outputs before any work: not an input, -o a .png, not a folder, existing files
/// only with --force, folders present and writable.
fn check_outputs(a: &RenderArgs) -> Result<()> {
    let mut outs = vec![("-o", a.output.clone())];
    if let Some(j) = &a.json {
        outs.push(("--json", j.clone()));
    }
    refuse_overwrite(&outs, &cut_files(&a.cuts))?;
    let is_png = a
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !is_png {
        return Err(Error::invalid(
            "-o",
            format!(
                "{} does not end in .png; the picture is a PNG (an animated PNG with --rock)",
                a.output.display()
            ),
        ));
    }
    if let Some(j) = &a.json {
        if crate::cli::outputs::resolved(j) == crate::cli::outputs::resolved(&a.output) {
            return Err(Error::invalid(
                "--json",
                format!("{} is also the -o picture; give another file", j.display()),
            ));
        }
    }
    for (flag, p) in &outs {
        crate::cli::outputs::check_new_file(flag, p, a.force)?;
    }
    Ok(())
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
    let (pictures, stone) = match facetlab::render::photo::PhotoLight::parse(&a.light)? {
        Some(light) => {
            let (p, stone) = photo::settings(a, light)?;
            photo::check_outputs(a)?;
            if p.frames() > 1 && a.photo.hdr_out.is_some() && a.cuts.len() > 1 {
                eprintln!("note: --hdr-out writes frame 0 of the first cut");
            }
            (Pictures::Photo(p), stone)
        }
        None => {
            if let Some(flag) = a.photo.first_given() {
                return Err(Error::invalid(
                    flag,
                    format!(
                        "is for photographs; give a photographic --light ({} or env:FILE)",
                        facetlab::render::photo::PhotoLight::names().join(", ")
                    ),
                ));
            }
            let (p, stone) = settings(a)?;
            check_outputs(a)?;
            (Pictures::Lab(p), stone)
        }
    };
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
    let drawn = draw(&job, &bar).map_err(|e| match e {
        Error::Invalid { field, message } if field == "output" => Error::invalid("-o", message),
        other => other,
    })?;
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
