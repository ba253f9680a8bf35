//! `optimize` and `sweep`: flags, progress bars, Ctrl-C and SIGTERM, the checks of the output
//! folder before any work, and the summary printed at the end.
//!
//! Both take the objective's scorer as an [`Evaluator`] (and `optimize` the photon tracer as a
//! [`Verifier`]), so the command line stays thin and the scorers are wired in one place. This
//! file is `optimize` (a run folder, or a trade-off with `[objective] pareto`) with what both
//! share; `sweep.rs` is `sweep` and its shards.

mod sweep;

pub(crate) use sweep::{choose_shard, write_sweep_outputs, Names};
pub use sweep::{run_sweep, SweepArgs};

use super::outputs::{refuse_overwrite, Exit};
use super::progress::bar;
use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optimize as opt;
use facetlab::optimize::Config;
pub use facetlab::optimize::{real_scorers, Scorers};
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
    /// Skip the photon-tracer verification of the winners.
    #[arg(long)]
    pub no_verify: bool,
    /// No progress bar (it is also hidden when stderr is not a terminal).
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

pub(crate) use super::interrupt::STOP;

/// Install the Ctrl-C handler ([`super::interrupt::install`]; it lowers the flag first).
fn install_ctrl_c() {
    super::interrupt::install();
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
        println!("wrote {}/", dir.display());
        println!(
            "trade-off {}: {} searches, {} evaluations in {:.1} s; {} non-dominated cuts",
            facetlab::metrics::score_name::joined(&front.scores, " / "),
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

#[cfg(test)]
mod tests {
    use super::sweep::{map_title, run_sweep_env};
    use super::*;
    use facetlab::cut::Cut;
    use facetlab::optimize::ScoreSet;
    use facetlab::optimize::{Axis, Grid, SweepScore};

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
            score: SweepScore::Objective,
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
            score: SweepScore::BRILLIANCE,
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
            score: SweepScore::BRILLIANCE,
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
        let spec = facetlab::optimize::MapSpec::new(&grid, s.map.as_deref(), &s.at).unwrap();
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
            map_title(&names, &grid, &SweepScore::FIRE, &spec),
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
        ] {
            let e =
                crate::cli::flags::to_flags(run_sweep_env(&change, &bumps, &no_env).unwrap_err())
                    .to_string();
            assert!(e.contains(want), "{e}");
        }
        // A bad --shard is refused while the command line is read, in the same words.
        let e = crate::cli::flags::shard("0/2").unwrap_err().to_string();
        assert!(e.contains("--shard: `0/2` is not K/N"), "{e}");
    }
}
