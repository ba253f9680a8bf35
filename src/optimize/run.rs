//! A whole run: search, pick distinct winners, verify them, and write the run folder.
//!
//! The run folder (`results/<name>-<UTC time>/` or `--out DIR`):
//!
//! | file | what |
//! |---|---|
//! | `config.toml` | the config as used, every default written out |
//! | `history.csv` | every evaluated point (see [`super::history`]) |
//! | `convergence.png`, `.svg` (with a [`ConvergenceChart`]) | best and current cost against evaluations |
//! | `best.toml` (+ `.asc`, `.obj`, `.svg` with those writers) | the best cut |
//! | `report.md`, `report.json` | start and winners side by side, verification, timing |
//!
//! Ctrl-C (the stop flag in [`Hooks`]) ends the search after the current iteration; the run
//! still scores its winners and writes every file, skips the verification, and says so.

use super::config::{Config, Method};
use super::guard::{Progress, Stop, Tracker};
use super::history::History;
use super::problem::{Objective, FAILED_COST};
use super::report::{Candidate, FoundAt, FreeJson, Report, SearchJson, VerificationJson};
use super::verify::{Verification, Verifier};
use super::{nelder_mead, pso, Evaluator};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::io::write_atomic;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// Optional connections to the outside: a stop flag (raised by Ctrl-C) and a progress display.
#[derive(Clone, Copy, Default)]
pub struct Hooks<'a> {
    /// When raised, the search stops after the current iteration.
    pub stop: Option<&'a AtomicBool>,
    /// Receives progress snapshots.
    pub progress: Option<&'a dyn Progress>,
}

impl Hooks<'_> {
    fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::SeqCst))
    }
}

/// What a search found.
pub struct Outcome {
    /// Every evaluated point.
    pub history: History,
    /// Why the search stopped.
    pub stop: Stop,
    /// Nelder–Mead: why each start stopped.
    pub start_stops: Vec<Stop>,
    /// Iterations (summed over starts).
    pub iterations: u64,
    /// Evaluations.
    pub evaluations: u64,
    /// Seconds of the search.
    pub seconds: f64,
    /// The start cut.
    pub start: Candidate,
    /// Distinct winners, best first (at least one, unless every cut failed).
    pub winners: Vec<Candidate>,
    /// The best cut.
    pub best_cut: Option<Cut>,
    /// Seconds of the verification.
    pub verify_seconds: f64,
    /// Why verification was skipped or cut short.
    pub verify_note: Option<String>,
    /// Whether a verifier ran.
    pub verified: bool,
}

impl Outcome {
    /// The best candidate (the start if every cut failed).
    pub fn best(&self) -> &Candidate {
        self.winners.first().unwrap_or(&self.start)
    }
}

/// Pick up to `n` distinct winners from the history: lowest cost first, each at least
/// `min_distance` (in the unit box of the free parameters) from those already picked. Failed
/// cuts are never winners. Returns row indices.
pub fn pick_winners(config: &Config, history: &History, n: usize, min_distance: f64) -> Vec<usize> {
    let mut order: Vec<usize> = (0..history.rows.len())
        .filter(|&i| history.rows[i].cost < 0.5 * FAILED_COST)
        .collect();
    order.sort_by(|&a, &b| {
        history.rows[a]
            .cost
            .total_cmp(&history.rows[b].cost)
            .then(a.cmp(&b))
    });
    let unit = |x: &[f64]| -> Vec<f64> {
        config
            .free
            .iter()
            .zip(x)
            .map(|(f, v)| f.unit_of(*v))
            .collect()
    };
    let mut picked: Vec<(usize, Vec<f64>)> = Vec::new();
    for i in order {
        if picked.len() >= n {
            break;
        }
        let u = unit(&history.rows[i].x);
        let far = picked.iter().all(|(_, p)| {
            let d2: f64 = p.iter().zip(&u).map(|(a, b)| (a - b) * (a - b)).sum();
            d2.sqrt() >= min_distance && d2 > 0.0
        });
        if far {
            picked.push((i, u));
        }
    }
    picked.into_iter().map(|(i, _)| i).collect()
}

