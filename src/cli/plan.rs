//! `facetlab plan ROUGH -o DIR`: the largest, best cuts inside a rough stone.
//!
//! ```text
//! facetlab plan cuts/rough-octahedron.obj -o results/rough            # every default family
//! facetlab plan octahedron --size-mm 6 --family round-brilliant --top 2 -o results/oct
//! facetlab plan scan.stl --size-mm 9.5 --config optim/plan/plan-value.toml -o results/scan
//! ```
//!
//! The planning and the run folder are the library's ([`facetlab::plan::plan_families`],
//! [`facetlab::plan::write_folder`], whose documentation lists the folder's files); this file
//! reads the flags, runs them with a progress bar and prints what was written.

use super::interrupt;
use super::outputs::Exit;
use super::progress;
use facetlab::error::{Error, Result};
use facetlab::optics::Material;
use facetlab::plan::config::{check_families, MAX_GAP_MM, MAX_STONES};
use facetlab::plan::{
    check_out, load_rough, plan_families, plan_layout, plan_warnings, write_folder, Cutter,
    Inclusion, PlanConfig, Run, CRYSTALS,
};
use facetlab::report::PlanDrawings;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Flags of `facetlab plan`.
#[derive(clap::Args, Debug, Clone)]
pub struct PlanArgs {
    /// The rough: an .obj or .stl mesh in millimetres (its convex hull is planned), or a
    /// crystal form (octahedron, dodecahedron, cube, macle, or sphere: an exact ball) with --size-mm.
    #[arg(value_name = "ROUGH")]
    // A String on purpose: a mesh file's path or a crystal form's name.
    pub rough: String,
    /// A family to plan (repeat for more); default: the config's, or round-brilliant and the
    /// fancy shapes.
    #[arg(long = "family", value_name = "NAME")]
    pub families: Vec<String>,
    /// Plan config (objective, bounds, search; see docs/plan.md).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The rough's largest extent in mm: scales a mesh in other units, sizes a crystal form.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = size_flag)]
    pub size_mm: Option<f64>,
    /// Material for the carat weight and the scores (`facetlab materials`); default diamond.
    #[arg(long, value_name = "NAME")]
    // A String on purpose: the name as given goes into the run's config.
    pub material: Option<String>,
    /// Distinct plans kept per family (1–50); default the config's (3).
    #[arg(
        long,
        value_name = "K",
        allow_hyphen_values = true,
        value_parser = super::flags::whole("--top", 1, 50)
    )]
    pub top: Option<u64>,
    /// Stones to place in the rough (1–8; default the config's, 1): 2 and more saw the rough
    /// into pieces, one stone each, ranked by the objective: weight, value, or value × colour
    /// (docs/plan.md).
    #[arg(
        long,
        value_name = "N",
        allow_hyphen_values = true,
        value_parser = super::flags::whole("--stones", 1, MAX_STONES as u64)
    )]
    pub stones: Option<u64>,
    /// The saw's kerf in mm (default the config's, 0.30).
    #[arg(long, value_name = "MM", allow_hyphen_values = true,
          value_parser = super::flags::real("--kerf", 0.0, MAX_GAP_MM, "the saw's kerf in mm"))]
    pub kerf: Option<f64>,
    /// The polishing allowance per stone in mm (default the config's, 0.20).
    #[arg(long, value_name = "MM", allow_hyphen_values = true,
          value_parser = super::flags::real("--allowance", 0.0, MAX_GAP_MM, "the polishing allowance in mm"))]
    pub allowance: Option<f64>,
    /// How the stones are parted: saw (straight cuts through a piece, in turn; the default)
    /// or laser (a kerf-wide cut along a plane between each pair of stones).
    #[arg(long, value_name = "saw|laser", value_parser = super::flags::parsed("--cutter", Cutter::named))]
    pub cutter: Option<Cutter>,
    /// An inclusion: a closed .obj or .stl mesh in mm in the rough's coordinates (repeat for
    /// more); no stone comes within the margin of its convex hull.
    #[arg(long = "inclusion", value_name = "FILE")]
    pub inclusions: Vec<PathBuf>,
    /// How far stones keep from an inclusion, mm (default the config's, 0.30).
    #[arg(long, value_name = "MM", allow_hyphen_values = true,
          value_parser = super::flags::real("--margin", 0.0, MAX_GAP_MM, "the inclusions' margin in mm"))]
    pub margin: Option<f64>,
    /// The run folder to write (must not exist, or be empty).
    #[arg(short = 'o', long = "out", value_name = "DIR")]
    pub out: PathBuf,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// The value parser of `--size-mm`: the rough's largest extent.
