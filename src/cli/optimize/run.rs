//! `facetlab optimize`: its flags, progress bar and Ctrl-C, the output folder's checks before any
//! work, and the run (a run folder, or a trade-off with `[objective] pareto`).

use super::print::{print_front, print_run};
use crate::cli::outputs::{refuse_overwrite, Exit};
use crate::cli::progress::bar;
use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optimize as opt;
use facetlab::optimize::Config;
use facetlab::optimize::Scorers;
use facetlab::optimize::{Hooks, RunOptions};
use facetlab::optimize::{Progress, Status};
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

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
    /// Override the config's `[score] head_shadow`: the viewer's head shadow in degrees
    /// (0–60; default 15; 0 = none, the open-sky scores of earlier versions).
    #[arg(
        long,
        value_name = "DEG",
        allow_hyphen_values = true,
        value_parser = crate::cli::flags::real("--head-shadow", 0.0, 60.0, "a half-angle in degrees (0 = none)")
    )]
    pub head_shadow: Option<f64>,
    /// Skip the photon-tracer verification of the winners.
    #[arg(long)]
    pub no_verify: bool,
    /// No progress bar (it is also hidden when stderr is not a terminal).
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

pub(crate) use crate::cli::interrupt::STOP;

/// Install the Ctrl-C handler ([`crate::cli::interrupt::install`]; it lowers the flag first).
pub(super) fn install_ctrl_c() {
    crate::cli::interrupt::install();
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

/// The exit status of a finished `optimize`: 130 when a signal stopped it (its folder is
/// written all the same), else 0.
pub fn optimize_exit(interrupted: bool) -> Exit {
    if interrupted {
        Exit::Interrupted
    } else {
        Exit::Ok
    }
}

/// The options of `optimize`'s run (writers, chart, page), without its hooks.
fn run_options(config: &Config, out: Option<PathBuf>) -> RunOptions<'static> {
    RunOptions {
        out,
        writers: facetlab::plot::optimize::run_writers(config),
        convergence: Some(facetlab::plot::optimize::convergence),
        html_report: Some(facetlab::report::run_page),
        ..RunOptions::default()
    }
}

/// Refuse an `--out` folder whose files (`files`, what the run writes:
/// [`RunOptions::files`]) would replace an input (the config read, the design its `[cut] file`
/// names), with or without `force`, or any folder that is not empty unless `force`; check
/// that it can be written (without making it).
fn check_run_folder(out: &Path, files: &[String], inputs: &[PathBuf], force: bool) -> Result<()> {
    let mut outputs = vec![("--out", out.to_path_buf())];
    outputs.extend(files.iter().map(|f| ("--out", out.join(f))));
    refuse_overwrite(&outputs, inputs)?;
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
    let mut config = Config::load(&a.config)?;
    if let Some(out) = &a.out {
        let mut inputs = vec![a.config.clone()];
        inputs.extend(config.inputs());
        let files = run_options(&config, None).files();
        check_run_folder(out, &files, &inputs, a.force)?;
    }
    if let Some(s) = a.seed {
        config.seed = s;
    }
    if let Some(h) = a.head_shadow {
        config.score.head_shadow_deg = h;
    }
    let (evaluator, verifier) = make(&config);
    let evaluator = evaluator.as_ref();
    // Fail on a bad start cut before spending any time.
    config.start_cut()?;
    install_ctrl_c();
    let pb = bar(
        config.budget.max_evaluations,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} evals  {msg}",
    );
    let progress = Bar(pb.clone());
    let opts = RunOptions {
        hooks: Hooks {
            stop: Some(&STOP),
            progress: Some(&progress),
        },
        ..run_options(&config, a.out.clone())
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
        print_front(&dir, &front);
        return Ok(optimize_exit(STOP.load(Ordering::SeqCst)));
    }
    let result = opt::run(&config, evaluator, verifier, &opts);
    pb.finish_and_clear();
    let s = result?;
    let exit = optimize_exit(STOP.load(Ordering::SeqCst));
    print_run(&s, &config);
    if exit == Exit::Interrupted {
        eprintln!("facetlab: interrupted; wrote what was found (exit code 130)");
    }
    Ok(exit)
}
