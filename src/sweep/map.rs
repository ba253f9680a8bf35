//! Sweeps: a score over a grid of two family parameters (the others as in the config's start
//! cut), evaluated in parallel, written as CSV and as a heatmap with contour lines — optionally
//! with an optimizer run's path drawn on it.
//!
//! Axes are given as `KEY:MIN:MAX:STEP` (`crown_angle:25:40:0.5`); the grid holds
//! `MIN, MIN+STEP, …` up to `MAX` (inclusive within rounding). The CSV has one row per grid
//! point, x varying fastest: `<x key>,<y key>,brilliance,fire,scintillation,objective`
//! (+ any extra scores), where `objective = Σ weight · score − penalties` (higher is better;
//! the negative of the optimizer's cost) and a cut that cannot be built has `NaN` scores.
//!
//! With one axis, [`profile`] evaluates the scores along it; its CSV is
//! `<x key>,brilliance,fire,scintillation,objective` (+ extras), one row per x, and its chart
//! (a [`ProfileChart`]) draws every score against x.
//!
//! Sweeps of any number of axes, and their shards, are in `points.rs` and `shard.rs`; they
//! write the same CSV for one and two axes.

use crate::cut::Unit;
use crate::error::{shown, Error, Result};
use crate::io::{read_bytes, write_atomic};
use crate::metrics::score_name::list as score_list;
use crate::metrics::ScoreName;
use crate::optimize::{axis_label, objective_of, Config, Evaluator, History, ScoreSet};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// A score over a grid of two parameters, as a chart shows it: the values, the axis labels and
/// optionally the optimizer's path.
#[derive(Clone, Debug, PartialEq)]
pub struct Heatmap {
    /// Title.
    pub title: String,
    /// Grid x values (at least 2, increasing).
    pub xs: Vec<f64>,
    /// Grid y values (at least 2, increasing).
    pub ys: Vec<f64>,
    /// `z[j][i]` at `(xs[i], ys[j])`; NaN where the cut failed.
    pub z: Vec<Vec<f64>>,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Colour bar label.
    pub z_label: String,
    /// The optimizer's path (best point so far), in (x, y).
    pub path: Option<Vec<(f64, f64)>>,
}

/// Draws a [`Heatmap`] as the PNG `png` and the SVG `svg`. The optimizer draws no charts
/// itself: the binary connects the plot module's `heatmap` here.
pub type HeatmapChart = fn(map: &Heatmap, png: &Path, svg: &Path) -> Result<()>;

/// Largest number of grid points.
pub const MAX_POINTS: usize = 250_000;

/// One axis of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Axis {
    /// Parameter of the config's cut space.
    pub key: String,
    /// Grid values, increasing.
    pub values: Vec<f64>,
    /// Unit, for the label.
    pub unit: Unit,
}

