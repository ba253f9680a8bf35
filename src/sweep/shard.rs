//! Shards of an N-axis sweep (`--shard K/N`): which points a shard owns, the line each
//! finished point appends to `rows.csv` and how it is read back, the shard's record
//! (`shard.json`), and the merge's check that the shards cover the grid exactly once.

use super::map::{Axis, SCORES};
use super::points::{num, Grid, GridCell};
use crate::error::{setting, Error, Result};
use crate::metrics::ScoreName;
use crate::optimize::ScoreSet;
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// The header of a shard's `rows.csv`.
pub fn rows_header(grid: &Grid) -> String {
    let keys: Vec<&str> = columns(grid).collect();
    format!("index,{},extras\n", keys.join(","))
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

/// Read a line of `rows.csv` back (without its newline) for `grid`: its columns by name, as
/// [`GridCell::from_named`] takes them.
pub fn parse_shard_row(line: &str, grid: &Grid) -> Option<GridCell> {
    let f: Vec<&str> = line.split(',').collect();
    let n = grid.axes.len();
    if f.len() != 1 + n + 4 + 1 {
        return None;
    }
    let index: usize = f[0].parse().ok()?;
    let mut values = columns(grid)
        .zip(&f[1..5 + n])
        .map(|(k, v)| Some((k.to_string(), v.parse().ok()?)))
        .collect::<Option<Vec<(String, f64)>>>()?;
    let ok = f[5 + n] != "-";
    if ok {
        for p in f[5 + n].split(';').filter(|p| !p.is_empty()) {
            let (k, v) = p.split_once('=')?;
            values.push((k.to_string(), v.parse().ok()?));
        }
    }
    GridCell::from_named(grid, index, ok, &values).ok()
}

/// Values by name: a row's columns, or its extra scores.
pub type Named = Vec<(String, f64)>;

/// The named columns of a row of `rows.csv` between its index and its extras: each axis's key,
/// then the four scores (`brilliance`, `fire`, `scintillation`, `objective`).
fn columns(grid: &Grid) -> impl Iterator<Item = &str> {
    grid.axes
        .iter()
        .map(|a| a.key.as_str())
        .chain(SCORES.iter().map(|s| s.name()))
}

impl GridCell {
    /// The row by name, with the values `rows.csv` holds (a score that is not finite is NaN):
    /// each axis's value under its key and the four scores (`brilliance`, `fire`,
    /// `scintillation`, `objective`); then the extra scores apart, or None for a cut that
    /// failed (its line's `-`).
    pub fn named(&self, grid: &Grid) -> (Named, Option<Named>) {
        let as_written = |v: f64| if v.is_finite() { v } else { f64::NAN };
        let fixed = columns(grid)
            .map(str::to_string)
            .zip(
                self.values
                    .iter()
                    .copied()
                    .chain(SCORES.iter().map(|s| as_written(self.value(s)))),
            )
            .collect();
        let extras = self.scores.as_ref().map(|s| {
            s.extra
                .iter()
                .map(|(k, v)| (k.to_string(), as_written(*v)))
                .collect()
        });
        (fixed, extras)
    }

    /// The cell of grid point `index` from its values by name (what [`GridCell::named`] gives,
    /// in any order): every axis's and the four scores'; with `ok` (the cut was scored) every
    /// other key is an extra score, kept in the order given. `Err` names a missing key, a key
    /// that is no score, or an index outside the grid.
    pub fn from_named(
        grid: &Grid,
        index: usize,
        ok: bool,
        values: &[(String, f64)],
    ) -> std::result::Result<GridCell, String> {
        if index >= grid.len() {
            return Err(format!(
                "index {index} is not a point of the grid (0 to {})",
                grid.len().saturating_sub(1)
            ));
        }
        let get = |k: &str| {
            values
                .iter()
                .find(|(key, _)| key == k)
                .map(|(_, v)| *v)
                .ok_or_else(|| format!("a row has no `{k}`"))
        };
        let fixed = columns(grid)
            .map(get)
            .collect::<std::result::Result<Vec<f64>, String>>()?;
        let n = grid.axes.len();
        let scores = if ok {
            let mut s = ScoreSet::new(fixed[n], fixed[n + 1], fixed[n + 2]);
            let named: Vec<&str> = columns(grid).collect();
            for (k, v) in values.iter().filter(|(k, _)| !named.contains(&k.as_str())) {
                let name = ScoreName::from_key(k).ok_or_else(|| format!("`{k}` is not a score"))?;
                s.extra.push((name, *v));
            }
            Some(s)
        } else {
            None
        };
        Ok(GridCell {
            index,
            values: fixed[..n].to_vec(),
            scores,
            objective: fixed[n + 3],
        })
    }
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
        match parse_shard_row(body, grid) {
            Some(c) => cells.push(c),
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
                    format!(
                        "is not set, but SLURM_ARRAY_TASK_ID is; give {} K/N",
                        setting("shard")
                    ),
                )
            })?;
            // `--array` is Slurm's own flag (sbatch), not facetlab's: kept as Slurm spells it.
            if let Some(step) = int("SLURM_ARRAY_TASK_STEP")? {
                if step != 1 {
                    return Err(Error::invalid(
                        "SLURM_ARRAY_TASK_STEP",
                        format!("is {step}; shards need a contiguous array (--array=0-N or 1-N), or give {} K/N", setting("shard")),
                    ));
                }
            }
            if id < min || id - min >= count {
                return Err(Error::invalid(
                    "SLURM_ARRAY_TASK_ID",
                    format!("{id} is outside MIN {min} .. MIN + COUNT {count}; the array must be contiguous, or give {} K/N", setting("shard")),
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
                    format!(
                        "is not set, but JOB_COMPLETION_INDEX is; set it to the Job's completions in the manifest, or give {} K/N",
                        setting("shard")
                    ),
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
pub fn config_hash(bytes: &[u8]) -> String {
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
