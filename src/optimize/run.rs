//! A whole run: search and verify ([`search`](super::search::search)), then write the run folder.
//!
//! The run folder (`results/<name>-<UTC time>/` or `--out DIR`):
//!
//! | file | what |
//! |---|---|
//! | `config.toml` | the config as used, every default written out |
//! | `history.csv` | every evaluated point (see [`super::history`]) |
//! | `convergence.png`, `.svg` (with a [`ConvergenceChart`]) | best and current cost against evaluations |
//! | `best.toml` (+ `.asc`, `.gem`, `.obj`, `.svg` with those writers) | the best cut |
//! | `report.html` (with a [`RunPage`]) | the one-page report of the start and the winners |
//! | `report.md`, `report.json` | start and winners side by side, verification, timing |
//!
//! The optimizer draws no charts and no pages itself: the caller hands it the functions that
//! do ([`ConvergenceChart`], [`RunPage`], a [`CutWriter`] for the diagram), drawn from what
//! the search returns. Ctrl-C (the stop flag in [`Hooks`]) ends the search after the current
//! iteration; the run still scores its winners and writes every file, skips the
//! verification, and says so.

use super::config::Config;
use super::evaluator::Evaluator;
use super::history::History;
use super::search::{search, verify, Hooks, Outcome};
use super::summary::{DesignJson, FreeJson, OpenedJson, RunReport, SearchJson, VerificationJson};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::io::write_atomic;
use crate::verify::Verifier;
use std::path::{Path, PathBuf};

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

/// The GemCad `.gem` writer: binary, on the design's own gear ([`crate::io::gem::write`]).
pub struct GemWriter;

impl CutWriter for GemWriter {
    fn extension(&self) -> &str {
        "gem"
    }
    fn render(&self, cut: &Cut) -> Result<Vec<u8>> {
        crate::io::gem::write(cut, 0)
    }
}

/// Draws a run's convergence chart (best and current cost against evaluations) from its history,
/// under `title`, as the PNG `png` and the SVG `svg`. The optimizer draws no charts itself: the
/// binary connects the plot module's `convergence` here.
pub type ConvergenceChart =
    fn(history: &History, title: &str, png: &Path, svg: &Path) -> Result<()>;

/// Makes a run's `report.html` from its config and outcome: the one-page report of the start
/// and the winners (pictures, diagram, proportions with the grade estimate, scores, and the
/// photon tracer's checks when the run verified). The optimizer makes no pages itself: the
/// binary connects the report module's `run_page` here.
pub type RunPage = fn(config: &Config, outcome: &Outcome) -> Result<String>;

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
    /// Makes `report.html` ([`RunPage`]); `None` = no page (the default: it scores and draws
    /// every candidate once more).
    pub html_report: Option<RunPage>,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions {
            out: None,
            results_root: PathBuf::from("results"),
            writers: Vec::new(),
            convergence: None,
            hooks: Hooks::default(),
            html_report: None,
        }
    }
}

impl RunOptions<'_> {
    /// Every file a [`run`] may write into its folder with these options ([`run_files`]).
    pub fn files(&self) -> Vec<String> {
        run_files(
            &self.writers,
            self.convergence.is_some(),
            self.html_report.is_some(),
        )
    }
}

/// The writers of `best.*`: the TOML spec first, then `writers` but a second `.toml`.
fn best_writers<'a>(writers: &[&'a dyn CutWriter]) -> Vec<&'a dyn CutWriter> {
    let mut all: Vec<&dyn CutWriter> = vec![&TOML_WRITER];
    all.extend(writers.iter().filter(|w| w.extension() != "toml"));
    all
}

/// Every file a [`run`] may write into its folder, in the order it writes them, with
/// `writers` for the best cut, a convergence chart (`chart`) and a page (`page`):
/// `config.toml`, `history.csv`, `convergence.png` and `.svg`, `best.toml` and `best.EXT` per
/// writer (when a best cut is found), `report.html`, `report.json`, `report.md`. What a caller
/// must not let replace an input.
pub fn run_files(writers: &[&dyn CutWriter], chart: bool, page: bool) -> Vec<String> {
    let mut files = vec!["config.toml".to_string(), "history.csv".into()];
    if chart {
        files.extend(["convergence.png".into(), "convergence.svg".into()]);
    }
    files.extend(
        best_writers(writers)
            .iter()
            .map(|w| format!("best.{}", w.extension())),
    );
    if page {
        files.push("report.html".into());
    }
    files.extend(["report.json".into(), "report.md".into()]);
    files
}

