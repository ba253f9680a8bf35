//! `generate` and `info`.

use clap::Args;
use facetlab::cut::Cut;
use facetlab::error::{Error, Result};
use facetlab::io;
use facetlab::optics::Material;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Flags of `facetlab generate`.
#[derive(Debug, Args)]
pub struct GenerateArgs {
    /// Preset name or path (.toml, .asc, .gem, .obj, .stl).
    pub cut: String,
    /// Change a parameter: a family's (`--set crown_angle=34.5`) or a design's tier angle
    /// (`--set P1=41.2`, depths solved so its meets are kept). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
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
    /// Preset name or path (.toml, .asc, .gem, .obj, .stl).
    pub cut: String,
    /// Change a parameter: a family's (`--set table=0.55`) or a design's tier angle
    /// (`--set P1=41.2`, depths solved so its meets are kept). Repeatable.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Print JSON instead of a table (keys documented in the README).
    #[arg(long)]
    pub json: bool,
    /// Girdle width W (a round's diameter) in millimetres, for the carat weight.
    #[arg(long, value_name = "MM", default_value_t = 6.5)]
    pub diameter_mm: f64,
    /// The stone's size in millimetres instead: its length L (the width follows from the
    /// design's L/W), or LxW (which must match the design's L/W within 1 %).
    #[arg(long, value_name = "L[xW]", conflicts_with = "diameter_mm")]
    pub size_mm: Option<String>,
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
    #[arg(long)]
    pub material: Option<String>,
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
    facetlab::design::with_set(&cut, &changes).map_err(|e| match e {
        Error::Invalid { field, message } if !field.starts_with("--set") => Error::Invalid {
            field: format!("--set {field}"),
            message,
        },
        other => other,
    })
}

