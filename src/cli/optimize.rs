//! `optimize` and `sweep`: flags, progress bars, Ctrl-C and SIGTERM, the checks of the output
//! folder before any work, and the summary printed at the end.
//!
//! Both take the objective's scorer as an [`Evaluator`] (and `optimize` the photon tracer as a
//! [`Verifier`]), so the command line stays thin and the scorers are wired in one place.

use super::outputs::{refuse_overwrite, Exit};
use super::progress::bar;
use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optimize::{
    self as opt, Axis, AxisRecord, Grid, GridCell, Shard, ShardRecord, SweepScore,
};
use facetlab::optimize::{BeamEvaluator, PhotonVerifier, Progress, Status};
use facetlab::optimize::{Config, Evaluator, Verifier};
use facetlab::optimize::{CutWriter, FnWriter, Hooks, RunOptions};
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

/// Flags of `facetlab optimize`.
#[derive(Debug, Args)]
pub struct OptimizeArgs {
    /// Optimization config (TOML), e.g. optim/round-brilliance.toml.
    pub config: PathBuf,
    /// Run folder to write (default: results/NAME-UTCTIME/, NAME from the config). It is
    /// made only when the results are written; a folder that is not empty is refused unless
    /// --force.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Write into an --out folder that is not empty (files of the same name are replaced; the
    /// config read is never overwritten).
    #[arg(long)]
    pub force: bool,
    /// Override the config's seed.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
    /// Skip the photon-tracer verification of the winners.
    #[arg(long)]
    pub no_verify: bool,
    /// No progress bar (it is also hidden when stderr is not a terminal).
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

/// Flags of `facetlab sweep`.
#[derive(Clone, Debug, Args)]
pub struct SweepArgs {
    /// Optimization config (TOML): the family, the other parameters' values, the objective.
    pub config: PathBuf,
    /// First axis: KEY:MIN:MAX:STEP, e.g. crown_angle:25:40:0.5.
    #[arg(long = "x", value_name = "KEY:MIN:MAX:STEP")]
    pub x: Option<String>,
    /// Second axis: KEY:MIN:MAX:STEP, e.g. pavilion_angle:38:43:0.1. With one axis only the
    /// sweep is a profile: a CSV and a line chart of every score.
    #[arg(long = "y", value_name = "KEY:MIN:MAX:STEP")]
    pub y: Option<String>,
    /// Further axes (repeatable), after --x and --y. The grid is their Cartesian product, the
    /// first axis varying fastest; the CSV has one column per axis.
    #[arg(long = "axis", value_name = "KEY:MIN:MAX:STEP")]
    pub axis: Vec<String>,
    /// The two axes the map shows, KEY1,KEY2 (one KEY: a profile along it). Default: the first
    /// two axes.
    #[arg(long, value_name = "KEY1,KEY2")]
    pub map: Option<String>,
    /// Where the map holds an axis it does not show (repeatable; snapped to the nearest grid
    /// value). Default: the grid value nearest the axis' middle.
    #[arg(long, value_name = "KEY=VALUE")]
    pub at: Vec<String>,
    /// Evaluate only shard K of N (1-based): the grid points whose index i has
    /// i mod N == K-1, into OUT/shard-K-of-N/ (shard.json, rows.csv), resuming what it already
    /// wrote; `facetlab merge` joins the shards. Without it, Slurm's SLURM_ARRAY_TASK_ID
    /// (- SLURM_ARRAY_TASK_MIN) of SLURM_ARRAY_TASK_COUNT, or Kubernetes' JOB_COMPLETION_INDEX
    /// of JOB_COMPLETION_COUNT, choose the shard when set; `--shard off` ignores them.
    #[arg(long, value_name = "K/N|off")]
    pub shard: Option<String>,
    /// The score drawn on the map and summarised: brilliance, fire, scintillation,
    /// or objective (the config's weighted score minus penalties). The CSV has all of them.
    #[arg(long, default_value = "brilliance")]
    pub score: String,
    /// A run folder of `facetlab optimize`: draw its path (best point so far) on the map
    /// (2-D maps only).
    #[arg(long, value_name = "DIR")]
    pub run: Option<PathBuf>,
    /// Output folder (sweep.csv, sweep.png, sweep.svg in it), or a file name whose stem is
    /// used for all three (map.png → map.csv, map.png, map.svg). With a shard: the sweep's
    /// folder, which gets a shard-K-of-N/ folder.
    /// Default: results/sweep-NAME-X-Y…/ (one key per axis).
    #[arg(long, value_name = "FILE|DIR")]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

/// Raised by Ctrl-C or SIGTERM (or SIGHUP) during `optimize`.
static STOP: AtomicBool = AtomicBool::new(false);
static HANDLER: Once = Once::new();

/// Install the Ctrl-C handler (once; ctrlc's `termination` feature makes it catch SIGTERM and
/// SIGHUP too): the first signal asks the search to stop after the current iteration and still
/// write its results, then exit 130; a second one quits at once, writing nothing.
fn install_ctrl_c() {
    HANDLER.call_once(|| {
        let _ = ctrlc::set_handler(|| {
            if STOP.swap(true, Ordering::SeqCst) {
                eprintln!("\nfacetlab: interrupted again, quitting without writing");
                std::process::exit(130);
            }
            eprintln!("\nfacetlab: stopping after the current iteration and writing what was found (Ctrl-C again to quit at once)");
        });
    });
}

struct Bar(ProgressBar);

impl Progress for Bar {
    fn update(&self, s: &Status) {
        self.0.set_position(s.evaluations.min(s.budget));
        if s.best_cost.is_finite() {
            self.0.set_message(format!(
                "iteration {}  best {:.4}",
                s.iterations, s.best_cost
            ));
        }
    }
}

/// The writers of the best cut besides `best.toml`: GemCad, OBJ and the SVG diagram.
fn cut_writers() -> Vec<&'static dyn CutWriter> {
    static ASC: FnWriter = FnWriter::new("asc", |c| Ok(facetlab::io::asc::write(c, 0)));
    static OBJ: FnWriter = FnWriter::new("obj", |c| Ok(facetlab::io::mesh::write_obj(c)));
    static SVG: FnWriter = FnWriter::new("svg", |c| Ok(facetlab::io::svg::diagram(c)));
    vec![&ASC, &OBJ, &SVG]
}

/// The objective's scorer and the winners' verifier for a loaded config.
pub type Scorers = (Box<dyn Evaluator>, Option<Box<dyn Verifier>>);

/// The real scorers: the beam tracer and the photon tracer, both with the config's `[score]`
/// settings. They can only be made from a loaded config, so no command scores with defaults.
pub fn real_scorers(config: &Config) -> Scorers {
    (
        Box::new(BeamEvaluator::new(config)),
        Some(Box::new(PhotonVerifier::new(config))),
    )
}

/// The files a run folder may hold (see `write_folder` in src/optimize/run.rs).
const RUN_FILES: [&str; 10] = [
    "config.toml",
    "history.csv",
    "convergence.png",
    "convergence.svg",
    "best.toml",
    "best.asc",
    "best.obj",
    "best.svg",
    "report.json",
    "report.md",
];

/// The exit status of a finished `optimize`: 130 when a signal stopped it (its folder is
/// written all the same), else 0.
pub fn optimize_exit(interrupted: bool) -> Exit {
    if interrupted {
        Exit::Interrupted
    } else {
        Exit::Ok
    }
}

/// Refuse an `--out` folder that holds the config read, or any folder that is not empty
/// unless `force`; check that it can be written (without making it).
fn check_run_folder(out: &Path, config: &Path, force: bool) -> Result<()> {
    let mut outputs = vec![("--out", out.to_path_buf())];
    outputs.extend(RUN_FILES.iter().map(|f| ("--out", out.join(f))));
    refuse_overwrite(&outputs, &[config.to_path_buf()])?;
    if out.is_dir() && !force {
        let busy = std::fs::read_dir(out)
            .map_err(|e| Error::io(out.display().to_string(), e))?
            .next()
            .is_some();
        if busy {
            return Err(Error::invalid(
                "--out",
                format!(
                    "folder {} is not empty; choose a new folder, or pass --force to write into it",
                    out.display()
                ),
            ));
        }
    }
    if out.exists() && !out.is_dir() {
        return Err(Error::invalid(
            "--out",
            format!("{} exists and is not a folder", out.display()),
        ));
    }
    facetlab::io::check_writable(out)
}

/// `facetlab optimize`: load the config, then make its scorers with `make`. Exits 130 when
/// Ctrl-C or SIGTERM stopped the search (after writing the folder).
pub fn run_optimize(a: &OptimizeArgs, make: &dyn Fn(&Config) -> Scorers) -> Result<Exit> {
    if let Some(out) = &a.out {
        check_run_folder(out, &a.config, a.force)?;
    }
    let mut config = Config::load(&a.config)?;
    if let Some(s) = a.seed {
        config.seed = s;
    }
    let (evaluator, verifier) = make(&config);
    let evaluator = evaluator.as_ref();
    // Fail on a bad start cut before spending any time.
    config.start_cut()?;
    // Lower the flag before the handler exists: a signal that arrives right after the
    // handler is installed must not be forgotten.
    STOP.store(false, Ordering::SeqCst);
    install_ctrl_c();
    let pb = bar(
        config.budget.max_evaluations,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} evals  {msg}",
    );
    let progress = Bar(pb.clone());
    let opts = RunOptions {
        out: a.out.clone(),
        writers: cut_writers(),
        convergence: Some(facetlab::plot::optimize::convergence),
        hooks: Hooks {
            stop: Some(&STOP),
            progress: Some(&progress),
        },
        html_report: true,
        ..RunOptions::default()
    };
    let verifier = if a.no_verify {
        None
    } else {
        verifier.as_deref()
    };
    if config.pareto.is_some() {
        let dir = a
            .out
            .clone()
            .unwrap_or_else(|| opt::new_run_dir(&opts.results_root, &config.name));
        facetlab::io::check_writable(&dir)?;
        let front = opt::run_pareto(
            &config,
            evaluator,
            verifier,
            &dir,
            Some(facetlab::plot::pareto::pareto),
            &opts.hooks,
        );
        pb.finish_and_clear();
        let front = front?;
        println!("wrote {}/", dir.display());
        println!(
            "trade-off {}: {} searches, {} evaluations in {:.1} s; {} non-dominated cuts",
            front.scores.join(" / "),
            front.searches,
            front.evaluations,
            front.seconds,
            front.front.len()
        );
        for p in front.front.iter().filter(|p| !p.roles.is_empty()) {
            let scores: Vec<String> = front
                .scores
                .iter()
                .filter_map(|k| p.scores.get(k).map(|v| format!("{k} {v:.4}")))
                .collect();
            let check = match &p.verification {
                Some(v) if v.disagreements.is_empty() && v.error.is_none() => {
                    "; photon tracer agrees".to_string()
                }
                Some(v) => format!("; photon tracer DISAGREES: {}", v.disagreements.join(", ")),
                None => String::new(),
            };
            println!("  {}: {}{check}", p.roles.join(", "), scores.join(", "));
        }
        return Ok(optimize_exit(STOP.load(Ordering::SeqCst)));
    }
    let result = opt::run(&config, evaluator, verifier, &opts);
    pb.finish_and_clear();
    let s = result?;
    let exit = optimize_exit(STOP.load(Ordering::SeqCst));
    let o = &s.outcome;
    let r = &s.report;
    println!("wrote {}/", s.dir.display());
    let best = o.best();
    let scores = best
        .scores
        .as_ref()
        .map(|m| {
            best.score_order
                .iter()
                .filter_map(|k| m.get(k).map(|v| format!("{k} {v:.4}")))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .unwrap_or_default();
    println!(
        "best: cost {:.4} (start {:.4}); {scores}",
        best.cost, o.start.cost
    );
    let free: Vec<String> = best
        .free
        .iter()
        .map(|(k, v)| format!("{k} = {v:.4}"))
        .collect();
    println!("      {}", free.join(", "));
    if let Some(g) = &best.grade {
        let limit = if g.limiting.is_empty() {
            String::new()
        } else {
            format!(", limited by {}", g.limiting.join(", "))
        };
        println!(
            "      grade estimate {}{limit} (published proportion ranges; not a laboratory grade)",
            g.estimate.name()
        );
    }
    for b in &best.at_bounds {
        println!(
            "      {} = {:.4} is at its {} bound {}: the optimum may lie beyond the range searched",
            b.key, b.value, b.side, b.bound
        );
    }
    println!(
        "search: {} evaluations in {:.1} s ({:.1}/s); {}",
        r.search.evaluations,
        r.search.seconds,
        r.search.evaluations_per_second,
        r.search.stop.text()
    );
    if o.verified {
        let flagged: Vec<String> = std::iter::once(&o.start)
            .chain(&o.winners)
            .filter_map(|c| {
                let v = c.verification.as_ref()?;
                (!v.disagreements.is_empty())
                    .then(|| format!("{} ({})", c.label, v.disagreements.join(", ")))
            })
            .collect();
        println!(
            "verification: {:.1} s; {}",
            o.verify_seconds,
            if flagged.is_empty() {
                format!(
                    "photon and beam tracer agree within {} standard errors",
                    config.verify.sigma
                )
            } else {
                format!(
                    "DISAGREEMENT beyond {} standard errors: {}",
                    config.verify.sigma,
                    flagged.join("; ")
                )
            }
        );
    } else if let Some(n) = &o.verify_note {
        println!("verification: {n}");
    }
    if exit == Exit::Interrupted {
        eprintln!("facetlab: interrupted; wrote what was found (exit code 130)");
    }
    Ok(exit)
}

/// `facetlab sweep`: load the config, then make its scorer with `make`. One axis is a profile,
/// two or more a grid mapped over two of them; with `--shard K/N` (or a job array's
/// environment) only that share of the grid is evaluated, resumably, into a shard folder.
pub fn run_sweep(a: &SweepArgs, make: &dyn Fn(&Config) -> Scorers) -> Result<Exit> {
    run_sweep_env(a, make, &|k| std::env::var(k).ok())
}

/// The axes of a sweep from `--x`, `--y` and `--axis`, in that order.
fn sweep_axes(a: &SweepArgs, config: &Config) -> Result<Vec<Axis>> {
    if a.x.is_none() && a.y.is_some() {
        return Err(Error::invalid("--y", "needs --x (the first axis)"));
    }
    let mut axes = Vec::new();
    if let Some(x) = &a.x {
        axes.push(Axis::parse("--x", x, config)?);
    }
    if let Some(y) = &a.y {
        let y = Axis::parse("--y", y, config)?;
        if axes[0].key == y.key {
            return Err(Error::invalid(
                "--y",
                format!(
                    "sweeps `{}` on both axes; give two different parameters",
                    y.key
                ),
            ));
        }
        axes.push(y);
    }
    for s in &a.axis {
        axes.push(Axis::parse("--axis", s, config)?);
    }
    Ok(axes)
}

/// What a map shows: the mapped axes (one: a profile; two: a heatmap) and where the others
/// are held (value indices).
pub(crate) struct MapSpec {
    pub axes: Vec<usize>,
    pub fixed: Vec<usize>,
}

/// Names for a sweep's titles: the config's name, the family, the config's file name.
pub(crate) struct Names {
    pub name: String,
    pub family: String,
    pub file: String,
}

/// The map's title (the same words as ever for 1 and 2 axes; held axes are named).
fn map_title(names: &Names, grid: &Grid, score: &SweepScore, spec: &MapSpec) -> String {
    let held: Vec<String> = (0..grid.axes.len())
        .filter(|i| !spec.axes.contains(i))
        .map(|i| {
            format!(
                "{} = {}",
                grid.axes[i].key, grid.axes[i].values[spec.fixed[i]]
            )
        })
        .collect();
    let held = if held.is_empty() {
        String::new()
    } else {
        format!(" at {}", held.join(", "))
    };
    let key = |i: usize| &grid.axes[spec.axes[i]].key;
    if spec.axes.len() == 1 {
        format!(
            "{}: scores of {} along {}{held} (others as in {})",
            names.name,
            names.family,
            key(0),
            names.file
        )
    } else {
        format!(
            "{} of {} over {} and {}{held} (others as in {})",
            score.name(),
            names.family,
            key(0),
            key(1),
            names.file
        )
    }
}

/// Write a whole sweep's CSV and its map where `out` says, and print what was written and the
/// highest `score`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_sweep_outputs(
    grid: &Grid,
    cells: &[GridCell],
    labels: &[String],
    score: &SweepScore,
    spec: &MapSpec,
    names: &Names,
    path: Option<Vec<(f64, f64)>>,
    out: &Path,
) -> Result<()> {
    let (csv, png, svg) = opt::sweep_output_paths(out);
    if let Some(d) = csv.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| Error::io(d.display().to_string(), e))?;
    }
    facetlab::io::write_atomic(&csv, opt::grid_csv(grid, cells).as_bytes())?;
    let title = map_title(names, grid, score, spec);
    if let [ax] = spec.axes[..] {
        let lines = opt::profile_lines(grid, cells, labels, ax, &spec.fixed, title);
        facetlab::plot::optimize::profile(&lines, &png, &svg)?;
    } else {
        let map = opt::grid_heatmap(
            grid,
            cells,
            labels,
            score,
            (spec.axes[0], spec.axes[1]),
            &spec.fixed,
            title,
            path,
        );
        facetlab::plot::optimize::heatmap(&map, &png, &svg)?;
    }
    println!(
        "wrote {}, {}, {}",
        csv.display(),
        png.display(),
        svg.display()
    );
    if let Some((c, v)) = opt::grid_best(cells, score) {
        let at: Vec<String> = grid
            .axes
            .iter()
            .zip(&c.values)
            .map(|(a, v)| format!("{} = {v}", a.key))
            .collect();
        println!("highest {}: {v:.4} at {}", score.name(), at.join(", "));
    }
    Ok(())
}

