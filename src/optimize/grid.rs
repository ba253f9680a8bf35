//! N-axis sweeps and their shards: the grid of any number of [`Axis`] values, its fixed order,
//! the share of it one shard evaluates, the shard's row file, and the exact merge.
//!
//! **Order.** The grid is the Cartesian product of the axes with the *first* axis varying
//! fastest (`--x`, then `--y`, then each `--axis` in order): point `i` has axis `a` at value
//! index `(i / (n_0 · … · n_{a−1})) mod n_a`. This is the order the 2-axis sweep has always
//! written (x fastest), so 1- and 2-axis CSVs are unchanged.
//!
//! **CSV.** `<axis keys…>,brilliance,fire,scintillation,objective` (+ the extra scores of the
//! first scored point), one row per grid point in grid order; `NaN` where the cut failed.
//!
//! **Shards.** Shard `K/N` (1-based K) evaluates the points `i` with `i mod N == K − 1`
//! (interleaved, so neighbouring — similarly slow — points spread over all shards). A shard
//! appends each finished point to `rows.csv` as one line
//! `index,<axis values…>,brilliance,fire,scintillation,objective,extras` where `extras` is
//! `-` for a cut that failed and otherwise `name=value;name=value` (possibly empty). Numbers are
//! written exactly as the sweep's CSV writes them (shortest round-trip), so a merge that reads
//! them back writes the same bytes as one unsharded run.

use super::sweep::{score_point, Axis, Heatmap, ProfileLines, SweepScore, MAX_POINTS, SCORES};
use super::{Config, Evaluator, ScoreSet};
use crate::error::{Error, Result};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt::Write;
use std::sync::atomic::{AtomicBool, Ordering};

/// The grid of an N-axis sweep (first axis fastest).
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// The axes, in command-line order.
    pub axes: Vec<Axis>,
}

impl Grid {
    /// A grid of `axes`: at least one, distinct keys, at most `MAX_POINTS` (250 000) points.
    pub fn new(axes: Vec<Axis>) -> Result<Grid> {
        if axes.is_empty() {
            return Err(Error::invalid(
                "--x",
                "give at least one axis: --x KEY:MIN:MAX:STEP (or --axis)",
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            if axes[..i].iter().any(|b| b.key == a.key) {
                return Err(Error::invalid(
                    "--axis",
                    format!("sweeps `{}` on two axes; give different parameters", a.key),
                ));
            }
        }
        let mut n: usize = 1;
        for a in &axes {
            n = n.saturating_mul(a.values.len());
        }
        if n > MAX_POINTS {
            return Err(Error::invalid(
                "--axis",
                format!("{n} grid points; at most {MAX_POINTS}: use larger steps or fewer axes"),
            ));
        }
        Ok(Grid { axes })
    }

    /// Number of grid points.
    pub fn len(&self) -> usize {
        self.axes.iter().map(|a| a.values.len()).product()
    }

    /// Whether the grid is empty (never, for a grid made by [`Grid::new`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The value index on each axis of point `i`.
    pub fn indices(&self, mut i: usize) -> Vec<usize> {
        self.axes
            .iter()
            .map(|a| {
                let n = a.values.len();
                let j = i % n;
                i /= n;
                j
            })
            .collect()
    }

    /// The point of value indices `idx` (one per axis).
    pub fn index(&self, idx: &[usize]) -> usize {
        let mut i = 0;
        let mut stride = 1;
        for (a, &j) in self.axes.iter().zip(idx) {
            i += j * stride;
            stride *= a.values.len();
        }
        i
    }

    /// The axis values of point `i`.
    pub fn point(&self, i: usize) -> Vec<f64> {
        self.indices(i)
            .iter()
            .zip(&self.axes)
            .map(|(&j, a)| a.values[j])
            .collect()
    }

    /// Position of the axis `key`.
    pub fn axis(&self, key: &str) -> Option<usize> {
        self.axes.iter().position(|a| a.key == key)
    }
}

/// One evaluated grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct GridCell {
    /// Grid index.
    pub index: usize,
    /// Axis values.
    pub values: Vec<f64>,
    /// Scores (None when the cut failed).
    pub scores: Option<ScoreSet>,
    /// Σ weight · score − penalties (NaN when the cut failed).
    pub objective: f64,
}

impl GridCell {
    /// The value of `score` (NaN when the cut failed).
    pub fn value(&self, score: &SweepScore) -> f64 {
        score.of(self.scores.as_ref(), self.objective)
    }
}

fn num(v: f64) -> String {
    if v.is_finite() {
        v.to_string()
    } else {
        "NaN".into()
    }
}

/// Evaluate the points `indices` of `grid` in parallel. `each` is called with every finished
/// point (from the worker threads, in any order); points not yet started when `stop` is raised
/// are skipped. The result is in the order of `indices`, without the skipped points.
pub fn evaluate(
    config: &Config,
    evaluator: &dyn Evaluator,
    grid: &Grid,
    indices: &[usize],
    stop: Option<&AtomicBool>,
    each: &(dyn Fn(&GridCell) + Sync),
) -> Vec<GridCell> {
    indices
        .par_iter()
        .filter_map(|&i| {
            if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
                return None;
            }
            let values = grid.point(i);
            let set: Vec<(&str, f64)> = grid
                .axes
                .iter()
                .zip(&values)
                .map(|(a, &v)| (a.key.as_str(), v))
                .collect();
            let (scores, objective) = score_point(config, evaluator, &set);
            let cell = GridCell {
                index: i,
                values,
                scores,
                objective,
            };
            each(&cell);
            Some(cell)
        })
        .collect()
}