fn size_flag(s: &str) -> Result<f64> {
    facetlab::plan::parse_rough_size_mm("--size-mm", s)
}

/// Run `facetlab plan`. Exits 130 when Ctrl-C or SIGTERM stopped it (after writing the
/// families planned so far, if any).
pub fn run(a: &PlanArgs) -> Result<Exit> {
    let started = Instant::now();
    let mut config = match &a.config {
        Some(p) => PlanConfig::load(p)?,
        None => PlanConfig::default(),
    };
    if !a.families.is_empty() {
        config.families = check_families(&a.families).map_err(|m| Error::invalid("--family", m))?;
    }
    if let Some(t) = a.top {
        config.top = t as usize;
    }
    if let Some(m) = &a.material {
        Material::by_name(m)?;
        config.material = m.clone();
    }
    if let Some(n) = a.stones {
        config.stones = n as usize;
    }
    if let Some(k) = a.kerf {
        config.kerf_mm = k;
    }
    if let Some(k) = a.allowance {
        config.allowance_mm = k;
    }
    if let Some(k) = a.margin {
        config.margin_mm = k;
    }
    if let Some(c) = a.cutter {
        config.cutter = c;
    }
    let material = Material::by_name(&config.material)?;
    let size = a.size_mm;
    if !a.inclusions.is_empty() && size.is_some() && !CRYSTALS.contains(&a.rough.as_str()) {
        return Err(Error::invalid(
            "--inclusion",
            "a mesh rescaled by --size-mm has no coordinates the inclusions could share; give the rough in mm without --size-mm",
        ));
    }
    let inclusions: Vec<Inclusion> = a
        .inclusions
        .iter()
        .map(|p| Inclusion::from_mesh(p, config.margin_mm))
        .collect::<Result<_>>()?;
    for p in &a.inclusions {
        facetlab::io::guard::refuse_overwrite(
            &[("--out", a.out.clone())],
            std::slice::from_ref(p),
        )?;
    }
    // Outputs: a new or empty folder that is none of the inputs (the rough, the config, the
    // price table it names).
    check_out("--out", &a.out, &a.rough, a.config.as_deref(), &config)?;
    let rough = load_rough(&a.rough, size).map_err(|e| match e {
        Error::Invalid { field, message }
            if field == "ROUGH"
                && !CRYSTALS.contains(&a.rough.as_str())
                && !Path::new(&a.rough).exists() =>
        {
            Error::io(
                &a.rough,
                format!("no such file, and not a crystal form; {message}"),
            )
        }
        other => other,
    })?;

    interrupt::install();
    if config.stones > 1 || !inclusions.is_empty() {
        return run_layout(a, &config, &material, &rough, &inclusions, started);
    }
    let bar = progress::bar(
        (config.families.len() * config.starts) as u64,
        a.quiet,
        "{msg:>16} [{bar:40}] {pos}/{len} starts, {elapsed}",
    );
    let tick = || bar.inc(1);
    let family = |f: &str| {
        bar.set_message(f.to_string());
        true
    };
    let all = plan_families(
        &rough,
        &config,
        &material,
        &family,
        &tick,
        Some(&interrupt::STOP),
    );
    bar.finish_and_clear();
    let all = all?;
    let interrupted = interrupt::stopped();
    if interrupted && all.is_empty() {
        eprintln!(
            "facetlab: interrupted before any family was planned; nothing written (exit code 130)"
        );
        return Ok(Exit::Interrupted);
    }
    let warnings = plan_warnings(&config, &all);
    let run = Run {
        out: &a.out,
        input: &a.rough,
        config: &config,
        material: &material,
        rough: &rough,
        all: &all,
        started,
        warnings: &warnings,
        layout: None,
        inclusions: &[],
    };
    write_folder(&run, &PlanDrawings)?;
    print_summary(&run);
    for w in &warnings {
        eprintln!("facetlab: warning: {w}");
    }
    if interrupted {
        let done: Vec<&str> = all.iter().map(|(f, _)| f.as_str()).collect();
        let left: Vec<&str> = config
            .families
            .iter()
            .map(String::as_str)
            .filter(|f| !done.contains(f))
            .collect();
        eprintln!(
            "facetlab: interrupted; wrote the families planned ({}), not {} (exit code 130)",
            done.join(", "),
            left.join(", ")
        );
        return Ok(Exit::Interrupted);
    }
    Ok(Exit::Ok)
}

