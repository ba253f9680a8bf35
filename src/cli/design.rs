//! `facetlab design`: build a recipe (a design written tier by tier) into a design file, or
//! write the recipe of an existing design (`--from`).

use clap::Args;
use facetlab::design::recipe::{infer, Built, Recipe};
use facetlab::error::{Error, Result};
use facetlab::io;
use facetlab::io::guard::{check_new_file, cut_files, refuse_overwrite, setting};
use std::path::PathBuf;

/// Flags of `facetlab design`.
#[derive(Debug, Args)]
pub struct DesignArgs {
    /// The recipe to build (a .toml with [design] and [[tier]] tables; see docs/design.md).
    // A String on purpose: the same spelling as every CUT argument.
    pub recipe: Option<String>,
    /// Write the recipe of an existing design instead (a preset, .asc, .gem, .toml, .obj or
    /// .stl): each tier placed by the vertex it meets where that gives back its depth.
    #[arg(long = "from", value_name = "DESIGN", conflicts_with = "recipe")]
    pub from: Option<String>,
    /// Output file: with a recipe, the design (.asc .gem .obj .stl .svg, or .toml for the cut
    /// spec); with --from, the recipe (.toml).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    /// Write the design even when a facet is under 1 % of the width or a pavilion tier is
    /// below the critical angle (printed as warnings).
    #[arg(long)]
    pub lenient: bool,
    /// Also print, for each tier whose angle is a number, how brilliance, its COS half and
    /// fire change per degree (central differences of the exact scores, the recipe cut again
    /// at ±0.5°), in the material of the recipe's index.
    #[arg(long)]
    pub slopes: bool,
    /// Replace an existing output file (an input is never replaced, even with --force).
    #[arg(long)]
    pub force: bool,
}

/// `facetlab design`.
pub fn run(a: &DesignArgs) -> Result<()> {
    let input = match (&a.recipe, &a.from) {
        (Some(r), None) => r.clone(),
        (None, Some(f)) => f.clone(),
        _ => {
            return Err(Error::invalid(
                "RECIPE",
                "give a recipe to build (facetlab design RECIPE.toml -o OUT.asc) or --from DESIGN -o RECIPE.toml",
            ))
        }
    };
    refuse_overwrite(
        &[(setting::OUTPUT, a.output.clone())],
        &cut_files(std::slice::from_ref(&input)),
    )?;
    check_new_file(setting::OUTPUT, &a.output, a.force)?;
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if a.from.is_some() {
        if ext != "toml" {
            return Err(Error::invalid(
                "-o",
                format!("--from writes a recipe: give a .toml file, not `.{ext}`"),
            ));
        }
        let cut = io::load_cut(&input)?;
        let inferred = infer(&cut).map_err(|e| e.context(&input))?;
        for n in &inferred.notes {
            eprintln!("note: {n}");
        }
        let mut text = format!(
            "# Inferred by `facetlab design --from {input}`; building it gives the same solid.\n"
        );
        for n in &inferred.notes {
            text.push_str(&format!("# Note: {n}.\n"));
        }
        text.push_str(&io::recipe::write(&inferred.recipe));
        io::write_atomic(&a.output, text.as_bytes())?;
        eprintln!(
            "wrote {} ({} tiers; `facetlab design {}` builds it back)",
            a.output.display(),
            inferred.recipe.tiers.len(),
            a.output.display()
        );
        return Ok(());
    }
    let (recipe, built) = build(&input)?;
    for f in &built.findings {
        if a.lenient {
            eprintln!("warning: {}", f.message);
        }
    }
    if let (false, Some(f)) = (a.lenient, built.findings.first()) {
        let more = built.findings.len() - 1;
        return Err(Error::invalid(
            input.clone(),
            format!(
                "{}{} (--lenient writes the design anyway)",
                f.message,
                if more > 0 {
                    format!("; {more} more")
                } else {
                    String::new()
                }
            ),
        ));
    }
    let cut = &built.cut;
    let bytes: Vec<u8> = match ext.as_str() {
        "svg" => facetlab::plot::diagram::diagram(cut).into_bytes(),
        e if io::CUT_FORMATS.contains(&e) => io::write_cut(cut, e)?,
        _ => {
            return Err(Error::invalid(
                "-o",
                format!(
                "cannot write `.{ext}`; allowed extensions: .asc, .gem, .obj, .stl, .svg, .toml"
            ),
            ))
        }
    };
    for s in &built.steps {
        let ix: Vec<String> = s.indices.iter().map(|x| format!("{x:02}")).collect();
        let ix = if s.angle == 0.0 {
            String::new()
        } else {
            ix.join("-")
        };
        eprintln!(
            "  {:<4} {:>8.2}°  {:<40} {}",
            s.tier, s.angle, ix, s.instruction
        );
    }
    io::write_atomic(&a.output, &bytes)?;
    if a.slopes {
        print_slopes(recipe)?;
    }
    eprintln!(
        "wrote {} ({} facets in {} tiers)",
        a.output.display(),
        cut.solid.facets().len(),
        built.steps.len()
    );
    Ok(())
}

/// The recipe file `path` read and built, errors naming it.
fn build(path: &str) -> Result<(Recipe, Built)> {
    let Some(recipe) = io::recipe::read(std::path::Path::new(path))? else {
        return Err(Error::invalid(
            path,
            "not a recipe: a recipe is a .toml file with [design] and [[tier]] tables (--from DESIGN writes one)",
        ));
    };
    let built = recipe.build().map_err(|e| e.context(path))?;
    Ok((recipe, built))
}

/// The table of `--slopes`: each free tier's change of the scores per degree.
fn print_slopes(recipe: Recipe) -> Result<()> {
    let index = recipe.index;
    let space = facetlab::design::recipe::RecipeSpace::new(recipe)?;
    let mut config = facetlab::metrics::ScoreConfig::default();
    if let Some(m) = facetlab::optics::Material::for_index(index) {
        config.material = m;
    }
    let slopes = facetlab::optimize::tier_slopes(&space, &config, 0.5)?;
    println!("per degree steeper (in {}):", config.material.name);
    println!(
        "{:<6} {:>8} {:>11} {:>11} {:>9}",
        "tier", "angle", "brilliance", "COS look", "fire"
    );
    for s in &slopes {
        println!(
            "{:<6} {:>8.2} {:>+11.4} {:>+11.4} {:>+9.4}{}",
            s.tier,
            s.angle,
            s.brilliance,
            s.brilliance_cos,
            s.fire,
            if s.one_sided { "  (one side)" } else { "" }
        );
    }
    Ok(())
}