/// Search: run the configured method and score the start and the winners. No files.
pub fn search(config: &Config, evaluator: &dyn Evaluator, hooks: &Hooks<'_>) -> Result<Outcome> {
    let objective = Objective::new(config, evaluator);
    let never = AtomicBool::new(false);
    let stop_flag = hooks.stop.unwrap_or(&never);
    let tracker = Tracker::new(hooks.progress, config.budget.max_evaluations);
    let t = Instant::now();
    let (history, stop, start_stops, iterations) = match &config.method {
        Method::NelderMead(nm) => {
            let (h, runs) =
                nelder_mead::search(&objective, nm, &config.budget, stop_flag, &tracker)?;
            let stops: Vec<Stop> = runs.iter().map(|r| r.stop).collect();
            let stop = if stops.contains(&Stop::Interrupted) {
                Stop::Interrupted
            } else {
                // The most common reason, ties to the first in this order.
                let mut best = (Stop::Converged, 0);
                for s in [Stop::MaxEvaluations, Stop::MaxIterations, Stop::Converged] {
                    let n = stops.iter().filter(|x| **x == s).count();
                    if n > best.1 {
                        best = (s, n);
                    }
                }
                best.0
            };
            let iters = runs.iter().map(|r| r.iterations).sum();
            (h, stop, stops, iters)
        }
        Method::ParticleSwarm(s) => {
            let (h, run) = pso::search(
                &objective,
                s,
                &config.budget,
                config.seed,
                stop_flag,
                &tracker,
            )?;
            (h, run.stop, Vec::new(), run.iterations)
        }
    };
    let seconds = t.elapsed().as_secs_f64();
    let evaluations = history.rows.len() as u64;

    let start_eval = objective.evaluate_full(&config.start_x());
    let start = Candidate::new("start", config, &start_eval, None);
    let picks = pick_winners(
        config,
        &history,
        config.verify.winners.max(1),
        config.verify.min_distance,
    );
    let mut winners = Vec::new();
    let mut best_cut = None;
    for (k, &i) in picks.iter().enumerate() {
        let r = &history.rows[i];
        let e = objective.evaluate_full(&r.x);
        if k == 0 {
            best_cut = e.cut.clone();
        }
        winners.push(Candidate::new(
            &format!("winner {}", k + 1),
            config,
            &e,
            Some(FoundAt {
                track: r.track,
                iteration: r.iteration,
                evaluations: r.evaluations,
            }),
        ));
    }
    if let Some(c) = best_cut.as_mut() {
        c.name = format!("{} best", config.name);
    }
    Ok(Outcome {
        history,
        stop,
        start_stops,
        iterations,
        evaluations,
        seconds,
        start,
        winners,
        best_cut,
        verify_seconds: 0.0,
        verify_note: None,
        verified: false,
    })
}

/// Verify the start and the first `config.verify.winners` winners with the photon tracer.
/// Skipped after Ctrl-C; a failing verifier is noted per cut, never fatal.
pub fn verify(outcome: &mut Outcome, config: &Config, verifier: &dyn Verifier, hooks: &Hooks<'_>) {
    let v = &config.verify;
    if v.winners == 0 {
        outcome.verify_note = Some("verify.winners = 0".into());
        return;
    }
    if outcome.stop == Stop::Interrupted || hooks.stopped() {
        outcome.verify_note = Some("skipped: the run was interrupted".into());
        return;
    }
    outcome.verified = true;
    let t = Instant::now();
    let n = v.winners.min(outcome.winners.len());
    let cands = std::iter::once(&mut outcome.start).chain(outcome.winners.iter_mut().take(n));
    for c in cands {
        if hooks.stopped() {
            outcome.verify_note = Some("cut short: interrupted".into());
            break;
        }
        let cut = match Cut::from_family(&c.label, config.family.name, &c.params) {
            Ok(cut) => cut,
            Err(e) => {
                c.error.get_or_insert(e.to_string());
                continue;
            }
        };
        c.verification = Some(Verification::run(
            verifier,
            &cut,
            v.photons,
            config.seed,
            v.sigma,
        ));
    }
    outcome.verify_seconds = t.elapsed().as_secs_f64();
}

/// Writes the best cut in one format.
pub trait CutWriter {
    /// File extension without the dot (`toml`, `asc`, `obj`, `svg`).
    fn extension(&self) -> &str;
    /// The file's contents.
    fn render(&self, cut: &Cut) -> Result<Vec<u8>>;
}

/// A [`CutWriter`] from a function, e.g. `FnWriter::new("asc", |c| Ok(asc::write(c, 96)))`.
pub struct FnWriter {
    ext: &'static str,
    f: fn(&Cut) -> Result<String>,
}