impl Axis {
    /// Parse `KEY:MIN:MAX:STEP` for `flag` (`--x`, `--y`), checking the key and every value
    /// against the config's cut space.
    pub fn parse(flag: &str, spec: &str, config: &Config) -> Result<Axis> {
        let parts: Vec<&str> = spec.split(':').map(str::trim).collect();
        if parts.len() != 4 {
            return Err(Error::invalid(
                flag,
                format!("`{spec}` is not KEY:MIN:MAX:STEP (e.g. crown_angle:25:40:0.5)"),
            ));
        }
        let (space, key) = (&config.space, parts[0]);
        let def = space.range(key).ok_or_else(|| {
            Error::invalid(
                flag,
                format!(
                    "`{}` is not a parameter of {}; allowed: {}",
                    key,
                    space.name(),
                    space.keys().join(", ")
                ),
            )
        })?;
        if def.unit == Unit::Count {
            return Err(Error::invalid(
                flag,
                format!("`{key}` is a whole-number parameter; sweep a continuous one"),
            ));
        }
        let num = |s: &str, what: &str| -> Result<f64> {
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(Error::invalid(
                    flag,
                    format!("{what} `{s}` is not a finite number"),
                )),
            }
        };
        let (min, max, step) = (
            num(parts[1], "MIN")?,
            num(parts[2], "MAX")?,
            num(parts[3], "STEP")?,
        );
        if step <= 0.0 {
            return Err(Error::invalid(
                flag,
                format!("STEP {} must be positive", shown(step)),
            ));
        }
        if max <= min {
            return Err(Error::invalid(
                flag,
                format!("MAX {} must be above MIN {}", shown(max), shown(min)),
            ));
        }
        let steps = ((max - min) / step * (1.0 + 1e-9)).floor();
        if steps >= 5000.0 {
            return Err(Error::invalid(
                flag,
                // The count to three figures: the step's slack (1e-9) would show as noise.
                format!(
                    "{} values; at most 5000 per axis",
                    shown(format!("{:.2e}", steps + 1.0).parse().unwrap_or(steps))
                ),
            ));
        }
        let n = steps as usize + 1;
        if n < 2 {
            return Err(Error::invalid(
                flag,
                format!(
                    "STEP {} leaves a single value between {} and {}; use a smaller step",
                    shown(step),
                    shown(min),
                    shown(max)
                ),
            ));
        }
        let decimals = [parts[1], parts[3]]
            .iter()
            .map(|s| s.split_once('.').map(|(_, f)| f.len()).unwrap_or(0))
            .max()
            .unwrap_or(0)
            .min(12) as i32;
        let scale = 10f64.powi(decimals);
        let values: Vec<f64> = (0..n)
            .map(|i| ((min + i as f64 * step) * scale).round() / scale)
            .collect();
        // Each value checked as the space checks it (its message, without the key).
        for &v in &values {
            space
                .complete(&BTreeMap::from([(key.to_string(), v)]))
                .map_err(|e| Error::invalid(format!("{flag} {key}"), strip_field(e)))?;
        }
        Ok(Axis {
            key: key.to_string(),
            values,
            unit: def.unit,
        })
    }

    /// Axis label with unit.
    pub fn label(&self) -> String {
        axis_label(&self.key, self.unit)
    }
}

fn strip_field(e: Error) -> String {
    match e {
        Error::Invalid { message, .. } => message,
        other => other.to_string(),
    }
}

/// Which score a heatmap shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SweepScore {
    /// One of the scores a sweep maps: brilliance, fire, scintillation, or a coloured
    /// stone's face-up colour score (`colour_l`, `colour_c`, `extinction` or `windowing`;
    /// NaN for a colourless stone); see [`SweepScore::SCORES`].
    Score(ScoreName),
    /// Σ weight · score − penalties.
    Objective,
}

impl SweepScore {
    /// The scores a sweep can map: the objective's three and a coloured stone's four.
    pub const SCORES: [ScoreName; 7] = [
        ScoreName::Brilliance,
        ScoreName::Fire,
        ScoreName::Scintillation,
        ScoreName::ColourL,
        ScoreName::ColourC,
        ScoreName::Extinction,
        ScoreName::Windowing,
    ];

    /// Brilliance.
    pub const BRILLIANCE: SweepScore = SweepScore::Score(ScoreName::Brilliance);
    /// Fire.
    pub const FIRE: SweepScore = SweepScore::Score(ScoreName::Fire);
    /// Scintillation.
    pub const SCINTILLATION: SweepScore = SweepScore::Score(ScoreName::Scintillation);

    /// This score of a grid point with `scores` (None when the cut failed: NaN) and
    /// `objective`.
    pub fn of(&self, scores: Option<&ScoreSet>, objective: f64) -> f64 {
        match (self, scores) {
            (SweepScore::Objective, _) => objective,
            (_, None) => f64::NAN,
            (SweepScore::Score(k), Some(s)) => s.get(*k).unwrap_or(f64::NAN),
        }
    }