/// The map of `--map`/`--at` for `grid`.
pub(crate) fn map_spec(grid: &Grid, map: Option<&str>, at: &[String]) -> Result<MapSpec> {
    let axes = opt::map_axes(grid, map)?;
    let fixed = opt::fixed_at(grid, &opt::parse_at(at)?)?;
    Ok(MapSpec { axes, fixed })
}

/// The shard of `--shard` (`off`: none, whatever the environment), else of a job array's
/// environment (`env` reads a variable).
pub(crate) fn choose_shard(
    flag: Option<&str>,
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<Option<(Shard, String)>> {
    match flag {
        Some("off") => Ok(None),
        Some(s) => Ok(Some((Shard::parse("--shard", s)?, "--shard".into()))),
        None => Shard::from_env(env),
    }
}

/// [`run_sweep`] with the environment read through `env`.
pub fn run_sweep_env(
    a: &SweepArgs,
    make: &dyn Fn(&Config) -> Scorers,
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<Exit> {
    let config = Config::load(&a.config)?;
    let grid = Grid::new(sweep_axes(a, &config)?)?;
    let score = SweepScore::parse(&a.score)?;
    let spec = map_spec(&grid, a.map.as_deref(), &a.at)?;
    if spec.axes.len() < 2 && a.run.is_some() {
        return Err(Error::invalid(
            "--run",
            "draws an optimizer's path on a 2-D map; give --y too",
        ));
    }
    let shard = choose_shard(a.shard.as_deref(), env)?;
    let keys: Vec<&str> = grid.axes.iter().map(|x| x.key.as_str()).collect();
    let default_out =
        || PathBuf::from("results").join(format!("sweep-{}-{}", config.name, keys.join("-")));
    let names = Names {
        name: config.name.clone(),
        family: config.family.name.to_string(),
        file: a
            .config
            .file_name()
            .map(|f| f.to_string_lossy().to_string())
            .unwrap_or_default(),
    };
    if let Some((shard, from)) = shard {
        if a.run.is_some() {
            return Err(Error::invalid(
                "--run",
                "a shard draws no map; give --run to `facetlab merge`",
            ));
        }
        let out = a.out.clone().unwrap_or_else(default_out);
        return run_shard(a, &config, &grid, shard, &from, &out, make);
    }
    let out = a.out.clone().unwrap_or_else(default_out);
    let (csv, png, svg) = opt::sweep_output_paths(&out);
    let mut inputs = vec![a.config.clone()];
    if let Some(r) = &a.run {
        inputs.extend([r.clone(), r.join("history.csv"), r.join("config.toml")]);
    }
    refuse_overwrite(
        &[
            ("--out", out.clone()),
            ("--out", csv.clone()),
            ("--out", png.clone()),
            ("--out", svg.clone()),
        ],
        &inputs,
    )?;
    let path = match &a.run {
        Some(dir) => {
            if !dir.is_dir() {
                return Err(Error::invalid(
                    "--run",
                    format!(
                        "{} is not a folder; give a run folder of `facetlab optimize`",
                        dir.display()
                    ),
                ));
            }
            let (mx, my) = (&grid.axes[spec.axes[0]].key, &grid.axes[spec.axes[1]].key);
            Some(opt::sweep_path(dir, mx, my)?)
        }
        None => None,
    };
    if let Some(d) = csv.parent() {
        facetlab::io::check_writable(d)?;
    }
    let (evaluator, _) = make(&config);
    let pb = bar(
        grid.len() as u64,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} cuts  {per_sec}  eta {eta}",
    );
    let all: Vec<usize> = (0..grid.len()).collect();
    let cells = opt::evaluate_grid(&config, evaluator.as_ref(), &grid, &all, None, &|_| {
        pb.inc(1)
    });
    pb.finish_and_clear();
    let labels: Vec<String> = grid.axes.iter().map(|x| x.label()).collect();
    write_sweep_outputs(&grid, &cells, &labels, &score, &spec, &names, path, &out)?;
    Ok(Exit::Ok)
}

/// The name of shard `s`'s folder inside a sweep's `--out` folder.
pub fn shard_folder(s: Shard) -> String {
    format!("shard-{}-of-{}", s.k, s.n)
}

/// Evaluate one shard into `out/shard-K-of-N/`, resuming from its `rows.csv`.
fn run_shard(
    a: &SweepArgs,
    config: &Config,
    grid: &Grid,
    shard: Shard,
    from: &str,
    out: &Path,
    make: &dyn Fn(&Config) -> Scorers,
) -> Result<Exit> {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if matches!(ext.as_deref(), Some("csv" | "png" | "svg")) {
        return Err(Error::invalid(
            "--out",
            format!(
                "{} is a file name; a sharded sweep writes a folder (its shard in OUT/{})",
                out.display(),
                shard_folder(shard)
            ),
        ));
    }
    let dir = out.join(shard_folder(shard));
    let (record_path, rows_path) = (dir.join("shard.json"), dir.join("rows.csv"));
    refuse_overwrite(
        &[
            ("--out", dir.clone()),
            ("--out", record_path.clone()),
            ("--out", rows_path.clone()),
        ],
        std::slice::from_ref(&a.config),
    )?;
    facetlab::io::check_writable(&dir)?;
    let config_bytes = facetlab::io::read_bytes(&a.config)?;
    let mine = shard.indices(grid.len());
    let mut record = ShardRecord {
        format: 1,
        config: a.config.display().to_string(),
        name: config.name.clone(),
        family: config.family.name.to_string(),
        config_hash: opt::config_hash(&config_bytes),
        axes: grid
            .axes
            .iter()
            .map(|x| AxisRecord {
                key: x.key.clone(),
                label: x.label(),
                values: x.values.clone(),
            })
            .collect(),
        grid_size: grid.len(),
        n: shard.n,
        k: shard.k,
        rule: format!("index mod {} == {}", shard.n, shard.k - 1),
        points: mine.len(),
        done: 0,
        complete: false,
        resumed: 0,
        computed: 0,
        indices_done: Vec::new(),
    };
    let shown = dir.display();
    // What an earlier run of this shard left: it must be the same sweep and shard.
    let mut done = std::collections::BTreeSet::new();
    if record_path.exists() {
        let old: ShardRecord = serde_json::from_slice(&facetlab::io::read_bytes(&record_path)?)
            .map_err(|e| Error::invalid("--out", format!("{}: {e}", record_path.display())))?;
        if !old.same_sweep(&record) || old.k != record.k {
            return Err(Error::invalid(
                "--out",
                format!("{shown} holds shard {}/{} of another sweep (config hash {}, axes or shard count differ); choose another folder", old.k, old.n, old.config_hash),
            ));
        }
        if rows_path.exists() {
            let text = String::from_utf8_lossy(&facetlab::io::read_bytes(&rows_path)?).to_string();
            let (cells, good) = opt::read_rows(&text, grid)
                .map_err(|e| Error::invalid("--out", format!("{}: {e}", rows_path.display())))?;
            for c in cells {
                if !shard.owns(c.index) || !done.insert(c.index) {
                    return Err(Error::invalid(
                        "--out",
                        format!(
                            "{}: grid point {} is not shard {}/{}'s or is there twice",
                            rows_path.display(),
                            c.index,
                            shard.k,
                            shard.n
                        ),
                    ));
                }
            }
            if good < text.len() {
                // A line cut short by an interruption: drop it before appending.
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(&rows_path)
                    .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
                f.set_len(good as u64)
                    .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
            }
        }
    } else if rows_path.exists() {
        return Err(Error::invalid(
            "--out",
            format!(
                "{} exists without shard.json; choose another folder",
                rows_path.display()
            ),
        ));
    }
    std::fs::create_dir_all(&dir).map_err(|e| Error::io(shown.to_string(), e))?;
    record.resumed = done.len();
    record.done = done.len();
    record.indices_done = done.iter().copied().collect();
    record.complete = record.done == record.points;
    let write_record = |r: &ShardRecord| -> Result<()> {
        let text =
            serde_json::to_string_pretty(r).map_err(|e| Error::invalid("--out", e.to_string()))?;
        facetlab::io::write_atomic(&record_path, (text + "\n").as_bytes())
    };
    write_record(&record)?;
    println!(
        "shard {}/{} (from {from}): {} of {} grid points ({}); resumed: {} of {} done",
        shard.k,
        shard.n,
        mine.len(),
        grid.len(),
        record.rule,
        record.resumed,
        record.points
    );
    let todo: Vec<usize> = mine.into_iter().filter(|i| !done.contains(i)).collect();
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&rows_path)
        .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
    if file
        .metadata()
        .map_err(|e| Error::io(rows_path.display().to_string(), e))?
        .len()
        == 0
    {
        use std::io::Write;
        file.write_all(opt::rows_header(grid).as_bytes())
            .map_err(|e| Error::io(rows_path.display().to_string(), e))?;
    }
    let file = std::sync::Mutex::new(file);
    let failed: std::sync::Mutex<Option<String>> = std::sync::Mutex::new(None);
    let (evaluator, _) = make(config);
    STOP.store(false, Ordering::SeqCst);
    install_ctrl_c();
    let pb = bar(
        todo.len() as u64,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} cuts  {per_sec}  eta {eta}",
    );
    let cells = opt::evaluate_grid(config, evaluator.as_ref(), grid, &todo, Some(&STOP), &|c| {
        use std::io::Write;
        // One write per row: a row is in the file whole or (after a hard kill) cut short
        // at the end, where a resume drops it.
        let row = opt::shard_row(c);
        let mut f = file.lock().unwrap_or_else(|p| p.into_inner());
        if let Err(e) = f.write_all(row.as_bytes()) {
            *failed.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.to_string());
            STOP.store(true, Ordering::SeqCst);
        }
        pb.inc(1);
    });
    pb.finish_and_clear();
    if let Some(e) = failed.into_inner().unwrap_or_else(|p| p.into_inner()) {
        return Err(Error::io(rows_path.display().to_string(), e));
    }
    done.extend(cells.iter().map(|c| c.index));
    record.computed = cells.len();
    record.done = done.len();
    record.indices_done = done.iter().copied().collect();
    record.complete = record.done == record.points;
    write_record(&record)?;
    println!(
        "computed {}; {} of {} done; wrote {}/ (shard.json, rows.csv)",
        record.computed,
        record.done,
        record.points,
        dir.display()
    );
    if !record.complete {
        eprintln!(
            "facetlab: interrupted; {} of {} points of shard {}/{} are written; run the same command again to resume (exit code 130)",
            record.done, record.points, shard.k, shard.n
        );
        return Ok(Exit::Interrupted);
    }
    Ok(Exit::Ok)
}

