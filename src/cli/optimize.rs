//! `optimize` and `sweep`: flags, progress bars, Ctrl-C, and the summary printed at the end.
//!
//! Both take the objective's scorer as an [`Evaluator`] (and `optimize` the photon tracer as a
//! [`Verifier`]), so the command line stays thin and the scorers are wired in one place.

use clap::Args;
use facetlab::error::{Error, Result};
use facetlab::optimize::{self as opt, Axis, SweepScore};
use facetlab::optimize::{BeamEvaluator, PhotonVerifier, Progress, Status};
use facetlab::optimize::{Config, Evaluator, Verifier};
use facetlab::optimize::{CutWriter, FnWriter, Hooks, RunOptions};
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Once;

/// Flags of `facetlab optimize`.
#[derive(Debug, Args)]
pub struct OptimizeArgs {
    /// Optimization config (TOML), e.g. optim/round-brilliance.toml.
    pub config: PathBuf,
    /// Run folder to write (default: results/NAME-UTCTIME/, NAME from the config).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
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
#[derive(Debug, Args)]
pub struct SweepArgs {
    /// Optimization config (TOML): the family, the other parameters' values, the objective.
    pub config: PathBuf,
    /// x axis: KEY:MIN:MAX:STEP, e.g. crown_angle:25:40:0.5.
    #[arg(long = "x", value_name = "KEY:MIN:MAX:STEP")]
    pub x: String,
    /// y axis: KEY:MIN:MAX:STEP, e.g. pavilion_angle:38:43:0.1.
    #[arg(long = "y", value_name = "KEY:MIN:MAX:STEP")]
    pub y: String,
    /// The score drawn: brilliance, fire, scintillation, or objective (the config's weighted
    /// score minus penalties). The CSV has all of them.
    #[arg(long, default_value = "brilliance")]
    pub score: String,
    /// A run folder of `facetlab optimize`: draw its path (best point so far) on the map.
    #[arg(long, value_name = "DIR")]
    pub run: Option<PathBuf>,
    /// Output folder (sweep.csv, sweep.png, sweep.svg in it), or a file name whose stem is
    /// used for all three (map.png → map.csv, map.png, map.svg).
    /// Default: results/sweep-NAME-X-Y/.
    #[arg(long, value_name = "FILE|DIR")]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long, short = 'q')]
    pub quiet: bool,
}

/// Raised by Ctrl-C during `optimize`.
static STOP: AtomicBool = AtomicBool::new(false);
static HANDLER: Once = Once::new();

/// Install the Ctrl-C handler (once): the first Ctrl-C asks the search to stop after the
/// current iteration and still write its results; a second one quits at once.
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

fn bar(len: u64, quiet: bool, template: &str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(len);
    if let Ok(style) = ProgressStyle::with_template(template) {
        pb.set_style(style.progress_chars("=> "));
    }
    pb
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
    static ASC: FnWriter = FnWriter::new("asc", |c| {
        Ok(facetlab::io::asc::write(c, facetlab::io::asc::DEFAULT_GEAR))
    });
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

/// `facetlab optimize`: load the config, then make its scorers with `make`.
pub fn run_optimize(a: &OptimizeArgs, make: &dyn Fn(&Config) -> Scorers) -> Result<()> {
    let mut config = Config::load(&a.config)?;
    if let Some(s) = a.seed {
        config.seed = s;
    }
    let (evaluator, verifier) = make(&config);
    let evaluator = evaluator.as_ref();
    // Fail on a bad start cut before spending any time.
    config.start_cut()?;
    install_ctrl_c();
    STOP.store(false, Ordering::SeqCst);
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
        ..RunOptions::default()
    };
    let verifier = if a.no_verify {
        None
    } else {
        verifier.as_deref()
    };
    let result = opt::run(&config, evaluator, verifier, &opts);
    pb.finish_and_clear();
    let s = result?;
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
    Ok(())
}

/// `facetlab sweep`: load the config, then make its scorer with `make`.
pub fn run_sweep(a: &SweepArgs, make: &dyn Fn(&Config) -> Scorers) -> Result<()> {
    let config = Config::load(&a.config)?;
    let (evaluator, _) = make(&config);
    let evaluator = evaluator.as_ref();
    let x = Axis::parse("--x", &a.x, &config)?;
    let y = Axis::parse("--y", &a.y, &config)?;
    let score = SweepScore::parse(&a.score)?;
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
            Some(opt::sweep_path(dir, &x.key, &y.key)?)
        }
        None => None,
    };
    let out = a.out.clone().unwrap_or_else(|| {
        PathBuf::from("results").join(format!("sweep-{}-{}-{}", config.name, x.key, y.key))
    });
    let n = (x.values.len() * y.values.len()) as u64;
    let pb = bar(
        n,
        a.quiet,
        "{spinner} {elapsed_precise} [{bar:20}] {pos}/{len} cuts  {per_sec}  eta {eta}",
    );
    let tick = || pb.inc(1);
    let result = opt::sweep(&config, evaluator, &x, &y, Some(&tick));
    pb.finish_and_clear();
    let s = result?;
    let title = format!(
        "{} of {} over {} and {} (others as in {})",
        score.name(),
        config.family.name,
        x.key,
        y.key,
        a.config
            .file_name()
            .map(|f| f.to_string_lossy())
            .unwrap_or_default()
    );
    let (csv, png, svg) = opt::write_sweep(
        &s,
        &score,
        title,
        path,
        &out,
        facetlab::plot::optimize::heatmap,
    )?;
    let z = s.grid(&score);
    let best = s
        .cells
        .iter()
        .zip(z.iter().flatten())
        .filter(|(_, v)| v.is_finite())
        .max_by(|a, b| a.1.total_cmp(b.1));
    println!(
        "wrote {}, {}, {}",
        csv.display(),
        png.display(),
        svg.display()
    );
    if let Some((c, v)) = best {
        println!(
            "highest {}: {v:.4} at {} = {}, {} = {}",
            score.name(),
            x.key,
            c.x,
            y.key,
            c.y
        );
    }
    Ok(())
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
        };
        run_optimize(&a, &bumps).unwrap();
        assert!(out.join("report.md").is_file());
        let used = std::fs::read_to_string(out.join("config.toml")).unwrap();
        assert!(used.contains("seed = 9"));
        let s = SweepArgs {
            config: cfg.clone(),
            x: "crown_angle:30:38:1".into(),
            y: "pavilion_angle:39.5:42.5:0.5".into(),
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
            },
            &bumps,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("missing.toml: no such file"), "{e}");
    }
}