    /// Parse `brilliance`, `fire`, `scintillation`, `objective` or a colour score
    /// (`colour_l`, `colour_c`, `extinction`, `windowing`); the error names the `sweep score`.
    pub fn parse(s: &str) -> Result<SweepScore> {
        if s == "objective" {
            return Ok(SweepScore::Objective);
        }
        ScoreName::from_key(s)
            .filter(|n| SweepScore::SCORES.contains(n))
            .map(SweepScore::Score)
            .ok_or_else(|| {
                Error::invalid(
                    "sweep score",
                    format!(
                        "unknown score `{s}`; allowed: {}, objective, {} (coloured stones)",
                        score_list(&ScoreName::OBJECTIVE),
                        score_list(&ScoreName::COLOUR)
                    ),
                )
            })
    }

    /// Name.
    pub fn name(&self) -> &'static str {
        match self {
            SweepScore::Objective => "objective",
            SweepScore::Score(k) => k.as_str(),
        }
    }
}

/// One grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// x value.
    pub x: f64,
    /// y value.
    pub y: f64,
    /// Scores (None when the cut failed).
    pub scores: Option<ScoreSet>,
    /// Σ weight · score − penalties (NaN when the cut failed).
    pub objective: f64,
}

impl Cell {
    /// The value of `score` (NaN when the cut failed).
    pub fn value(&self, score: &SweepScore) -> f64 {
        score.of(self.scores.as_ref(), self.objective)
    }
}

/// A finished sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// x axis.
    pub x: Axis,
    /// y axis.
    pub y: Axis,
    /// Cells, x fastest: cell `(i, j)` is `cells[j * nx + i]`.
    pub cells: Vec<Cell>,
}

/// The scores and the objective (NaN when not finite) of the config's start cut with `set`
/// changed; no scores and a NaN objective when the cut cannot be built or scored.
pub(crate) fn score_point(
    config: &Config,
    evaluator: &dyn Evaluator,
    set: &[(&str, f64)],
) -> (Option<ScoreSet>, f64) {
    let mut p = config.start.clone();
    for (k, v) in set {
        p.insert((*k).to_string(), *v);
    }
    let scored = config
        .space
        .build(&config.name, &p)
        .and_then(|cut| evaluator.evaluate(&cut).map(|s| (cut, s)));
    match scored {
        Ok((cut, s)) => {
            let obj = objective_of(config, &cut, &s);
            (Some(s), if obj.is_finite() { obj } else { f64::NAN })
        }
        Err(_) => (None, f64::NAN),
    }
}

/// Evaluate the grid (in parallel; the result is in grid order whatever the thread count).
/// `tick` is called once per finished point.
pub fn sweep(
    config: &Config,
    evaluator: &dyn Evaluator,
    x: &Axis,
    y: &Axis,
    tick: Option<&(dyn Fn() + Sync)>,
) -> Result<Sweep> {
    if x.key == y.key {
        return Err(Error::invalid(
            "sweep y axis",
            format!(
                "sweeps `{}` on both axes; give two different parameters",
                x.key
            ),
        ));
    }
    let nx = x.values.len();
    let n = nx * y.values.len();
    if n > MAX_POINTS {
        return Err(Error::invalid(
            "sweep grid",
            format!("{n} grid points; at most {MAX_POINTS}: use larger steps"),
        ));
    }
    let cells: Vec<Cell> = (0..n)
        .into_par_iter()
        .map(|k| {
            let (xv, yv) = (x.values[k % nx], y.values[k / nx]);
            let (scores, objective) = score_point(config, evaluator, &[(&x.key, xv), (&y.key, yv)]);
            if let Some(t) = tick {
                t();
            }
            Cell {
                x: xv,
                y: yv,
                scores,
                objective,
            }
        })
        .collect();
    Ok(Sweep {
        x: x.clone(),
        y: y.clone(),
        cells,
    })
}