#[cfg(test)]
mod tests {
    use super::*;
    use facetlab::cut::Cut;
    use facetlab::optimize::ScoreSet;

    fn bump(cut: &Cut) -> Result<ScoreSet> {
        let (c, p) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
        Ok(ScoreSet::new(
            (-((c - 34.5) / 3.0).powi(2) - (p - 40.8).powi(2)).exp(),
            0.0,
            0.0,
        ))
    }

    fn bumps(_: &Config) -> Scorers {
        (Box::new(bump), None)
    }

    #[test]
    fn optimize_and_sweep_write_their_files() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("small.toml");
        std::fs::write(
            &cfg,
            "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\npavilion_angle = [39.5, 42.5]\n[method]\nstarts = 2\nmax_evaluations = 120\n",
        )
        .unwrap();
        let out = dir.path().join("run");
        let a = OptimizeArgs {
            config: cfg.clone(),
            out: Some(out.clone()),
            seed: Some(9),
            no_verify: false,
            quiet: true,
            force: false,
        };
        assert_eq!(run_optimize(&a, &bumps).unwrap(), Exit::Ok);
        assert!(out.join("report.md").is_file());
        let used = std::fs::read_to_string(out.join("config.toml")).unwrap();
        assert!(used.contains("seed = 9"));
        let s = SweepArgs {
            config: cfg.clone(),
            x: Some("crown_angle:30:38:1".into()),
            y: Some("pavilion_angle:39.5:42.5:0.5".into()),
            axis: vec![],
            map: None,
            at: vec![],
            shard: None,
            score: "objective".into(),
            run: Some(out.clone()),
            out: Some(dir.path().join("map.png")),
            quiet: true,
        };
        run_sweep(&s, &bumps).unwrap();
        assert!(dir.path().join("map.csv").is_file() && dir.path().join("map.svg").is_file());
        let bad = SweepArgs {
            run: Some(dir.path().join("nope")),
            ..s
        };
        let e = run_sweep(&bad, &bumps).unwrap_err().to_string();
        assert!(e.starts_with("--run:"), "{e}");
        let e = run_optimize(
            &OptimizeArgs {
                config: dir.path().join("missing.toml"),
                out: None,
                seed: None,
                no_verify: true,
                quiet: true,
                force: false,
            },
            &bumps,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("missing.toml: no such file"), "{e}");