impl FnWriter {
    /// Wrap `f` for extension `ext`.
    pub const fn new(ext: &'static str, f: fn(&Cut) -> Result<String>) -> FnWriter {
        FnWriter { ext, f }
    }
}

impl CutWriter for FnWriter {
    fn extension(&self) -> &str {
        self.ext
    }
    fn render(&self, cut: &Cut) -> Result<Vec<u8>> {
        (self.f)(cut).map(String::into_bytes)
    }
}

fn toml_spec(cut: &Cut) -> Result<String> {
    Ok(crate::io::spec::write(cut))
}

/// The TOML spec writer (always available).
pub const TOML_WRITER: FnWriter = FnWriter::new("toml", toml_spec);

/// Draws a run's convergence chart (best and current cost against evaluations) from its history,
/// under `title`, as the PNG `png` and the SVG `svg`. The optimizer draws no charts itself: the
/// binary connects the plot module's `convergence` here.
pub type ConvergenceChart =
    fn(history: &History, title: &str, png: &Path, svg: &Path) -> Result<()>;

/// Everything a run folder needs besides the config and the evaluator.
pub struct RunOptions<'a> {
    /// The folder to write; `None` = a new `<results_root>/<name>-<UTC time>/`.
    pub out: Option<PathBuf>,
    /// Where new run folders go (default `results`).
    pub results_root: PathBuf,
    /// Writers of the best cut; `best.toml` is always written.
    pub writers: Vec<&'a dyn CutWriter>,
    /// Draws `convergence.png` and `.svg`; `None` = no chart.
    pub convergence: Option<ConvergenceChart>,
    /// Stop flag and progress.
    pub hooks: Hooks<'a>,
    /// Write `report.html`: the one-page report of the start and the winners
    /// ([`crate::report`]: pictures, diagram, proportions with the grade estimate, scores).
    /// Default off (it scores and draws every candidate once more).
    pub html_report: bool,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions {
            out: None,
            results_root: PathBuf::from("results"),
            writers: Vec::new(),
            convergence: None,
            hooks: Hooks::default(),
            html_report: false,
        }
    }
}

/// A finished run.
pub struct RunSummary {
    /// The run folder.
    pub dir: PathBuf,
    /// What was found.
    pub outcome: Outcome,
    /// The report as written.
    pub report: Report,
}

/// `YYYYmmdd-HHMMSS` in UTC for a Unix time.
pub fn utc_stamp(unix: u64) -> String {
    let days = (unix / 86_400) as i64;
    let secs = unix % 86_400;
    // Howard Hinnant's civil_from_days.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}{m:02}{d:02}-{:02}{:02}{:02}",
        secs / 3600,
        (secs / 60) % 60,
        secs % 60
    )
}

/// A new folder name under `root` that does not exist yet: `<name>-<UTC time>[-k]`.
pub fn new_run_dir(root: &Path, name: &str) -> PathBuf {
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let base = format!("{name}-{}", utc_stamp(now));
    let mut dir = root.join(&base);
    let mut k = 2;
    while dir.exists() {
        dir = root.join(format!("{base}-{k}"));
        k += 1;
    }
    dir
}

/// Build the report of an outcome (`files` lists the folder's files).
pub fn report(config: &Config, o: &Outcome, files: Vec<String>) -> Report {
    Report {
        name: config.name.clone(),
        description: config.description.clone(),
        config: config.source.clone(),
        family: config.family.name.to_string(),
        method: config.method.name().to_string(),
        seed: config.seed,
        free: config
            .free
            .iter()
            .map(|f| FreeJson {
                key: f.key.clone(),
                min: f.lo,
                max: f.hi,
                start: f.start,
            })
            .collect(),
        objective: config.weights,
        constraints: config.constraints,
        search: SearchJson {
            evaluations: o.evaluations,
            iterations: o.iterations,
            stop: o.stop,
            start_stops: o.start_stops.clone(),
            seconds: o.seconds,
            evaluations_per_second: if o.seconds > 0.0 {
                o.evaluations as f64 / o.seconds
            } else {
                0.0
            },
            threads: rayon::current_num_threads(),
        },
        verification: VerificationJson {
            available: o.verified,
            photons: config.verify.photons,
            sigma: config.verify.sigma,
            seconds: o.verify_seconds,
            note: o.verify_note.clone(),
        },
        start: o.start.clone(),
        winners: o.winners.clone(),
        files,
    }
}

