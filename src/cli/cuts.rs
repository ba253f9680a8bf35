//! `generate` and `info`.

use clap::Args;
use facetlab::cut::Cut;
use facetlab::document::info::{info_json, info_text, meets_json, meets_text};
use facetlab::error::{Error, Result};
use facetlab::io;
use facetlab::io::guard::{check_new_file, cut_files, refuse_overwrite, setting};
use facetlab::metrics::{ColourNotes, NoteKind, StoneChoice};
use facetlab::optics::Material;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The one cut of `generate`, `info` and `sheet`: a preset or a file, and its changes.
#[derive(Debug, Args)]
pub struct OneCut {
    /// Preset name or path (.toml, .asc, .gem, .obj, .stl).
    // A String on purpose: a preset's name or a file's path.
    pub cut: String,
    /// Change a parameter: a family's (`--set crown_angle=34.5`) or a design's tier angle
    /// (`--set P1=41.2`, depths solved so its meets are kept). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

/// Flags of `facetlab generate`.
#[derive(Debug, Args)]
pub struct GenerateArgs {
    /// The cut and its changes.
    #[command(flatten)]
    pub one: OneCut,
    /// Output file; the format follows the extension: .toml .asc .gem .obj .stl .svg.
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    /// Replace an existing output file (an input is never replaced, even with --force).
    #[arg(long)]
    pub force: bool,
}

/// Flags of `facetlab info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The cut and its changes.
    #[command(flatten)]
    pub one: OneCut,
    /// Print JSON instead of a table (keys documented in docs/commands.md).
    #[arg(long)]
    pub json: bool,
    /// Girdle width W (a round's diameter) in millimetres, for the carat weight.
    #[arg(long, value_name = "MM", default_value_t = 6.5)]
    pub diameter_mm: f64,
    /// The stone's size in millimetres instead: its length L (the width follows from the
    /// design's L/W), or LxW (which must match the design's L/W within 1 %).
    #[arg(long, value_name = "L[xW]", conflicts_with = "diameter_mm", value_parser = super::flags::parsed("--size-mm", super::flags::size_mm))]
    pub size_mm: Option<facetlab::optics::StoneSize>,
    /// Also list the cutting instructions: each tier with its angle (0.01°), its indices on the
    /// design's gear (96 for generated cuts) and its note, pavilion first, then crown.
    #[arg(long)]
    pub instructions: bool,
    /// Also list the design's meets: points where four or more facets meet within
    /// `--meet-tol` of W, with the tiers they join and how far the file's planes miss the point.
    #[arg(long)]
    pub meets: bool,
    /// Tolerance of `--meets`, in widths W.
    #[arg(long, value_name = "W", default_value_t = facetlab::design::MEET_TOL)]
    pub meet_tol: f64,
    /// Material, for the carat weight: a name from `facetlab materials` or ri:N[:BG]; default
    /// the design's own (a GemCad file's `I` index), else diamond.
    #[arg(long, value_parser = super::flags::parsed("--material", super::flags::material_name))]
    pub material: Option<Material>,
}

/// Parse `--set key=value` flags.
pub fn parse_sets(sets: &[String]) -> Result<BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    for s in sets {
        // The value follows the last `=`: a tie `C1=C2=35` sets both tiers to 35.
        let Some((k, v)) = s.rsplit_once('=') else {
            return Err(Error::invalid(
                "--set",
                format!("expected KEY=VALUE, got `{s}`"),
            ));
        };
        let (k, v) = (k.trim(), v.trim());
        let value: f64 = v
            .parse()
            .map_err(|_| Error::invalid(format!("--set {k}"), format!("`{v}` is not a number")))?;
        out.insert(k.to_string(), value);
    }
    Ok(out)
}

/// Load a cut and apply `--set` changes.
pub fn load_with_sets(arg: &str, sets: &[String]) -> Result<Cut> {
    let changes = parse_sets(sets)?;
    let cut = io::load_cut(arg)?;
    // A recipe's tiers turn as the recipe places them (its meets, not the solid's).
    let recipe = match changes.is_empty() {
        true => None,
        false => io::recipe::read(std::path::Path::new(arg))?,
    };
    let set = match recipe {
        Some(r) => facetlab::design::recipe::RecipeSpace::new(r)
            .and_then(|space| facetlab::cut::CutSpace::build(&space, &cut.name, &changes)),
        None => facetlab::design::with_set(&cut, &changes),
    };
    set.map_err(|e| match e {
        // A tier's or parameter's error named by its key; the setting itself is spelled
        // `--set` by `flags::to_flags`.
        Error::Invalid { field, message }
            if !field.starts_with("--set") && field != facetlab::design::CUT_PARAMETER =>
        {
            Error::Invalid {
                field: format!("--set {field}"),
                message,
            }
        }
        other => other,
    })
}