        // The folder of the first run is not empty: refused, unless --force.
        let e = run_optimize(&a, &bumps).unwrap_err().to_string();
        assert!(e.starts_with("--out: ") && e.contains("--force"), "{e}");
        // A folder holding the config as `config.toml` is refused even with --force.
        let inside = OptimizeArgs {
            config: out.join("config.toml"),
            force: true,
            ..a
        };
        let before = std::fs::read_to_string(out.join("config.toml")).unwrap();
        let e = run_optimize(&inside, &bumps).unwrap_err().to_string();
        assert!(e.starts_with("--out: ") && e.contains("overwrite"), "{e}");
        assert_eq!(
            std::fs::read_to_string(out.join("config.toml")).unwrap(),
            before
        );

        // A signal during the search: the folder is still written and the exit status is 130.
        // (Here, not in a test of its own: the stop flag is one per process.)
        fn pressing(cut: &Cut) -> Result<ScoreSet> {
            static CALLS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
            if CALLS.fetch_add(1, Ordering::SeqCst) >= 10 {
                STOP.store(true, Ordering::SeqCst);
            }
            bump(cut)
        }
        let stopped = dir.path().join("stopped");
        let a = OptimizeArgs {
            out: Some(stopped.clone()),
            force: true,
            ..inside
        };
        let a = OptimizeArgs {
            config: cfg.clone(),
            ..a
        };
        fn pressings(_: &Config) -> Scorers {
            (Box::new(pressing), None)
        }
        let e = run_optimize(&a, &pressings).unwrap();
        assert_eq!(e, Exit::Interrupted);
        assert_eq!(e.code(), 130);
        assert!(stopped.join("history.csv").is_file() && stopped.join("report.md").is_file());
        assert_eq!(optimize_exit(false), Exit::Ok);
    }

    #[test]
    fn a_profile_writes_one_row_per_x_and_outputs_never_overwrite_inputs() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("small.toml");
        std::fs::write(
            &cfg,
            "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
        )
        .unwrap();
        let s = SweepArgs {
            config: cfg.clone(),
            x: Some("crown_angle:30:38:2".into()),
            y: None,
            axis: vec![],
            map: None,
            at: vec![],
            shard: None,
            score: "brilliance".into(),
            run: None,
            out: Some(dir.path().join("prof")),
            quiet: true,
        };
        assert_eq!(run_sweep(&s, &bumps).unwrap(), Exit::Ok);
        let csv = std::fs::read_to_string(dir.path().join("prof/sweep.csv")).unwrap();
        assert!(csv.starts_with("crown_angle,brilliance,fire,scintillation,objective\n30,"));
        assert_eq!(csv.lines().count(), 1 + 5);
        assert!(dir.path().join("prof/sweep.png").is_file());
        // --run needs a map.
        let e = run_sweep(
            &SweepArgs {
                run: Some(dir.path().into()),
                ..s.clone()
            },
            &bumps,
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("--run: ") && e.contains("--y"), "{e}");
        // `--out small.csv` beside `small.toml` is fine; `--out small.toml` is not.
        let e = run_sweep(
            &SweepArgs {
                out: Some(cfg.clone()),
                ..s.clone()
            },
            &bumps,
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("--out: ") && e.contains("overwrite"), "{e}");
        assert!(std::fs::read_to_string(&cfg).unwrap().starts_with("[cut]"));
    }

    #[test]
    fn three_axes_map_any_two_held_where_asked() {
        let dir = tempfile::tempdir().unwrap();
        let cfg = dir.path().join("small.toml");
        std::fs::write(
            &cfg,
            "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
        )
        .unwrap();
        let s = SweepArgs {
            config: cfg.clone(),
            x: Some("crown_angle:30:38:2".into()),
            y: Some("pavilion_angle:40:41:0.5".into()),
            axis: vec!["table:0.55:0.58:0.01".into()],
            map: Some("table,crown_angle".into()),
            at: vec!["pavilion_angle=40.9".into()],
            shard: None,
            score: "brilliance".into(),
            run: None,
            out: Some(dir.path().join("three")),
            quiet: true,
        };
        let no_env = |_: &str| None;
        assert_eq!(run_sweep_env(&s, &bumps, &no_env).unwrap(), Exit::Ok);
        let csv = std::fs::read_to_string(dir.path().join("three/sweep.csv")).unwrap();
        assert!(csv.starts_with("crown_angle,pavilion_angle,table,brilliance,"));
        assert_eq!(csv.lines().count(), 1 + 5 * 3 * 4);
        let grid = Grid::new(vec![
            Axis::parse("--x", "crown_angle:30:38:2", &Config::load(&cfg).unwrap()).unwrap(),
            Axis::parse(
                "--y",
                "pavilion_angle:40:41:0.5",
                &Config::load(&cfg).unwrap(),
            )
            .unwrap(),
            Axis::parse(
                "--axis",
                "table:0.55:0.58:0.01",
                &Config::load(&cfg).unwrap(),
            )
            .unwrap(),
        ])
        .unwrap();
        let spec = map_spec(&grid, s.map.as_deref(), &s.at).unwrap();
        assert_eq!(
            (spec.axes.clone(), spec.fixed.clone()),
            (vec![2, 0], vec![2, 2, 1]),
            "a tie at the middle (0.565) goes to the lower value"
        );
        let names = Names {
            name: "n".into(),
            family: "round-brilliant".into(),
            file: "small.toml".into(),
        };
        assert_eq!(
            map_title(&names, &grid, &SweepScore::Fire, &spec),
            "fire of round-brilliant over table and crown_angle at pavilion_angle = 41 (others as in small.toml)"
        );
        for (change, want) in [
            (
                SweepArgs {
                    map: Some("table,girdle".into()),
                    ..s.clone()
                },
                "--map: `girdle` is not an axis",
            ),
            (
                SweepArgs {
                    at: vec!["table=0.9".into()],
                    ..s.clone()
                },
                "--at: table = 0.9 is outside",
            ),
            (
                SweepArgs {
                    axis: vec!["crown_angle:30:31:1".into()],
                    ..s.clone()
                },
                "sweeps `crown_angle` on two axes",
            ),
            (
                SweepArgs {
                    x: None,
                    ..s.clone()
                },
                "--y: needs --x",
            ),
            (
                SweepArgs {
                    shard: Some("0/2".into()),
                    ..s.clone()
                },
                "--shard: `0/2` is not K/N",
            ),
        ] {
            let e = run_sweep_env(&change, &bumps, &no_env)
                .unwrap_err()
                .to_string();
            assert!(e.contains(want), "{e}");
        }
    }
}