/// Write the run folder for an outcome; `convergence` draws its chart.
pub fn write_folder(
    dir: &Path,
    config: &Config,
    outcome: &Outcome,
    writers: &[&dyn CutWriter],
    convergence: Option<ConvergenceChart>,
    html_report: bool,
) -> Result<Report> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir.display().to_string(), e))?;
    let mut files = Vec::new();
    let mut put = |name: &str, bytes: &[u8]| -> Result<()> {
        write_atomic(&dir.join(name), bytes)?;
        files.push(name.to_string());
        Ok(())
    };
    put("config.toml", config.as_used_toml().as_bytes())?;
    put("history.csv", outcome.history.to_csv().as_bytes())?;
    if let Some(chart) = convergence {
        let title = format!(
            "{} — {} ({} evaluations)",
            config.name,
            config.method.name(),
            outcome.evaluations
        );
        chart(
            &outcome.history,
            &title,
            &dir.join("convergence.png"),
            &dir.join("convergence.svg"),
        )?;
        files.push("convergence.png".into());
        files.push("convergence.svg".into());
    }
    if let Some(cut) = &outcome.best_cut {
        let mut all: Vec<&dyn CutWriter> = vec![&TOML_WRITER];
        all.extend(writers.iter().filter(|w| w.extension() != "toml"));
        for w in all {
            let name = format!("best.{}", w.extension());
            let bytes = w.render(cut)?;
            write_atomic(&dir.join(&name), &bytes)?;
            files.push(name);
        }
    }
    if html_report {
        write_atomic(
            &dir.join("report.html"),
            html_page(config, outcome)?.as_bytes(),
        )?;
        files.push("report.html".into());
    }
    files.push("report.json".into());
    files.push("report.md".into());
    let rep = report(config, outcome, files);
    write_atomic(&dir.join("report.json"), rep.to_json().as_bytes())?;
    write_atomic(&dir.join("report.md"), rep.to_markdown(config).as_bytes())?;
    Ok(rep)
}

/// `report.html` of a run: the start and the winners side by side, scored with the run's
/// score settings, with the photon tracer's checks when the run verified.
fn html_page(config: &Config, outcome: &Outcome) -> Result<String> {
    let o = crate::report::ReportOptions {
        score: config.score.score_config(),
        size: 240,
        title: format!("facetlab optimize: {}", config.name),
        ..Default::default()
    };
    let mut cuts = Vec::new();
    for c in std::iter::once(&outcome.start).chain(&outcome.winners) {
        let cut = Cut::from_family(&c.label, config.family.name, &c.params)?;
        let mut r = crate::report::measure(&c.label, &cut, &o)?;
        r.checks.clear();
        if let Some(v) = &c.verification {
            r.checks = v
                .report
                .rows
                .iter()
                .filter_map(|row| {
                    let beam = row.beam?;
                    Some(crate::verify::Check {
                        name: row.name.clone(),
                        beam,
                        photon: row.value,
                        stderr: row.stderr,
                        z: if row.stderr > 0.0 {
                            (beam - row.value) / row.stderr
                        } else {
                            0.0
                        },
                    })
                })
                .collect();
        }
        cuts.push(r);
    }
    crate::report::html(&cuts, &o)
}

/// Search, verify (when a verifier is given) and write the run folder.
pub fn run(
    config: &Config,
    evaluator: &dyn Evaluator,
    verifier: Option<&dyn Verifier>,
    opts: &RunOptions<'_>,
) -> Result<RunSummary> {
    let dir = match &opts.out {
        Some(d) => d.clone(),
        None => new_run_dir(&opts.results_root, &config.name),
    };
    // Fail before the search if the folder could not be written, but make it only in
    // `write_folder`: a run killed before then leaves no empty folder behind.
    crate::io::check_writable(&dir)?;
    let mut outcome = search(config, evaluator, &opts.hooks)?;
    match verifier {
        Some(v) => verify(&mut outcome, config, v, &opts.hooks),
        None => outcome.verify_note = Some("no photon tracer connected".into()),
    }
    let report = write_folder(
        &dir,
        config,
        &outcome,
        &opts.writers,
        opts.convergence,
        opts.html_report,
    )?;
    Ok(RunSummary {
        dir,
        outcome,
        report,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_stamps() {
        assert_eq!(utc_stamp(0), "19700101-000000");
        assert_eq!(utc_stamp(951_782_400), "20000229-000000");
        assert_eq!(utc_stamp(1_700_000_000), "20231114-221320");
    }
}