/// `facetlab plan --stones N` (or with inclusions): the layout, its folder and its lines.
fn run_layout(
    a: &PlanArgs,
    config: &PlanConfig,
    material: &Material,
    rough: &facetlab::plan::Rough,
    inclusions: &[Inclusion],
    started: Instant,
) -> Result<Exit> {
    let bar = progress::bar(
        facetlab::plan::layout::candidates(config).max(1),
        a.quiet,
        "{msg:>16} [{bar:40}] {pos}/{len} saw cuts judged, {elapsed}",
    );
    bar.set_message("layout");
    let tick = || bar.inc(1);
    let layout = plan_layout(
        rough,
        config,
        material,
        inclusions,
        &tick,
        Some(&interrupt::STOP),
    );
    bar.finish_and_clear();
    if interrupt::stopped() {
        eprintln!(
            "facetlab: interrupted before the layout was planned; nothing written (exit code 130)"
        );
        return Ok(Exit::Interrupted);
    }
    let layout = layout?;
    let run = Run {
        out: &a.out,
        input: &a.rough,
        config,
        material,
        rough,
        all: &[],
        started,
        warnings: &[],
        layout: Some(&layout),
        inclusions,
    };
    write_folder(&run, &PlanDrawings)?;
    println!("rough {}: {:.3} mm³", rough.name, rough.volume());
    for (k, c) in layout.saw.iter().enumerate() {
        println!(
            "{} {} ({}): normal ({:.4}, {:.4}, {:.4}), offset {:.3} mm, kerf loss {:.3} mm³",
            layout.cutter.name(),
            k + 1,
            c.piece,
            c.normal.x,
            c.normal.y,
            c.normal.z,
            c.offset,
            c.kerf_loss_mm3
        );
    }
    for (k, s) in layout.stones.iter().enumerate() {
        let holds = if s.holds.is_empty() {
            ""
        } else {
            ", holds an inclusion"
        };
        // Ranked by colour: its worth, face-up chroma and colour factor.
        let colour = match (s.colour, s.plan.colour) {
            (Some(w), Some(c)) => format!(
                ", worth {:.4} × colour {:.3} (C* {:.1})",
                w.worth, w.factor, c.c
            ),
            _ => String::new(),
        };
        println!(
            "stone-{} {:<16} {:.4} ct, W {:.3} mm, objective {:.4}{colour}{holds}",
            k + 1,
            s.family,
            s.plan.carats,
            s.plan.scale,
            s.plan.objective
        );
    }
    println!(
        "total {:.4} ct, objective {:.4}, yield {:.2} %, kerf loss {:.3} mm³",
        layout.carats,
        layout.total,
        100.0 * layout.yield_fraction,
        layout.kerf_loss_mm3
    );
    println!("{}", a.out.display());
    Ok(Exit::Ok)
}

/// The lines `facetlab plan` prints at the end: the rough, each family's best, the folder.
fn print_summary(run: &Run<'_>) {
    let rough = run.rough;
    let hull = match rough.mesh_volume {
        Some(v) => format!(
            " (the mesh {v:.3} mm³; its convex hull adds {:.2} %)",
            100.0 * rough.hull_excess()
        ),
        None => String::new(),
    };
    println!("rough {}: {:.3} mm³{hull}", rough.name, rough.volume());
    if rough.left_out > 0.0 {
        println!(
            "  planned in the hull of {} of its vertices, inside the full hull; the farthest vertex left out lies {:.1} µm outside it",
            rough.hull_vertices,
            1000.0 * rough.left_out
        );
    }
    for (fam, plans) in run.all {
        if let Some(p) = plans.first() {
            let colour = p.colour.map_or(String::new(), |c| {
                format!(", colour C* {:.1} (L* {:.1})", c.c, c.l)
            });
            println!(
                "{fam:<16} {:.4} ct, yield {:.2} %, W {:.3} mm{colour}",
                p.carats,
                100.0 * p.yield_fraction,
                p.scale
            );
        }
    }
    println!("{}", run.out.display());
}
