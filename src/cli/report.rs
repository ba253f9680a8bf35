//! `facetlab report CUT... -o FILE.html`: a one-page report per cut, or comparing cuts side by
//! side, as one self-contained HTML file (pictures embedded, no network): COS with a 15° head
//! shadow, ASET and fire pictures, the facet diagram, proportions with the grade estimate (round
//! brilliants), every score with one line on what it means, and with `--verify N` the photon
//! tracer's check.

use super::flags;
use facetlab::error::{Error, Result};
use facetlab::io::guard::{check_new_file, cut_files, refuse_overwrite, setting};
use facetlab::metrics::{ColourNotes, ScoreConfig, StoneChoice};
use facetlab::report::{html, measure, ReportOptions};
use std::path::PathBuf;

/// Flags of `facetlab report`.
#[derive(clap::Args, Debug, Clone)]
pub struct ReportArgs {
    /// Cuts to report, side by side: preset names or .toml/.asc/.gem/.obj/.stl files.
    #[arg(required = true, value_name = "CUT")]
    pub cuts: Vec<String>,
    /// Change a parameter: a family's (`--set crown_angle=34.5`) or a design's tier angle
    /// (`--set P1=41.2`). Repeatable; applied to every CUT.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    #[command(flatten)]
    pub material: super::flags::MaterialArgs,
    #[command(flatten)]
    pub head: super::flags::HeadShadowArgs,
    /// Re-measure light return and brilliance with the photon tracer using this many photons
    /// (e.g. 200000); 0 = no check.
    #[arg(
        long,
        default_value = "0",
        value_name = "PHOTONS",
        allow_hyphen_values = true,
        value_parser = flags::whole("--verify", 0, 1_000_000_000)
    )]
    pub verify: u64,
    /// Pixels per side of each picture (64–1024).
    #[arg(
        long,
        default_value = "320",
        value_name = "PX",
        allow_hyphen_values = true,
        value_parser = super::flags::whole("--size", 64, 1024)
    )]
    pub size: u64,
    /// Title of the page.
    #[arg(long, value_name = "TEXT")]
    // A String on purpose: a free title.
    pub title: Option<String>,
    /// Replace -o if it exists (an input is never replaced).
    #[arg(long)]
    pub force: bool,
    /// The page to write (.html).
    #[arg(short = 'o', long = "output", value_name = "FILE.html")]
    pub output: PathBuf,
}

/// Run `facetlab report`.
pub fn run(a: &ReportArgs) -> Result<()> {
    let size = a.size as usize;
    let photons = a.verify;
    let material = a.material.material()?;
    refuse_overwrite(&[(setting::OUTPUT, a.output.clone())], &cut_files(&a.cuts))?;
    let is_html = a
        .output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"));
    if !is_html {
        return Err(Error::invalid(
            "-o",
            format!("{} does not end in .html", a.output.display()),
        ));
    }
    check_new_file(setting::OUTPUT, &a.output, a.force)?;
    let cuts = a
        .cuts
        .iter()
        .map(|c| super::cuts::load_with_sets(c, &a.set))
        .collect::<Result<Vec<_>>>()?;
    let chosen = a.material.chosen();
    // A design is traced in its own material (GemCad's `I` index) unless one was chosen; the
    // page names the first cut's.
    // A coloured material (`--material ruby`, a design's note) is named with the default
    // width (this command has no size flags); its scores carry the face-up colour.
    let mut stone = StoneChoice::new(
        material.clone(),
        chosen,
        None,
        None,
        flags::STONE_FIELDS.colour,
    )?;
    stone.crystal = Some(flags::CrystalArgs::default().choice(589.3));
    let materials = stone
        .stones(
            &cuts,
            &flags::STONE_FIELDS,
            ColourNotes::Traced,
            &mut flags::say,
        )?
        .materials;
    let material = materials.first().cloned().unwrap_or(material);
    let score = ScoreConfig {
        material,
        head_shadow_deg: a.head.head_shadow,
        ..ScoreConfig::default()
    };
    // With the default settings only the material can be at fault: the error names it, and
    // flags::flag names its flag as the error leaves the command.
    score.validate().map_err(|e| match e {
        Error::Invalid { message, .. } => Error::invalid("material", message),
        other => other,
    })?;
    let o = ReportOptions {
        score,
        size,
        verify_photons: photons,
        title: a.title.clone().unwrap_or_else(|| {
            format!(
                "facetlab report: {}",
                cuts.iter()
                    .map(|c| c.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }),
        ..ReportOptions::default()
    };
    let reports = cuts
        .iter()
        .zip(&materials)
        .map(|(c, m)| {
            let mut oc = o.clone();
            oc.score.material = m.clone();
            measure(&c.name, c, &oc)
        })
        .collect::<Result<Vec<_>>>()?;
    for r in &reports {
        println!(
            "{}: brilliance {:.4}, fire {:.4}, scintillation {:.4}{}",
            r.label,
            r.scores.brilliance,
            r.scores.fire,
            r.scores.scintillation,
            facetlab::cut::grade::estimate(&r.cut)
                .map(|g| format!(", grade estimate {}", g.estimate.name()))
                .unwrap_or_default()
        );
    }
    let page = html(&reports, &o)?;
    facetlab::io::write_atomic(&a.output, page.as_bytes())?;
    println!("wrote {}", a.output.display());
    Ok(())
}