impl Sweep {
    /// Names of the extra scores (from the first scored cell).
    fn extras(&self) -> Vec<ScoreName> {
        self.cells
            .iter()
            .find_map(|c| c.scores.as_ref())
            .map(|s| s.extra.iter().map(|(k, _)| *k).collect())
            .unwrap_or_default()
    }

    /// The CSV text.
    pub fn to_csv(&self) -> String {
        let extras = self.extras();
        let mut o = format!(
            "{},{},brilliance,fire,scintillation,objective",
            self.x.key, self.y.key
        );
        for e in &extras {
            let _ = write!(o, ",{e}");
        }
        o.push('\n');
        for c in &self.cells {
            let s = |v: f64| {
                if v.is_finite() {
                    v.to_string()
                } else {
                    "NaN".into()
                }
            };
            let _ = write!(
                o,
                "{},{},{},{},{},{}",
                c.x,
                c.y,
                s(c.value(&SweepScore::BRILLIANCE)),
                s(c.value(&SweepScore::FIRE)),
                s(c.value(&SweepScore::SCINTILLATION)),
                s(c.objective)
            );
            for e in &extras {
                let v = c
                    .scores
                    .as_ref()
                    .and_then(|sc| sc.get(*e))
                    .unwrap_or(f64::NAN);
                let _ = write!(o, ",{}", s(v));
            }
            o.push('\n');
        }
        o
    }

    /// The grid of `score`: `z[j][i]`.
    pub fn grid(&self, score: &SweepScore) -> Vec<Vec<f64>> {
        let nx = self.x.values.len();
        self.cells
            .chunks(nx)
            .map(|row| row.iter().map(|c| c.value(score)).collect())
            .collect()
    }

    /// The heatmap of `score`, with an optional path.
    pub fn heatmap(
        &self,
        score: &SweepScore,
        title: String,
        path: Option<Vec<(f64, f64)>>,
    ) -> Heatmap {
        Heatmap {
            title,
            xs: self.x.values.clone(),
            ys: self.y.values.clone(),
            z: self.grid(score),
            x_label: self.x.label(),
            y_label: self.y.label(),
            z_label: match score {
                SweepScore::Objective => "objective = weighted score − penalties".into(),
                other => other.name().to_string(),
            },
            path,
        }
    }
}

/// The optimizer's path (best point so far) from a run folder, projected on the sweep's axes.
/// A parameter that was not free in that run is constant: its value comes from the run's
/// `config.toml`.
pub fn run_path(run_dir: &Path, x: &str, y: &str) -> Result<Vec<(f64, f64)>> {
    let hist_path = run_dir.join("history.csv");
    let text = String::from_utf8_lossy(&read_bytes(&hist_path)?).to_string();
    let h = History::from_csv(&text, &hist_path.display().to_string())?;
    let col = |k: &str| h.keys.iter().position(|c| c == k);
    let fixed = |k: &str| -> Result<f64> {
        let cfg_path = run_dir.join("config.toml");
        let cfg = Config::load(&cfg_path)?;
        cfg.start.get(k).copied().ok_or_else(|| {
            Error::invalid(
                "run folder",
                format!(
                    "{}: the run's family {} has no parameter `{k}`",
                    run_dir.display(),
                    cfg.space.name()
                ),
            )
        })
    };
    let (cx, cy) = (col(x), col(y));
    let fx = match cx {
        Some(_) => 0.0,
        None => fixed(x)?,
    };
    let fy = match cy {
        Some(_) => 0.0,
        None => fixed(y)?,
    };
    Ok(h.best_path()
        .into_iter()
        .map(|p| (cx.map_or(fx, |i| p[i]), cy.map_or(fy, |i| p[i])))
        .collect())
}

/// A score along one parameter, as a chart shows it: every score's values against x.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileLines {
    /// Title.
    pub title: String,
    /// x values (at least 2, increasing).
    pub xs: Vec<f64>,
    /// x axis label.
    pub x_label: String,
    /// `(score name, values at xs)`: brilliance, fire, scintillation, objective; NaN where the
    /// cut failed.
    pub series: Vec<(String, Vec<f64>)>,
}