/// The sweep's CSV (see the module documentation) of all the grid's `cells`, in grid order.
pub fn to_csv(grid: &Grid, cells: &[GridCell]) -> String {
    let extras: Vec<String> = cells
        .iter()
        .find_map(|c| c.scores.as_ref())
        .map(|s| s.extra.iter().map(|(k, _)| k.clone()).collect())
        .unwrap_or_default();
    let keys: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
    let mut o = format!("{},brilliance,fire,scintillation,objective", keys.join(","));
    for e in &extras {
        let _ = write!(o, ",{e}");
    }
    o.push('\n');
    for c in cells {
        let vals: Vec<String> = c.values.iter().map(|v| v.to_string()).collect();
        o.push_str(&vals.join(","));
        for score in &SCORES {
            let _ = write!(o, ",{}", num(c.value(score)));
        }
        for e in &extras {
            let v = c.scores.as_ref().and_then(|sc| sc.get(e));
            let _ = write!(o, ",{}", num(v.unwrap_or(f64::NAN)));
        }
        o.push('\n');
    }
    o
}

/// The header of a shard's `rows.csv`.
pub fn rows_header(grid: &Grid) -> String {
    let keys: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
    format!(
        "index,{},brilliance,fire,scintillation,objective,extras\n",
        keys.join(",")
    )
}

/// One line of a shard's `rows.csv` (with its newline).
pub fn shard_row(cell: &GridCell) -> String {
    let mut o = cell.index.to_string();
    for v in &cell.values {
        let _ = write!(o, ",{v}");
    }
    for score in &SCORES {
        let _ = write!(o, ",{}", num(cell.value(score)));
    }
    o.push(',');
    match &cell.scores {
        None => o.push('-'),
        Some(s) => {
            let pairs: Vec<String> = s
                .extra
                .iter()
                .map(|(k, v)| format!("{k}={}", num(*v)))
                .collect();
            o.push_str(&pairs.join(";"));
        }
    }
    o.push('\n');
    o
}

/// Read a line of `rows.csv` back (without its newline) for a grid of `naxes` axes.
pub fn parse_shard_row(line: &str, naxes: usize) -> Option<GridCell> {
    let f: Vec<&str> = line.split(',').collect();
    if f.len() != 1 + naxes + 4 + 1 {
        return None;
    }
    let index: usize = f[0].parse().ok()?;
    let nums = |s: &[&str]| -> Option<Vec<f64>> { s.iter().map(|v| v.parse().ok()).collect() };
    let values = nums(&f[1..1 + naxes])?;
    let sc = nums(&f[1 + naxes..5 + naxes])?;
    let scores = match f[5 + naxes] {
        "-" => None,
        pairs => {
            let mut s = ScoreSet::new(sc[0], sc[1], sc[2]);
            for p in pairs.split(';').filter(|p| !p.is_empty()) {
                let (k, v) = p.split_once('=')?;
                s.extra.push((k.to_string(), v.parse().ok()?));
            }
            Some(s)
        }
    };
    Some(GridCell {
        index,
        values,
        scores,
        objective: sc[3],
    })
}