/// `facetlab generate`.
pub fn generate(a: &GenerateArgs) -> Result<()> {
    // `generate t.toml --set … -o t.toml` would replace the design it read.
    refuse_overwrite(
        &[(setting::OUTPUT, a.output.clone())],
        &cut_files(std::slice::from_ref(&a.one.cut)),
    )?;
    check_new_file(setting::OUTPUT, &a.output, a.force)?;
    let cut = load_with_sets(&a.one.cut, &a.one.set)?;
    let ext = a
        .output
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    let bytes: Vec<u8> = match ext.as_str() {
        "svg" => facetlab::plot::diagram::diagram(&cut).into_bytes(),
        e if io::CUT_FORMATS.contains(&e) => io::write_cut(&cut, e)?,
        _ => {
            return Err(Error::invalid(
                "-o",
                format!(
                "cannot write `.{ext}`; allowed extensions: .toml, .asc, .gem, .obj, .stl, .svg"
            ),
            ))
        }
    };
    io::write_atomic(&a.output, &bytes)?;
    eprintln!(
        "wrote {} ({} facets)",
        a.output.display(),
        cut.solid.facets().len()
    );
    Ok(())
}

/// The material of a cut's weight: `chosen`, else a design's own (a GemCad file's index), else
/// diamond; the design's note said as `info` says it.
pub(crate) fn weight_material(chosen: Option<Material>, cut: &Cut) -> Result<Material> {
    let default = chosen.clone().unwrap_or_else(Material::diamond);
    // A design is traced in its own material unless one was chosen (only that is said).
    let stone = StoneChoice::new(
        default.clone(),
        chosen.is_some(),
        None,
        None,
        super::flags::STONE_FIELDS.colour,
    )?;
    Ok(stone
        .stones(
            std::slice::from_ref(cut),
            &super::flags::STONE_FIELDS,
            ColourNotes::Traced,
            &mut |kind, line| {
                if kind == NoteKind::Design {
                    super::flags::say(kind, line)
                }
            },
        )?
        .materials
        .into_iter()
        .next()
        .unwrap_or(default))
}

/// `facetlab info`.
pub fn info(a: &InfoArgs) -> Result<()> {
    facetlab::optics::StoneSize::check_mm(a.diameter_mm, "--diameter-mm")?;
    if !(a.meet_tol.is_finite() && a.meet_tol > 0.0 && a.meet_tol <= 0.01) {
        return Err(Error::invalid(
            "--meet-tol",
            format!(
                "{} is not allowed; give a tolerance in (0, 0.01] of W",
                facetlab::error::shown(a.meet_tol)
            ),
        ));
    }
    let cut = load_with_sets(&a.one.cut, &a.one.set)?;
    let material = weight_material(a.material.clone(), &cut)?;
    let lower = a.one.cut.to_ascii_lowercase();
    if lower.ends_with(".obj") || lower.ends_with(".stl") {
        if let Ok((_, Some(note))) = facetlab::io::mesh::read_with_note(&a.one.cut) {
            eprintln!("{}: {note}", a.one.cut);
        }
    }
    let width_mm = match &a.size_mm {
        Some(size) => size.width_mm(cut.ratios().l_w, "--size-mm")?,
        None => a.diameter_mm,
    };
    let mut j = info_json(&cut, width_mm, &material);
    if a.instructions {
        j.instructions = Some(io::asc::cutting_instructions(&cut, 0));
    }
    if a.meets {
        j.meets = Some(meets_json(&cut, a.meet_tol)?);
    }
    if a.json {
        let text = serde_json::to_string_pretty(&j)
            .map_err(|e| Error::invalid("--json", e.to_string()))?;
        println!("{text}");
        return Ok(());
    }
    print!("{}", super::flags::spelled(&info_text(&j)));
    if let Some(c) = &j.instructions {
        print!("\n{}", c.text());
    }
    if let Some(m) = &j.meets {
        print!("\n{}", meets_text(m, a.meet_tol));
    }
    Ok(())
}

/// Flags of `facetlab list`.
#[derive(Debug, Args)]
pub struct ListArgs {
    /// Print only the preset names, one per line (for scripts).
    #[arg(long)]
    pub names: bool,
}

/// `facetlab list`.
pub fn list(a: &ListArgs) -> Result<()> {
    if a.names {
        for n in io::presets::names() {
            println!("{n}");
        }
        return Ok(());
    }
    println!("Presets (use as CUT):");
    for n in io::presets::names() {
        let desc = match io::presets::load(n) {
            Some(Ok(c)) => format!("{} — {}", c.name, c.family.unwrap_or_default()),
            Some(Err(e)) => format!("(broken: {e})"),
            None => String::new(),
        };
        println!("  {n:<16} {desc}");
    }
    println!("\nFamilies and their parameters (--set KEY=VALUE; lengths are fractions of the girdle diameter):");
    for f in facetlab::cut::families() {
        println!("\n  {} — {}", f.name, f.doc);
        for p in f.params {
            let (l, r) = if p.open { ("(", ")") } else { ("[", "]") };
            let range = format!("{l}{}, {}{r} {}", p.min, p.max, p.unit.label());
            println!(
                "    {:<16} default {:<7} {:<40} {}",
                p.key, p.default, range, p.doc
            );
        }
    }
    Ok(())
}