/// Draws a [`ProfileLines`] as the PNG `png` and the SVG `svg`. Like [`HeatmapChart`], the
/// binary connects the plot module's `profile` here.
pub type ProfileChart = fn(lines: &ProfileLines, png: &Path, svg: &Path) -> Result<()>;

/// One point of a [`Profile`].
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// x value.
    pub x: f64,
    /// Scores (None when the cut failed).
    pub scores: Option<ScoreSet>,
    /// Σ weight · score − penalties (NaN when the cut failed).
    pub objective: f64,
}

impl Point {
    /// The value of `score` (NaN when the cut failed).
    pub fn value(&self, score: &SweepScore) -> f64 {
        Cell {
            x: self.x,
            y: f64::NAN,
            scores: self.scores.clone(),
            objective: self.objective,
        }
        .value(score)
    }
}

/// A finished one-parameter sweep (a profile).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// The swept parameter.
    pub x: Axis,
    /// One point per x value, in order.
    pub points: Vec<Point>,
}

/// The scores drawn and written for every point, in order.
pub(crate) const SCORES: [SweepScore; 4] = [
    SweepScore::BRILLIANCE,
    SweepScore::FIRE,
    SweepScore::SCINTILLATION,
    SweepScore::Objective,
];

/// Evaluate the scores along one axis (in parallel; the result is in order whatever the thread
/// count). `tick` is called once per finished point.
pub fn profile(
    config: &Config,
    evaluator: &dyn Evaluator,
    x: &Axis,
    tick: Option<&(dyn Fn() + Sync)>,
) -> Result<Profile> {
    let points = x
        .values
        .par_iter()
        .map(|&xv| {
            let (scores, objective) = score_point(config, evaluator, &[(&x.key, xv)]);
            if let Some(t) = tick {
                t();
            }
            Point {
                x: xv,
                scores,
                objective,
            }
        })
        .collect();
    Ok(Profile {
        x: x.clone(),
        points,
    })
}

impl Profile {
    /// The CSV text: `<x key>,brilliance,fire,scintillation,objective` (+ any extra scores),
    /// one row per x.
    pub fn to_csv(&self) -> String {
        let extras: Vec<ScoreName> = self
            .points
            .iter()
            .find_map(|p| p.scores.as_ref())
            .map(|s| s.extra.iter().map(|(k, _)| *k).collect())
            .unwrap_or_default();
        let s = |v: f64| {
            if v.is_finite() {
                v.to_string()
            } else {
                "NaN".into()
            }
        };
        let mut o = format!("{},brilliance,fire,scintillation,objective", self.x.key);
        for e in &extras {
            let _ = write!(o, ",{e}");
        }
        o.push('\n');
        for p in &self.points {
            let _ = write!(o, "{}", p.x);
            for score in &SCORES {
                let _ = write!(o, ",{}", s(p.value(score)));
            }
            for e in &extras {
                let v = p.scores.as_ref().and_then(|sc| sc.get(*e));
                let _ = write!(o, ",{}", s(v.unwrap_or(f64::NAN)));
            }
            o.push('\n');
        }
        o
    }

    /// The chart's lines: every score against x.
    pub fn lines(&self, title: String) -> ProfileLines {
        ProfileLines {
            title,
            xs: self.x.values.clone(),
            x_label: self.x.label(),
            series: SCORES
                .iter()
                .map(|score| {
                    let v = self.points.iter().map(|p| p.value(score)).collect();
                    (score.name().to_string(), v)
                })
                .collect(),
        }
    }
}

