//! `facetlab sheet`: the cutting sheet (one A4 page as .html, .svg or .pdf) and, with
//! `--mode`, the cutting mode (one step per screen, .html).

use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::io;
use facetlab::io::guard::{check_new_file, cut_files, refuse_overwrite, setting};
use facetlab::optics::Material;
use facetlab::report::sheet::{cutting_mode_html, sheet_html, sheet_pdf, sheet_svg, SheetOptions};
use std::path::PathBuf;

/// Flags of `facetlab sheet`.
#[derive(Debug, Args)]
pub struct SheetArgs {
    /// The cut and its changes.
    #[command(flatten)]
    pub one: super::cuts::OneCut,
    /// Output file: .html, .svg or .pdf (one A4 page); with --mode, .html.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    /// The cutting mode instead: one step per screen with the stone as cut so far (.html).
    #[arg(long)]
    pub mode: bool,
    /// The stone's width W in mm: depths in mm, the weight at that size (default: depths in
    /// W, the weight at 6.5 mm).
    #[arg(long, value_name = "MM")]
    pub diameter_mm: Option<f64>,
    /// The stone's size instead: its length L (the width follows from the design's L/W), or
    /// LxW (which must match the design's L/W within 1 %).
    #[arg(long, value_name = "L[xW]", conflicts_with = "diameter_mm", value_parser = super::flags::parsed("--size-mm", super::flags::size_mm))]
    pub size_mm: Option<facetlab::optics::StoneSize>,
    /// Material of the weight: a name from `facetlab materials` or ri:N[:BG]; default the
    /// design's own (a GemCad file's `I` index), else diamond.
    #[arg(long, value_parser = super::flags::parsed("--material", super::flags::material_name))]
    pub material: Option<Material>,
    /// Replace an existing output file (an input is never replaced, even with --force).
    #[arg(long)]
    pub force: bool,
}

/// `facetlab sheet`.
pub fn run(a: &SheetArgs) -> Result<()> {
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let allowed: &[&str] = if a.mode {
        &["html"]
    } else {
        &["html", "svg", "pdf"]
    };
    if !allowed.contains(&ext.as_str()) {
        let list = allowed
            .iter()
            .map(|e| format!(".{e}"))
            .collect::<Vec<_>>()
            .join(", ");
        let what = if a.mode {
            "the cutting mode (--mode)"
        } else {
            "a sheet"
        };
        return Err(Error::invalid(
            "-o",
            format!(
                "cannot write {what} as `{}`; allowed extensions: {list}",
                a.output.display()
            ),
        ));
    }
    if let Some(d) = a.diameter_mm {
        facetlab::optics::StoneSize::check_mm(d, "--diameter-mm")?;
    }
    refuse_overwrite(
        &[(setting::OUTPUT, a.output.clone())],
        &cut_files(std::slice::from_ref(&a.one.cut)),
    )?;
    check_new_file(setting::OUTPUT, &a.output, a.force)?;
    let cut = super::cuts::load_with_sets(&a.one.cut, &a.one.set)?;
    let material = super::cuts::weight_material(a.material.clone(), &cut)?;
    let size_mm = match (&a.size_mm, a.diameter_mm) {
        (Some(size), _) => Some(size.width_mm(cut.ratios().l_w, "--size-mm")?),
        (None, d) => d,
    };
    let o = SheetOptions { size_mm, material };
    // A recipe's sheet: its own cutting order and instructions.
    let recipe = io::recipe::read(std::path::Path::new(&a.one.cut))?;
    let steps = match recipe {
        Some(r) => {
            let space = facetlab::design::recipe::RecipeSpace::new(r)?;
            let values = super::cuts::parse_sets(&a.one.set)?;
            let built = space.recipe_at(&values)?.build()?;
            built.sheet_steps(size_mm)
        }
        None => facetlab::design::sheet_steps(&cut, size_mm),
    };
    let bytes = if a.mode {
        cutting_mode_html(&cut, &steps, &o)?.into_bytes()
    } else {
        match ext.as_str() {
            "svg" => sheet_svg(&cut, &steps, &o).into_bytes(),
            "pdf" => sheet_pdf(&cut, &steps, &o)?,
            _ => sheet_html(&cut, &steps, &o).into_bytes(),
        }
    };
    io::write_atomic(&a.output, &bytes)?;
    eprintln!(
        "wrote {} ({} {}, {} facets)",
        a.output.display(),
        steps.len(),
        if a.mode { "screens" } else { "tiers" },
        cut.solid.facets().len()
    );
    Ok(())
}
