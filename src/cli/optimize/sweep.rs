//! `sweep`: scores over a grid of one or more parameters of an optimization config — a
//! profile along one axis, a heatmap over two, an N-axis grid mapped over two of its axes —
//! and its shards (`--shard K/N` or a job array's environment), each resumable in its own
//! folder, that `facetlab merge` joins. The Ctrl-C handler, the progress bar and the scorers
//! are the `optimize` command's (`mod.rs`).

use super::{bar, install_ctrl_c, Scorers, STOP};
use crate::cli::flags::ShardFlag;
use crate::cli::outputs::{refuse_overwrite, Exit};
use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optimize::Config;
use facetlab::sweep::{self, Axis, Grid, MapSpec, Shard, ShardRun, SweepScore, Swept};
use std::path::{Path, PathBuf};

/// Flags of `facetlab sweep`.
#[derive(Clone, Debug, Args)]
pub struct SweepArgs {
    /// Optimization config (TOML): the family, the other parameters' values, the objective.
    pub config: PathBuf,
    /// First axis: KEY:MIN:MAX:STEP, e.g. crown_angle:25:40:0.5.
    #[arg(long = "x", value_name = "KEY:MIN:MAX:STEP")]
    // A String on purpose: an axis of the config's free parameters, known once it is read.
    pub x: Option<String>,
    /// Second axis: KEY:MIN:MAX:STEP, e.g. pavilion_angle:38:43:0.1. With one axis only the
    /// sweep is a profile: a CSV and a line chart of every score.
    #[arg(long = "y", value_name = "KEY:MIN:MAX:STEP")]
    // A String on purpose: an axis of the config's free parameters, known once it is read.
    pub y: Option<String>,
    /// Further axes (repeatable), after --x and --y. The grid is their Cartesian product, the
    /// first axis varying fastest; the CSV has one column per axis.
    #[arg(long = "axis", value_name = "KEY:MIN:MAX:STEP")]
    pub axis: Vec<String>,
    /// The two axes the map shows, KEY1,KEY2 (one KEY: a profile along it). Default: the first
    /// two axes.
    #[arg(long, value_name = "KEY1,KEY2")]
    // A String on purpose: two of the grid's axes, known once the config is read.
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
    #[arg(long, value_name = "K/N|off", value_parser = crate::cli::flags::shard)]
    pub shard: Option<ShardFlag>,
    /// The score drawn on the map and summarised: brilliance, fire, scintillation,
    /// objective (the config's weighted score minus penalties), or for a coloured stone
    /// (`[score] colour` or a coloured material) colour_l, colour_c, extinction or windowing.
    /// The CSV has all of them.
    #[arg(long, default_value = "brilliance", value_parser = crate::cli::flags::sweep_score)]
    pub score: SweepScore,
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

/// Names for a sweep's titles: the config's name, the family, the config's file name.
pub(crate) struct Names {
    pub name: String,
    pub family: String,
    pub file: String,
}

/// The map's title (the same words as ever for 1 and 2 axes; held axes are named).
pub(super) fn map_title(names: &Names, grid: &Grid, score: &SweepScore, spec: &MapSpec) -> String {
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
pub(crate) fn write_sweep_outputs(
    swept: &Swept<'_>,
    score: &SweepScore,
    spec: &MapSpec,
    names: &Names,
    path: Option<Vec<(f64, f64)>>,
    out: &Path,
) -> Result<()> {
    let (grid, cells) = (swept.grid, swept.cells);
    let (csv, png, svg) = sweep::output_paths(out);
    if let Some(d) = csv.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| Error::io(d.display().to_string(), e))?;
    }
    facetlab::io::write_atomic(&csv, sweep::to_csv(grid, cells).as_bytes())?;
    let title = map_title(names, grid, score, spec);
    if let [ax] = spec.axes[..] {
        let lines = swept.profile_lines(ax, &spec.fixed, title);
        facetlab::plot::optimize::profile(&lines, &png, &svg)?;
    } else {
        let map = swept.heatmap(
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
    if let Some((c, v)) = sweep::best(cells, score) {
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

/// The shard of `--shard` (`off`: none, whatever the environment), else of a job array's
/// environment (`env` reads a variable).
pub(crate) fn choose_shard(
    flag: Option<ShardFlag>,
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<Option<(Shard, String)>> {
    match flag {
        Some(ShardFlag::Off) => Ok(None),
        Some(ShardFlag::Given(s)) => Ok(Some((s, "--shard".into()))),
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
    let score = a.score.clone();
    let spec = MapSpec::new(&grid, a.map.as_deref(), &a.at)?;
    if spec.axes.len() < 2 && a.run.is_some() {
        return Err(Error::invalid(
            "--run",
            "draws an optimizer's path on a 2-D map; give --y too",
        ));
    }
    let shard = choose_shard(a.shard, env)?;
    let keys: Vec<&str> = grid.axes.iter().map(|x| x.key.as_str()).collect();
    let default_out =
        || PathBuf::from("results").join(format!("sweep-{}-{}", config.name, keys.join("-")));
    let names = Names {
        name: config.name.clone(),
        family: config.space.name().to_string(),
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
    let (csv, png, svg) = sweep::output_paths(&out);
    let mut inputs = vec![a.config.clone()];
    inputs.extend(config.inputs());
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
            Some(sweep::run_path(dir, mx, my)?)
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
    let cells = sweep::evaluate(&config, evaluator.as_ref(), &grid, &all, None, &|_| {
        pb.inc(1)
    });
    pb.finish_and_clear();
    let labels: Vec<String> = grid.axes.iter().map(|x| x.label()).collect();
    let swept = Swept {
        grid: &grid,
        cells: &cells,
        labels: &labels,
    };
    write_sweep_outputs(&swept, &score, &spec, &names, path, &out)?;
    Ok(Exit::Ok)
}

/// Evaluate one shard into `out/shard-K-of-N/`, resuming from its `rows.csv`
/// ([`sweep::ShardRun`]).
fn run_shard(
    a: &SweepArgs,
    config: &Config,
    grid: &Grid,
    shard: Shard,
    from: &str,
    out: &Path,
    make: &dyn Fn(&Config) -> Scorers,
) -> Result<Exit> {
    if !matches!(
        out.extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .as_deref(),
        Some("csv" | "png" | "svg")
    ) {
        let outputs = ShardRun::paths(out, shard).map(|p| ("--out", p));
        refuse_overwrite(
            &outputs,
            &[vec![a.config.clone()], config.inputs()].concat(),
        )?;
    }
    let run = ShardRun::open(&a.config, config, grid, shard, out)?;
    let r = &run.record;
    println!(
        "shard {}/{} (from {from}): {} of {} grid points ({}); resumed: {} of {} done",
        shard.k, shard.n, r.points, r.grid_size, r.rule, r.resumed, r.points
    );
    let (evaluator, _) = make(config);
    install_ctrl_c();
    let pb = bar(
        run.todo().len() as u64,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} cuts  {per_sec}  eta {eta}",
    );
    let dir = run.dir.clone();
    let record = run.evaluate(config, evaluator.as_ref(), grid, &STOP, &|| pb.inc(1));
    pb.finish_and_clear();
    let record = record?;
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