/// Write a profile's CSV and its chart (PNG and SVG, drawn by `chart`) where [`output_paths`]
/// says.
pub fn write_profile(
    profile: &Profile,
    title: String,
    out: &Path,
    chart: ProfileChart,
) -> Result<(PathBuf, PathBuf, PathBuf)> {
    let (csv, png, svg) = output_paths(out);
    if let Some(d) = csv.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| Error::io(d.display().to_string(), e))?;
    }
    write_atomic(&csv, profile.to_csv().as_bytes())?;
    chart(&profile.lines(title), &png, &svg)?;
    Ok((csv, png, svg))
}

/// Where a sweep's three files go: `--out` as a folder (`sweep.csv`, `.png`, `.svg` in it) or,
/// with a `.csv`, `.png` or `.svg` extension, as the common stem.
pub fn output_paths(out: &Path) -> (PathBuf, PathBuf, PathBuf) {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let stem = match ext.as_deref() {
        Some("csv" | "png" | "svg") => out.with_extension(""),
        _ => out.join("sweep"),
    };
    (
        stem.with_extension("csv"),
        stem.with_extension("png"),
        stem.with_extension("svg"),
    )
}

/// Write the CSV and the heatmap (PNG and SVG, drawn by `chart`).
pub fn write(
    sweep: &Sweep,
    score: &SweepScore,
    title: String,
    path: Option<Vec<(f64, f64)>>,
    out: &Path,
    chart: HeatmapChart,
) -> Result<(PathBuf, PathBuf, PathBuf)> {
    let (csv, png, svg) = output_paths(out);
    if let Some(d) = csv.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(d).map_err(|e| Error::io(d.display().to_string(), e))?;
    }
    write_atomic(&csv, sweep.to_csv().as_bytes())?;
    chart(&sweep.heatmap(score, title, path), &png, &svg)?;
    Ok((csv, png, svg))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::Cut;

    fn cfg() -> Config {
        Config::from_str(
            "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [30.0, 38.0]\n",
            "s.toml",
        )
        .unwrap()
    }

    #[test]
    fn axes_parse_and_refuse() {
        let c = cfg();
        let a = Axis::parse("x axis", "crown_angle:25:40:0.5", &c).unwrap();
        assert_eq!(a.values.len(), 31);
        assert_eq!(a.values[3], 26.5);
        assert_eq!(*a.values.last().unwrap(), 40.0);
        let b = Axis::parse("y axis", "pavilion_angle:38:43:0.1", &c).unwrap();
        assert_eq!(b.values.len(), 51);
        assert_eq!(b.values[7], 38.7, "rounded to the step's decimals");
        for (spec, want) in [
            (
                "crown_angle:25:40",
                "x axis: `crown_angle:25:40` is not KEY:MIN:MAX:STEP",
            ),
            (
                "crown:25:40:1",
                "x axis: `crown` is not a parameter of round-brilliant",
            ),
            ("crown_angle:40:25:1", "x axis: MAX 25 must be above MIN 40"),
            ("crown_angle:25:40:0", "x axis: STEP 0 must be positive"),
            (
                "crown_angle:25:40:x",
                "x axis: STEP `x` is not a finite number",
            ),
            (
                "crown_angle:1:40:1",
                "x axis crown_angle: 1 is out of range",
            ),
            ("girdle_facets:0:32:16", "whole-number"),
            ("crown_angle:25:26:5", "single value"),
            ("crown_angle:25:40:1e-300", "at most 5000 per axis"),
        ] {
            let e = Axis::parse("x axis", spec, &c).unwrap_err().to_string();
            assert!(e.contains(want), "{spec}: {e}");
        }
        assert!(SweepScore::parse("fyre")
            .unwrap_err()
            .to_string()
            .starts_with("sweep score: unknown score `fyre`"));
    }

    #[test]
    fn sweep_is_in_grid_order_and_writes_files() {
        let c = cfg();
        let x = Axis::parse("x axis", "crown_angle:30:36:1", &c).unwrap();
        let y = Axis::parse("y axis", "pavilion_angle:39:42:0.5", &c).unwrap();
        let bump = |cut: &Cut| -> Result<ScoreSet> {
            let (a, b) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
            Ok(ScoreSet::new(
                (-((a - 34.0) / 2.0).powi(2) - (b - 40.5).powi(2)).exp(),
                a / 100.0,
                0.0,
            ))
        };
        let s = sweep(&c, &bump, &x, &y, None).unwrap();
        assert_eq!(s.cells.len(), 7 * 7);
        assert_eq!((s.cells[8].x, s.cells[8].y), (31.0, 39.5));
        let g = s.grid(&SweepScore::BRILLIANCE);
        assert!((g[3][4] - 1.0).abs() < 1e-12, "peak at (34, 40.5)");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let s1 = pool.install(|| sweep(&c, &bump, &x, &y, None).unwrap());
        assert_eq!(s1.to_csv(), s.to_csv());
        let dir = tempfile::tempdir().unwrap();
        // The chart receives the map; this one writes its size and path as text.
        let chart: HeatmapChart = |m, png, svg| {
            let text = format!("{}x{} {:?}", m.xs.len(), m.ys.len(), m.path);
            write_atomic(png, text.as_bytes())?;
            write_atomic(svg, m.z_label.as_bytes())
        };
        let (csv, png, svg) = write(
            &s,
            &SweepScore::BRILLIANCE,
            "t".into(),
            Some(vec![(31.0, 39.5), (34.0, 40.5)]),
            &dir.path().join("map.png"),
            chart,
        )
        .unwrap();
        assert!(csv.ends_with("map.csv"));
        assert_eq!(
            std::fs::read_to_string(png).unwrap(),
            "7x7 Some([(31.0, 39.5), (34.0, 40.5)])"
        );
        assert_eq!(std::fs::read_to_string(svg).unwrap(), "brilliance");
        let text = std::fs::read_to_string(csv).unwrap();
        assert!(text.starts_with(
            "crown_angle,pavilion_angle,brilliance,fire,scintillation,objective\n30,39,"
        ));
        assert_eq!(output_paths(Path::new("out")).0, Path::new("out/sweep.csv"));
    }

    #[test]
    fn a_profile_is_in_order_and_writes_one_row_per_x() {
        let c = cfg();
        let x = Axis::parse("x axis", "crown_angle:30:36:1", &c).unwrap();
        let bump = |cut: &Cut| -> Result<ScoreSet> {
            let a = cut.params["crown_angle"];
            if a == 35.0 {
                return Err(Error::Geometry("refused".into()));
            }
            let mut s = ScoreSet::new((-((a - 34.0) / 2.0).powi(2)).exp(), a / 100.0, 0.25);
            s.extra.push((crate::metrics::ScoreName::AsetRed, 0.5));
            Ok(s)
        };
        let p = profile(&c, &bump, &x, None).unwrap();
        let csv = p.to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "crown_angle,brilliance,fire,scintillation,objective,aset_red"
        );
        assert_eq!(lines.len(), 1 + 7);
        assert_eq!(
            lines[5], "34,1,0.34,0.25,1,0.5",
            "default weights: brilliance only"
        );
        assert_eq!(lines[6], "35,NaN,NaN,NaN,NaN,NaN");
        let l = p.lines("t".into());
        assert_eq!(l.series.len(), 4);
        assert_eq!(l.series[1].0, "fire");
        assert_eq!(l.series[0].1[4], 1.0);
        let dir = tempfile::tempdir().unwrap();
        let chart: ProfileChart = |l, png, svg| {
            write_atomic(png, format!("{} points", l.xs.len()).as_bytes())?;
            write_atomic(svg, l.x_label.as_bytes())
        };
        let (csv_path, png, _) =
            write_profile(&p, "t".into(), &dir.path().join("prof"), chart).unwrap();
        assert!(csv_path.ends_with("prof/sweep.csv"));
        assert_eq!(std::fs::read_to_string(csv_path).unwrap(), csv);
        assert_eq!(std::fs::read_to_string(png).unwrap(), "7 points");
    }
}
