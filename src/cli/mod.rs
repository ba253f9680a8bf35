//! The command line: a thin layer that validates flags into the library's own types and calls
//! it. Each subcommand lives in its own module.

mod batch;
mod cuts;
mod design;
pub mod flags;
mod interrupt;
pub mod materials;
pub mod merge;
pub mod optimize;
pub mod outputs;
pub mod plan;
mod progress;
pub mod render;
pub mod report;
pub mod retarget;
pub mod score;
pub mod serve;
mod sheet;
pub mod trace;
#[cfg(test)]
mod walk_tests;

use clap::{Parser, Subcommand};
use facetlab::error::Result;
pub use outputs::Exit;

/// facetlab: design, score and optimize cut gemstones with real optics.
///
/// CUT is a preset name (tolkowsky, gia-reference, …) or a path to a .toml spec, a GemCad .asc
/// or .gem design, or an .obj/.stl mesh (taken as its convex hull). Lengths are fractions of the girdle
/// diameter (table 0.57), angles are degrees.
#[derive(Debug, Parser)]
#[command(
    name = "facetlab",
    version,
    about,
    long_about = None,
    propagate_version = true,
    after_help = "Exit codes: 0 done; 1 done, but `score --verify` found a disagreement between the tracers; 2 bad input (one line on stderr); 130 interrupted (Ctrl-C or SIGTERM; `optimize` and `plan` still write what they found)."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Write a cut to a file: .toml spec, .asc or .gem (GemCad), .obj, .stl or .svg diagram, by
    /// extension.
    Generate(cuts::GenerateArgs),
    /// Build a design from a recipe written tier by tier (cut to meet, to the centre point, a
    /// girdle, a table width; angles as expressions), or write the recipe of an existing
    /// design with --from.
    Design(design::DesignArgs),
    /// Show a cut's proportions, tiers, facet count, volume and carat weight.
    Info(cuts::InfoArgs),
    /// A cutting sheet to print: the design's header and ratios, its views with every facet's
    /// name and index, one row per tier in cutting order (.html, .svg or .pdf, one A4 page);
    /// `--mode`: the cutting mode, one step per screen with the stone as cut so far (.html).
    Sheet(sheet::SheetArgs),
    /// List the bundled presets and the families with their parameters (defaults, ranges).
    List(cuts::ListArgs),
    /// List the materials: n_D, B–G dispersion, density, which ray of a birefringent stone,
    /// the dispersion formula and its source; `--material ri:N[:BG]` gives any index.
    Materials(materials::MaterialsArgs),
    /// Shoot photons through cuts (the thesis's forward Monte Carlo): face categories, exit
    /// angles, light return; overhead, offset, directed or rotating light.
    Trace(Box<trace::TraceArgs>),
    /// Score cuts with the beam tracer: brilliance, fire, scintillation, ASET shares, overhead
    /// light return; `--verify N` re-measures with the photon tracer.
    Score(score::ScoreArgs),
    /// Search a family's proportions for the best weighted brilliance, fire and scintillation
    /// (argmin Nelder–Mead or particle swarm), then verify the winners with the photon tracer.
    /// Ctrl-C or SIGTERM stops the search and still writes the run folder (exit code 130).
    Optimize(optimize::OptimizeArgs),
    /// Map a score over a grid of parameters (--x, --y, more with --axis; CSV and a heatmap
    /// with contours of any two), or, without --y, the scores along one (CSV and a line
    /// chart); --shard K/N evaluates one resumable share of the grid for job arrays.
    ///
    /// More axes with --axis (the map shows two of them: --map, --at); --shard K/N (or a Slurm
    /// or Kubernetes job array) evaluates a share of the grid, resumably, for `merge`.
    Sweep(optimize::SweepArgs),
    /// One self-contained HTML page per cut or comparing cuts: COS (15° head shadow), ASET and
    /// fire pictures, the diagram, proportions with the grade estimate, every score explained,
    /// `--verify N`.
    Report(report::ReportArgs),
    /// Adapt a design to another refractive index: the tangent-ratio rule, an optimized pair
    /// of ratios that restores its light return there and, for a design (.asc), its tier
    /// angles optimized with the meets kept; all reported, the better optimized one written.
    Retarget(retarget::RetargetArgs),
    /// Plan a rough: the largest, best cuts of each family inside a rough stone (an OBJ/STL
    /// mesh in mm, taken as its convex hull, or a crystal form with --size-mm), each placed by
    /// an exact containment program and searched over orientation and proportions; writes a
    /// run folder with the cuts in the rough's coordinates, pictures and summary.json.
    /// Ctrl-C or SIGTERM stops it and writes the families planned so far (exit code 130).
    Plan(plan::PlanArgs),
    /// Join the shards of one sweep (`sweep --shard K/N`) into the CSV and map one unsharded
    /// run writes, after checking they cover the grid exactly once.
    Merge(merge::MergeArgs),
    /// Draw cuts as a cutter sees them: one PNG, side by side, statistics below each.
    ///
    /// Lights: iso or cos (GemRay), aset and idealscope false colours (with a legend), the
    /// hearts & arrows viewer, fire under spot lights, or a photograph under a studio rig or an
    /// environment map (every name: --light in `facetlab render --help`). Face-up, tilted (--tilt 10@45) or
    /// rocking as an animated PNG (--rock 15:24). --json writes the statistics.
    Render(Box<render::RenderArgs>),
    /// The cutter's workbench in the browser: a local web server with one page (presets and
    /// uploads, parameter sliders, live render, diagram, scores, a second cut to compare,
    /// downloads and reports, optimization runs with live convergence). Listens on 127.0.0.1 unless --bind says otherwise; prints the URL.
    Serve(serve::ServeArgs),
}

/// Run a parsed command line; the `Exit` is the process's exit status (an `Err` is bad input,
/// exit code 2).
pub fn run(cli: Cli) -> Result<Exit> {
    let done = |r: Result<()>| r.map(|()| Exit::Ok);
    let result = match cli.command {
        Command::Generate(a) => done(cuts::generate(&a)),
        Command::Design(a) => done(design::run(&a)),
        Command::Info(a) => done(cuts::info(&a)),
        Command::Sheet(a) => done(sheet::run(&a)),
        Command::List(a) => done(cuts::list(&a)),
        Command::Materials(a) => done(materials::run(&a)),
        Command::Trace(a) => done(trace::run(&a)),
        Command::Score(a) if batch::asked(&a) => batch::run(&a),
        Command::Score(a) => score::run(&a),
        Command::Optimize(a) => optimize::run_optimize(&a, &optimize::real_scorers),
        Command::Sweep(a) => optimize::run_sweep(&a, &optimize::real_scorers),
        Command::Merge(a) => merge::run(&a),
        Command::Render(a) => done(render::run(&a)),
        Command::Report(a) => done(report::run(&a)),
        Command::Retarget(a) => done(retarget::run(&a)),
        Command::Plan(a) => plan::run(&a),
        Command::Serve(a) => done(serve::run(&a)),
    };
    result.map_err(flags::to_flags)
}