/// Read a shard's `rows.csv` text: the cells of its complete lines, and the byte length of
/// those lines (a last line cut short by an interruption is not counted, so the caller can
/// truncate it away before appending). `Err` names the first malformed complete line.
pub fn read_rows(text: &str, grid: &Grid) -> std::result::Result<(Vec<GridCell>, usize), String> {
    let mut cells = Vec::new();
    let mut good = 0;
    let mut pos = 0;
    for (n, line) in text.split_inclusive('\n').enumerate() {
        pos += line.len();
        let Some(body) = line.strip_suffix('\n') else {
            break; // cut short: dropped
        };
        if n == 0 {
            if line != rows_header(grid) {
                return Err("its header does not match the sweep's axes".into());
            }
            good = pos;
            continue;
        }
        match parse_shard_row(body, grid.axes.len()) {
            Some(c) if c.index < grid.len() => cells.push(c),
            _ => return Err(format!("line {} is not a row of this sweep", n + 1)),
        }
        good = pos;
    }
    Ok((cells, good))
}

/// A share of a grid or batch: `K/N`, 1-based `k`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard, 1..=n.
    pub k: usize,
    /// Number of shards.
    pub n: usize,
}

impl Shard {
    /// Parse `K/N` (1 ≤ K ≤ N) for `flag`.
    pub fn parse(flag: &str, s: &str) -> Result<Shard> {
        let bad = || {
            Error::invalid(
                flag,
                format!("`{s}` is not K/N with 1 ≤ K ≤ N (e.g. 2/8; K is 1-based)"),
            )
        };
        let (k, n) = s.trim().split_once('/').ok_or_else(bad)?;
        let (k, n): (usize, usize) = (
            k.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if k == 0 || n == 0 || k > n {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }

    /// The shard from the environment of a job array (`get` reads a variable), or None when
    /// none is set: Slurm's `SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN + 1` of
    /// `SLURM_ARRAY_TASK_COUNT` (MIN 0 when unset; a step other than 1 is refused), else
    /// Kubernetes' `JOB_COMPLETION_INDEX + 1` of `JOB_COMPLETION_COUNT` (which the Job's
    /// manifest sets to its `completions`). Returns the shard and where it came from.
    pub fn from_env(get: &dyn Fn(&str) -> Option<String>) -> Result<Option<(Shard, String)>> {
        let int = |name: &str| -> Result<Option<usize>> {
            match get(name) {
                None => Ok(None),
                Some(v) if v.trim().is_empty() => Ok(None),
                Some(v) => v
                    .trim()
                    .parse::<usize>()
                    .map(Some)
                    .map_err(|_| Error::invalid(name, format!("`{v}` is not a whole number"))),
            }
        };
        if let Some(id) = int("SLURM_ARRAY_TASK_ID")? {
            let min = int("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
            let count = int("SLURM_ARRAY_TASK_COUNT")?.ok_or_else(|| {
                Error::invalid(
                    "SLURM_ARRAY_TASK_COUNT",
                    "is not set, but SLURM_ARRAY_TASK_ID is; give --shard K/N",
                )
            })?;
            if let Some(step) = int("SLURM_ARRAY_TASK_STEP")? {
                if step != 1 {
                    return Err(Error::invalid(
                        "SLURM_ARRAY_TASK_STEP",
                        format!("is {step}; shards need a contiguous array (--array=0-N or 1-N), or give --shard K/N"),
                    ));
                }
            }
            if id < min || id - min >= count {
                return Err(Error::invalid(
                    "SLURM_ARRAY_TASK_ID",
                    format!("{id} is outside MIN {min} .. MIN + COUNT {count}; the array must be contiguous, or give --shard K/N"),
                ));
            }
            let s = Shard {
                k: id - min + 1,
                n: count,
            };
            return Ok(Some((
                s,
                format!("SLURM_ARRAY_TASK_ID={id}, SLURM_ARRAY_TASK_MIN={min}, SLURM_ARRAY_TASK_COUNT={count}"),
            )));
        }
        if let Some(ix) = int("JOB_COMPLETION_INDEX")? {
            let count = int("JOB_COMPLETION_COUNT")?.ok_or_else(|| {
                Error::invalid(
                    "JOB_COMPLETION_COUNT",
                    "is not set, but JOB_COMPLETION_INDEX is; set it to the Job's completions in the manifest, or give --shard K/N",
                )
            })?;
            if ix >= count {
                return Err(Error::invalid(
                    "JOB_COMPLETION_INDEX",
                    format!("{ix} is not below JOB_COMPLETION_COUNT {count}"),
                ));
            }
            return Ok(Some((
                Shard {
                    k: ix + 1,
                    n: count,
                },
                format!("JOB_COMPLETION_INDEX={ix}, JOB_COMPLETION_COUNT={count}"),
            )));
        }
        Ok(None)
    }

    /// Whether item `i` (0-based) is this shard's: `i mod N == K − 1`.
    pub fn owns(&self, i: usize) -> bool {
        i % self.n == self.k - 1
    }

    /// This shard's items among `0..len`.
    pub fn indices(&self, len: usize) -> Vec<usize> {
        (self.k - 1..len).step_by(self.n).collect()
    }
}

/// FNV-1a (64 bit) of `bytes`, as 16 hex digits: the `config_hash` of a shard.
pub fn hash(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// One axis as a shard records it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AxisRecord {
    /// Parameter.
    pub key: String,
    /// Axis label with unit (for the maps a merge draws).
    pub label: String,
    /// Grid values.
    pub values: Vec<f64>,
}

/// `shard.json`: what a shard covers and what it has done.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShardRecord {
    /// Format version (1).
    pub format: u32,
    /// The config file as given.
    pub config: String,
    /// The config's name.
    pub name: String,
    /// The family swept.
    pub family: String,
    /// FNV-1a 64 of the config file's bytes.
    pub config_hash: String,
    /// The axes, in grid order (first fastest).
    pub axes: Vec<AxisRecord>,
    /// Grid points in the whole sweep.
    pub grid_size: usize,
    /// Number of shards.
    pub n: usize,
    /// This shard (1-based).
    pub k: usize,
    /// The rule: `index mod n == k - 1`.
    pub rule: String,
    /// This shard's points.
    pub points: usize,
    /// How many of them are in rows.csv.
    pub done: usize,
    /// Whether every point of the shard is done.
    pub complete: bool,
    /// Points found in rows.csv when this run started (not recomputed).
    pub resumed: usize,
    /// Points computed by the last run.
    pub computed: usize,
    /// The grid indices in rows.csv, increasing.
    pub indices_done: Vec<usize>,
}

impl ShardRecord {
    /// Whether `other` belongs to the same sweep (config, axes, N).
    pub fn same_sweep(&self, other: &ShardRecord) -> bool {
        self.config_hash == other.config_hash
            && self.n == other.n
            && self.grid_size == other.grid_size
            && self.axes.len() == other.axes.len()
            && self
                .axes
                .iter()
                .zip(&other.axes)
                .all(|(a, b)| a.key == b.key && a.values == b.values)
    }

    /// A grid with these axes (units are not recorded; only keys and values are used).
    pub fn grid(&self) -> Grid {
        Grid {
            axes: self
                .axes
                .iter()
                .map(|a| Axis {
                    key: a.key.clone(),
                    values: a.values.clone(),
                    unit: crate::cut::Unit::Count,
                })
                .collect(),
        }
    }
}

/// Where the map's other axes are held: the value index on each axis (`None` for the two
/// mapped axes). Default: the grid value nearest each axis' middle; `at` gives `(key, value)`
/// choices, each snapped to the nearest grid value (a value off the axis' range is refused;
/// a tie goes to the lower value).
pub fn fixed_at(grid: &Grid, at: &[(String, f64)]) -> Result<Vec<usize>> {
    let mut idx: Vec<usize> = grid
        .axes
        .iter()
        .map(|a| {
            let (lo, hi) = (a.values[0], a.values[a.values.len() - 1]);
            nearest(&a.values, (lo + hi) / 2.0)
        })
        .collect();
    for (k, v) in at {
        let Some(ai) = grid.axis(k) else {
            let keys: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
            return Err(Error::invalid(
                "--at",
                format!(
                    "`{k}` is not an axis of this sweep; axes: {}",
                    keys.join(", ")
                ),
            ));
        };
        let a = &grid.axes[ai];
        let (lo, hi) = (a.values[0], a.values[a.values.len() - 1]);
        let step = a.values.get(1).map_or(0.0, |s| s - lo);
        if !v.is_finite() || *v < lo - step / 2.0 || *v > hi + step / 2.0 {
            return Err(Error::invalid(
                "--at",
                format!("{k} = {v} is outside the axis ({lo} to {hi})"),
            ));
        }
        idx[ai] = nearest(&a.values, *v);
    }
    Ok(idx)
}

fn nearest(values: &[f64], v: f64) -> usize {
    let mut best = 0;
    for (i, x) in values.iter().enumerate() {
        if (x - v).abs() < (values[best] - v).abs() - 1e-12 {
            best = i;
        }
    }
    best
}

/// Parse `--at KEY=VALUE` pairs.
pub fn parse_at(specs: &[String]) -> Result<Vec<(String, f64)>> {
    specs
        .iter()
        .map(|s| {
            let (k, v) = s
                .split_once('=')
                .ok_or_else(|| Error::invalid("--at", format!("`{s}` is not KEY=VALUE")))?;
            let v: f64 = v
                .trim()
                .parse()
                .map_err(|_| Error::invalid("--at", format!("`{v}` in `{s}` is not a number")))?;
            Ok((k.trim().to_string(), v))
        })
        .collect()
}

/// A heatmap of `score` over the axes `mx`, `my` with the others at `fixed` (value indices;
/// see [`fixed_at`]). `cells` are all of the grid's, in grid order; `labels` the axis labels.
#[allow(clippy::too_many_arguments)]
pub fn heatmap(
    grid: &Grid,
    cells: &[GridCell],
    labels: &[String],
    score: &SweepScore,
    (mx, my): (usize, usize),
    fixed: &[usize],
    title: String,
    path: Option<Vec<(f64, f64)>>,
) -> Heatmap {
    let (xs, ys) = (&grid.axes[mx].values, &grid.axes[my].values);
    let mut idx = fixed.to_vec();
    let z = (0..ys.len())
        .map(|j| {
            (0..xs.len())
                .map(|i| {
                    idx[mx] = i;
                    idx[my] = j;
                    cells[grid.index(&idx)].value(score)
                })
                .collect()
        })
        .collect();
    Heatmap {
        title,
        xs: xs.clone(),
        ys: ys.clone(),
        z,
        x_label: labels[mx].clone(),
        y_label: labels[my].clone(),
        z_label: match score {
            SweepScore::Objective => "objective = weighted score − penalties".into(),
            other => other.name().to_string(),
        },
        path,
    }
}

/// Every score along axis `ax` with the others at `fixed` (see [`fixed_at`]).
pub fn profile_lines(
    grid: &Grid,
    cells: &[GridCell],
    labels: &[String],
    ax: usize,
    fixed: &[usize],
    title: String,
) -> ProfileLines {
    let xs = &grid.axes[ax].values;
    let mut idx = fixed.to_vec();
    let at: Vec<&GridCell> = (0..xs.len())
        .map(|i| {
            idx[ax] = i;
            &cells[grid.index(&idx)]
        })
        .collect();
    ProfileLines {
        title,
        xs: xs.clone(),
        x_label: labels[ax].clone(),
        series: SCORES
            .iter()
            .map(|s| {
                (
                    s.name().to_string(),
                    at.iter().map(|c| c.value(s)).collect(),
                )
            })
            .collect(),
    }
}

/// Check that the shards' cells cover `grid` exactly once and put them in grid order.
/// `owner` names the shard (folder) each cell came from, for the error.
pub fn assemble(
    grid: &Grid,
    cells: Vec<(String, GridCell)>,
) -> std::result::Result<Vec<GridCell>, String> {
    let mut slots: Vec<Option<(String, GridCell)>> = vec![None; grid.len()];
    for (who, c) in cells {
        let i = c.index;
        if let Some((first, _)) = &slots[i] {
            return Err(format!(
                "grid point {i} is in both {first} and {who}; give each shard once"
            ));
        }
        slots[i] = Some((who, c));
    }
    let missing: Vec<usize> = slots
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(i, _)| i)
        .collect();
    if let Some(&first) = missing.first() {
        return Err(format!(
            "{} of {} grid points are missing (first: {first})",
            missing.len(),
            grid.len()
        ));
    }
    Ok(slots.into_iter().map(|s| s.unwrap().1).collect())
}

/// The map axes from `--map KEY1[,KEY2]` (default: the first two axes).
pub fn map_axes(grid: &Grid, map: Option<&str>) -> Result<Vec<usize>> {
    let Some(m) = map else {
        return Ok((0..grid.axes.len().min(2)).collect());
    };
    let keys: Vec<&str> = m.split(',').map(str::trim).collect();
    if keys.is_empty() || keys.len() > 2 {
        return Err(Error::invalid(
            "--map",
            format!("`{m}` is not KEY1,KEY2 (or one KEY for a profile)"),
        ));
    }
    let mut out = Vec::new();
    for k in &keys {
        let Some(i) = grid.axis(k) else {
            let all: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
            return Err(Error::invalid(
                "--map",
                format!(
                    "`{k}` is not an axis of this sweep; axes: {}",
                    all.join(", ")
                ),
            ));
        };
        if out.contains(&i) {
            return Err(Error::invalid(
                "--map",
                format!("`{k}` twice; give two different axes"),
            ));
        }
        out.push(i);
    }
    Ok(out)
}

/// The highest finite `score` and its point.
pub fn best<'a>(cells: &'a [GridCell], score: &SweepScore) -> Option<(&'a GridCell, f64)> {
    cells
        .iter()
        .map(|c| (c, c.value(score)))
        .filter(|(_, v)| v.is_finite())
        .max_by(|a, b| a.1.total_cmp(&b.1))
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

    fn bump(cut: &Cut) -> Result<ScoreSet> {
        let (a, b) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
        if a == 35.0 && b == 40.0 {
            return Err(Error::Geometry("refused".into()));
        }
        let mut s = ScoreSet::new(
            (-((a - 34.0) / 2.0).powi(2) - (b - 40.5).powi(2)).exp(),
            cut.params["table"] / 3.0,
            0.1,
        );
        s.extra.push(("aset_red".into(), a / 7.0));
        Ok(s)
    }

    #[test]
    fn order_shards_rows_and_merge_agree_with_the_two_axis_sweep() {
        let c = cfg();
        let x = Axis::parse("--x", "crown_angle:33:36:1", &c).unwrap();
        let y = Axis::parse("--y", "pavilion_angle:40:41:0.5", &c).unwrap();
        let t = Axis::parse("--axis", "table:0.55:0.57:0.01", &c).unwrap();
        let two = Grid::new(vec![x.clone(), y.clone()]).unwrap();
        assert_eq!(two.point(5), vec![34.0, 40.5], "first axis fastest");
        let all: Vec<usize> = (0..two.len()).collect();
        let cells = evaluate(&c, &bump, &two, &all, None, &|_| {});
        let old = super::super::sweep::sweep(&c, &bump, &x, &y, None).unwrap();
        assert_eq!(
            to_csv(&two, &cells),
            old.to_csv(),
            "same bytes as the 2-axis sweep"
        );
        let one = Grid::new(vec![x.clone()]).unwrap();
        let p = super::super::sweep::profile(&c, &bump, &x, None).unwrap();
        let cells1 = evaluate(&c, &bump, &one, &[0, 1, 2, 3], None, &|_| {});
        assert_eq!(
            to_csv(&one, &cells1),
            p.to_csv(),
            "same bytes as the profile"
        );

        let three = Grid::new(vec![x.clone(), y.clone(), t]).unwrap();
        assert_eq!(three.len(), 36);
        assert_eq!(three.indices(23), vec![3, 2, 1]);
        assert_eq!(three.index(&[3, 2, 1]), 23);
        let all: Vec<usize> = (0..three.len()).collect();
        let cells = evaluate(&c, &bump, &three, &all, None, &|_| {});
        let whole = to_csv(&three, &cells);
        assert!(whole.starts_with("crown_angle,pavilion_angle,table,brilliance,"));
        // Three shards, their rows written and read back, merged: the same bytes.
        let mut rows = Vec::new();
        for k in 1..=3 {
            let s = Shard { k, n: 3 };
            let mut text = rows_header(&three);
            for i in s.indices(three.len()) {
                assert!(s.owns(i));
                text.push_str(&shard_row(&cells[i]));
            }
            text.push_str("17,3"); // cut short by an interruption
            let (back, len) = read_rows(&text, &three).unwrap();
            assert_eq!(len, text.len() - 4);
            rows.extend(back.into_iter().map(|c| (format!("shard {k}"), c)));
        }
        let merged = assemble(&three, rows.clone()).unwrap();
        assert_eq!(to_csv(&three, &merged), whole);
        let mut dup = rows.clone();
        dup.push(("shard 9".into(), rows[0].1.clone()));
        assert!(assemble(&three, dup).unwrap_err().contains("shard 9"));
        rows.pop();
        assert!(assemble(&three, rows).unwrap_err().contains("1 of 36"));
        // A map of any two axes with the third held.
        let labels: Vec<String> = three.axes.iter().map(|a| a.label()).collect();
        let fixed = fixed_at(&three, &[("crown_angle".into(), 34.2)]).unwrap();
        assert_eq!(fixed, vec![1, 1, 1]);
        let m = heatmap(
            &three,
            &cells,
            &labels,
            &SweepScore::Fire,
            (1, 2),
            &fixed,
            "t".into(),
            None,
        );
        assert_eq!((m.xs.len(), m.ys.len()), (3, 3));
        assert!((m.z[2][0] - 0.57 / 3.0).abs() < 1e-12);
        assert!(fixed_at(&three, &[("table".into(), 0.9)]).is_err());
        assert!(map_axes(&three, Some("table,nope")).is_err());
        assert_eq!(
            map_axes(&three, Some("table,crown_angle")).unwrap(),
            vec![2, 0]
        );
    }

    #[test]
    fn shards_parse_and_come_from_job_arrays() {
        assert_eq!(
            Shard::parse("--shard", "2/3").unwrap(),
            Shard { k: 2, n: 3 }
        );
        for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
            assert!(Shard::parse("--shard", bad)
                .unwrap_err()
                .to_string()
                .starts_with("--shard:"));
        }
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| {
                pairs
                    .iter()
                    .find(|(n, _)| *n == k)
                    .map(|(_, v)| v.to_string())
            }
        };
        let slurm = env(&[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "4"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]);
        assert_eq!(
            Shard::from_env(&slurm).unwrap().unwrap().0,
            Shard { k: 2, n: 3 }
        );
        let k8s = env(&[("JOB_COMPLETION_INDEX", "0"), ("JOB_COMPLETION_COUNT", "4")]);
        assert_eq!(
            Shard::from_env(&k8s).unwrap().unwrap().0,
            Shard { k: 1, n: 4 }
        );
        let half = env(&[("JOB_COMPLETION_INDEX", "0")]);
        assert!(Shard::from_env(&half).is_err());
        assert!(Shard::from_env(&env(&[])).unwrap().is_none());
        assert_eq!(Shard { k: 2, n: 3 }.indices(8), vec![1, 4, 7]);
        assert_eq!(hash(b"a"), "af63dc4c8601ec8c");
    }
}