/// `facetlab generate`.
pub fn generate(a: &GenerateArgs) -> Result<()> {
    // `generate t.toml --set … -o t.toml` would replace the design it read.
    super::outputs::refuse_overwrite(
        &[("-o", a.output.clone())],
        &super::outputs::cut_files(std::slice::from_ref(&a.cut)),
    )?;
    super::outputs::check_new_file("-o", &a.output, a.force)?;
    let cut = load_with_sets(&a.cut, &a.set)?;
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

/// JSON of `info` (keys documented in the README).
#[derive(Debug, Serialize)]
pub struct InfoJson {
    /// Cut name.
    pub name: String,
    /// Family, if generated from one.
    pub family: Option<String>,
    /// Family parameters.
    pub params: BTreeMap<String, f64>,
    /// Number of facets, girdle facets included.
    pub facet_count: usize,
    /// Number of vertices.
    pub vertex_count: usize,
    /// Volume in widths W cubed (girdle diameters for a round).
    pub volume: f64,
    /// Measured proportions.
    pub proportions: facetlab::cut::Proportions,
    /// Tiers: name, mean angle, count, side.
    pub tiers: Vec<facetlab::cut::TierSummary>,
    /// Girdle width W used for the weight, mm (a round's diameter).
    pub diameter_mm: f64,
    /// The stone's length, width and depth in mm for that width.
    pub size_mm: SizeMm,
    /// GemCad's ratios over the width: `l_w`, `t_w`, `p_w`, `c_w`, `h_w`, `vol_w3`.
    pub ratios: facetlab::cut::Ratios,
    /// Material used for the weight.
    pub material: String,
    /// Weight in carats for that diameter and material.
    pub carats: f64,
    /// Geometric checks: closed surface (V − E + F = 2).
    pub checks: Checks,
    /// Proportion grade estimate (round brilliants of the `round-brilliant` family only):
    /// `estimate` (`excellent` … `poor`), `limiting` (the parameters that set it),
    /// `parameters` (each with its value, grade and that grade's range), `note`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grade: Option<facetlab::cut::grade::GradeEstimate>,
    /// Cutting instructions (with `--instructions`): `gear`, `gear_offset`, `ri`, and
    /// `steps[]` with `step`, `side`, `tier`, `angle`, `indices`, `note`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub instructions: Option<facetlab::io::asc::CuttingInstructions>,
    /// The design's meets (with `--meets`): `tiers`, `facets`, `point` [x, y, z] in W, `off`
    /// (how far the farthest of its planes passes from the point, in W).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meets: Option<Vec<MeetJson>>,
    /// What a GemCad design file says about itself: `ri`, `title`, `footnotes`, `gear`,
    /// `gear_offset`, `symmetry`, `mirror`, `instructions` (by facet name), `scale` (file
    /// units per girdle width); absent for generated cuts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub design: Option<facetlab::cut::GemcadRecord>,
}

/// A stone's size in millimetres.
#[derive(Debug, Serialize)]
pub struct SizeMm {
    /// Length (the outline's larger extent along x and y).
    pub length: f64,
    /// Width (its smaller extent).
    pub width: f64,
    /// Depth (top to bottom).
    pub depth: f64,
}

/// The width W in mm from `--size-mm L[xW]` for a design of length/width `l_w` (the same rule
/// as `score`'s and `render`'s `--size-mm`: [`facetlab::optics::StoneSize`]).
pub fn width_from_size(size: &str, l_w: f64) -> Result<f64> {
    facetlab::optics::StoneSize::parse_length(size, "--size-mm")?.width_mm(l_w, "--size-mm")
}

/// Geometric checks reported by `info`.
#[derive(Debug, Serialize)]
pub struct Checks {
    /// V − E + F.
    pub euler_characteristic: i64,
    /// Every edge separates exactly two facets and V − E + F = 2.
    pub closed: bool,
    /// Smallest facet area over the mean facet area.
    pub smallest_facet_ratio: f64,
}

/// Build the `info` record.
pub fn info_json(cut: &Cut, diameter_mm: f64, material: &Material) -> InfoJson {
    let s = &cut.solid;
    let volume = s.volume();
    let ratios = cut.ratios();
    // Lengths are per width W (the unit convention); W is `diameter_mm` millimetres.
    let w = facetlab::cut::units::outline_size(s.vertices())
        .1
        .max(1e-300);
    let mm3 = volume / (w * w * w) * diameter_mm.powi(3);
    let carats = mm3 * 1e-3 * material.density / 0.2;
    let euler = s.vertices().len() as i64 - s.edges().len() as i64 + s.facets().len() as i64;
    let mean = s.surface_area() / s.facets().len() as f64;
    let smallest = s
        .facets()
        .iter()
        .map(|f| f.area)
        .fold(f64::INFINITY, f64::min);
    InfoJson {
        name: cut.name.clone(),
        family: cut.family.clone(),
        params: cut.params.clone(),
        facet_count: s.facets().len(),
        vertex_count: s.vertices().len(),
        volume,
        proportions: cut.proportions(),
        tiers: cut.tiers(),
        diameter_mm,
        size_mm: SizeMm {
            length: ratios.l_w * diameter_mm,
            width: diameter_mm,
            depth: ratios.h_w * diameter_mm,
        },
        ratios,
        material: material.name.clone(),
        carats,
        checks: Checks {
            euler_characteristic: euler,
            closed: euler == 2,
            smallest_facet_ratio: smallest / mean,
        },
        grade: facetlab::cut::grade::estimate(cut),
        design: cut.record.clone(),
        instructions: None,
        meets: None,
    }
}

/// `facetlab info`.
pub fn info(a: &InfoArgs) -> Result<()> {
    if !(a.diameter_mm.is_finite() && a.diameter_mm > 0.0 && a.diameter_mm < 1000.0) {
        return Err(Error::invalid(
            "--diameter-mm",
            format!(
                "{} is not allowed; give a diameter in (0, 1000) mm",
                a.diameter_mm
            ),
        ));
    }
    if !(a.meet_tol.is_finite() && a.meet_tol > 0.0 && a.meet_tol <= 0.01) {
        return Err(Error::invalid(
            "--meet-tol",
            format!(
                "{} is not allowed; give a tolerance in (0, 0.01] of W",
                a.meet_tol
            ),
        ));
    }
    let chosen = a.material.as_deref().map(Material::by_name).transpose()?;
    let cut = load_with_sets(&a.cut, &a.set)?;
    let default = chosen.clone().unwrap_or_else(Material::diamond);
    let (materials, notes) =
        super::flags::design_materials(std::slice::from_ref(&cut), &default, chosen.is_some());
    for note in notes {
        eprintln!("{note}");
    }
    let material = materials.into_iter().next().unwrap_or(default);
    let lower = a.cut.to_ascii_lowercase();
    if lower.ends_with(".obj") || lower.ends_with(".stl") {
        if let Ok((_, Some(note))) = facetlab::io::mesh::read_with_note(&a.cut) {
            eprintln!("{}: {note}", a.cut);
        }
    }
    let width_mm = match &a.size_mm {
        Some(size) => width_from_size(size, cut.ratios().l_w)?,
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
    print!("{}", info_text(&j));
    if let Some(c) = &j.instructions {
        print!("\n{}", c.text());
    }
    if let Some(m) = &j.meets {
        print!("\n{}", meets_text(m, a.meet_tol));
    }
    Ok(())
}

/// One meet of `info --meets`.
#[derive(Debug, Serialize)]
pub struct MeetJson {
    /// The tiers it joins (GemCad line names), each once.
    pub tiers: Vec<String>,
    /// The facets through it.
    pub facets: Vec<String>,
    /// The point, in W.
    pub point: [f64; 3],
    /// How far the farthest of its planes passes from the point, in W.
    pub off: f64,
}

fn meets_json(cut: &Cut, tol: f64) -> Result<Vec<MeetJson>> {
    let model = facetlab::design::TierModel::of_cut(cut, tol)?;
    Ok(model
        .meets
        .iter()
        .map(|m| MeetJson {
            tiers: model.meet_tiers(m).iter().map(|t| t.to_string()).collect(),
            facets: m
                .facets
                .iter()
                .map(|&f| cut.solid.facets()[f].name.clone())
                .collect(),
            point: m.point.to_array(),
            off: m.gap,
        })
        .collect())
}

fn meets_text(meets: &[MeetJson], tol: f64) -> String {
    use std::fmt::Write;
    let worst = meets.iter().map(|m| m.off).fold(0.0, f64::max);
    let mut o = format!(
        "Meets ({} where four or more facets pass within {tol:e} W of one point; farthest plane {worst:.1e} W)\n",
        meets.len()
    );
    let _ = writeln!(
        o,
        "  {:<36} {:>8} {:>8} {:>8}  {:>8}",
        "tiers (facets)", "x", "y", "z", "off"
    );
    for m in meets {
        let tiers = format!("{} ({})", m.tiers.join(" "), m.facets.len());
        let [x, y, z] = m.point;
        let _ = writeln!(
            o,
            "  {tiers:<36} {x:>8.4} {y:>8.4} {z:>8.4}  {:>8.1e}",
            m.off
        );
    }
    o
}

/// Human-readable `info`.
pub fn info_text(j: &InfoJson) -> String {
    use std::fmt::Write;
    let mut o = String::new();
    let fam = j
        .family
        .as_deref()
        .map(|f| format!(" ({f})"))
        .unwrap_or_default();
    let _ = writeln!(o, "{}{fam}", j.name);
    if let Some(d) = &j.design {
        for t in d.title.iter().filter(|t| !t.trim().is_empty()) {
            let _ = writeln!(o, "  {}", t.trim());
        }
        let ri = d.ri.map(|n| format!(", index {n}")).unwrap_or_default();
        let _ = writeln!(
            o,
            "  GemCad design: gear {} (offset {}), {}-fold symmetry{}{ri}",
            d.gear,
            d.gear_offset,
            d.symmetry,
            if d.mirror { " with mirror" } else { "" }
        );
        for f in &d.footnotes {
            let _ = writeln!(o, "  note: {f}");
        }
    }
    let p = &j.proportions;
    let pct = |v: f64| format!("{:6.1} %", v * 100.0);
    let _ = writeln!(o, "\nProportions (lengths as % of the width W)");
    let _ = writeln!(o, "  table            {}", pct(p.table));
    let _ = writeln!(o, "  crown angle      {:6.2} °", p.crown_angle);
    let _ = writeln!(o, "  pavilion angle   {:6.2} °", p.pavilion_angle);
    let _ = writeln!(o, "  crown height     {}", pct(p.crown_height));
    let _ = writeln!(o, "  pavilion depth   {}", pct(p.pavilion_depth));
    let _ = writeln!(o, "  total depth      {}", pct(p.total_depth));
    let _ = writeln!(o, "  girdle           {}", pct(p.girdle));
    let _ = writeln!(o, "\nTiers                 angle   count");
    for t in &j.tiers {
        let _ = writeln!(
            o,
            "  {:<16} {:8.2} ° {:5}   {}",
            t.name, t.angle, t.count, t.side
        );
    }
    if j.family.is_none() {
        let _ = writeln!(
            o,
            "  (--set TIER=DEG turns a tier; the depths follow so that the meets are kept)"
        );
    }
    let _ = writeln!(
        o,
        "\nFacets {}   vertices {}   volume {:.5} W³",
        j.facet_count, j.vertex_count, j.volume
    );
    let r = &j.ratios;
    let _ = writeln!(
        o,
        "Ratios L/W {:.3}   T/W {:.3}   P/W {:.3}   C/W {:.3}   H/W {:.3}   Vol/W³ {:.4}",
        r.l_w, r.t_w, r.p_w, r.c_w, r.h_w, r.vol_w3
    );
    let z = &j.size_mm;
    let _ = writeln!(
        o,
        "Size {:.2} × {:.2} × {:.2} mm (L × W × D)   weight {:.3} ct in {}",
        z.length, z.width, z.depth, j.carats, j.material
    );
    if j.material.starts_with("ri:") {
        let _ = writeln!(
            o,
            "  ({} has no density of its own: the weight uses diamond's, 3.515 g/cm³)",
            j.material
        );
    }
    let c = &j.checks;
    let _ = writeln!(
        o,
        "Checks: convex solid, {} (V − E + F = {}), smallest facet {:.3} of the mean area",
        if c.closed { "closed" } else { "NOT closed" },
        c.euler_characteristic,
        c.smallest_facet_ratio
    );
    if let Some(g) = &j.grade {
        let limit = if g.limiting.is_empty() {
            String::new()
        } else {
            format!(", limited by {}", g.limiting.join(", "))
        };
        let _ = writeln!(
            o,
            "Grade estimate: {}{limit} ({})",
            g.estimate.name(),
            g.note
        );
    }
    if !j.params.is_empty() {
        let _ = writeln!(o, "\nParameters (--set KEY=VALUE)");
        for (k, v) in &j.params {
            let _ = writeln!(o, "  {k:<16} {v}");
        }
    }
    o
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