/// A finished run.
pub struct RunSummary {
    /// The run folder.
    pub dir: PathBuf,
    /// What was found.
    pub outcome: Outcome,
    /// The report as written.
    pub report: RunReport,
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
pub fn report(config: &Config, o: &Outcome, files: Vec<String>) -> RunReport {
    RunReport {
        name: config.name.clone(),
        description: config.description.clone(),
        config: config.source.clone(),
        family: config.space.name().to_string(),
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
        failed: o
            .history
            .rows
            .iter()
            .filter(|r| r.cost >= 0.5 * super::problem::FAILED_COST)
            .count() as u64,
        design: design_json(config, o),
    }
}

/// The design part of a run's report (`None` for a family run): its file, meets and the meets
/// the free angles open, with their gaps in the best cut.
pub fn design_json(config: &Config, o: &Outcome) -> Option<DesignJson> {
    let d = config.design.as_ref()?;
    let gaps = o.best_cut.as_ref().map(|c| d.gaps(c));
    Some(DesignJson {
        file: config
            .cut_file
            .as_ref()
            .map_or(String::new(), |f| f.0.clone()),
        meets: d.meets().len(),
        meet_tol: d.model().meet_tol(),
        open_meets: d.open_meets().name().to_string(),
        opened: config
            .open_meets
            .iter()
            .map(|m| OpenedJson {
                meet: m.name.clone(),
                by: m.by.clone(),
                gap_at_best: gaps.as_ref().map(|g| g[m.meet]),
            })
            .collect(),
    })
}

/// The best cut as its files hold it, and a free optic axis it carries (`[free] optic_axis`,
/// riding on the cut's params), as `DEG@AZ` with the config's azimuth: the axis is the
/// stone's, not the cut's, so `best.toml` keeps only the cut's own parameters (it reads back)
/// and `best.asc` gets the note `F Optic axis: DEG@AZ` that `score` and configs read.
fn split_axis(config: &Config, cut: &Cut) -> (Cut, Option<String>) {
    let mut cut = cut.clone();
    let axis = cut.params.remove(super::config::OPTIC_AXIS).map(|tilt| {
        let mut a = config
            .score
            .material
            .uniaxial
            .as_ref()
            .map(|u| u.axis)
            .unwrap_or(crate::optics::OpticAxis {
                tilt_deg: 0.0,
                azimuth_deg: 0.0,
            });
        a.tilt_deg = tilt;
        a.label()
    });
    // The design's own optic-axis note gives way to the one found.
    if let (Some(_), Some(r)) = (&axis, cut.record.as_mut()) {
        let is_axis = |l: &String| {
            l.split_once(':').is_some_and(|(k, _)| {
                matches!(
                    k.trim().to_ascii_lowercase().as_str(),
                    "optic axis" | "optic-axis" | "c-axis"
                )
            })
        };
        r.footnotes.retain(|l| !is_axis(l));
        r.title.retain(|l| !is_axis(l));
    }
    (cut, axis)
}

/// Write the run folder for an outcome; `convergence` draws its chart and `html_report` makes
/// its page.
pub fn write_folder(
    dir: &Path,
    config: &Config,
    outcome: &Outcome,
    writers: &[&dyn CutWriter],
    convergence: Option<ConvergenceChart>,
    html_report: Option<RunPage>,
) -> Result<RunReport> {
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
    if let Some(best) = &outcome.best_cut {
        let (mut cut, axis) = split_axis(config, best);
        // A family's winner carries the GemCad record its files need (`I` the index it was
        // scored in, its symmetry, its name as the title); a design's winner has its own.
        if cut.record.is_none() {
            cut.record = Some(crate::cut::GemcadRecord::generated(
                &cut,
                0,
                config.score.material.ri_d(),
            ));
        }
        if let (Some(a), Some(r)) = (&axis, cut.record.as_mut()) {
            r.footnotes.push(format!("Optic axis: {a}"));
        }
        let cut = &cut;
        for w in best_writers(writers) {
            let name = format!("best.{}", w.extension());
            let mut bytes = w.render(cut)?;
            // A comment in the file for a person, one file for every face: it gives the
            // axis as the command line and as the config write it (kept on purpose).
            if let (Some(a), "toml") = (&axis, w.extension()) {
                bytes.extend(
                    format!(
                        "\n# The stone's optic axis found (not part of the cut): --optic-axis {a}, [score] optic_axis = \"{a}\"\n"
                    )
                    .bytes(),
                );
            }
            write_atomic(&dir.join(&name), &bytes)?;
            files.push(name);
        }
    }
    if let Some(page) = html_report {
        write_atomic(&dir.join("report.html"), page(config, outcome)?.as_bytes())?;
        files.push("report.html".into());
    }
    files.push("report.json".into());
    files.push("report.md".into());
    let rep = report(config, outcome, files);
    write_atomic(&dir.join("report.json"), rep.to_json().as_bytes())?;
    write_atomic(&dir.join("report.md"), rep.to_markdown(config).as_bytes())?;
    Ok(rep)
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
