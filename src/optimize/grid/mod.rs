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
//!
//! The rooms: `mod.rs` holds the grid, its evaluation and its CSV; `shard.rs` a shard's
//! share, its row file, its record (`shard.json`) and the merge's check that the shards cover
//! the grid once; `resume.rs` a shard run into its folder, resumably ([`ShardRun`]);
//! `slice.rs` the views of an N-axis grid (the axes mapped, the others held at
//! `--at` values): heatmaps and profiles.

mod resume;
mod shard;
mod slice;

pub use resume::{shard_folder, ShardRun};
pub use shard::{
    assemble, hash, read_rows, rows_header, shard_row, AxisRecord, Shard, ShardRecord,
};
pub use slice::{fixed_at, heatmap, map_axes, parse_at, profile_lines};

use super::sweep::{score_point, Axis, SweepScore, MAX_POINTS, SCORES};
use super::{Config, Evaluator, ScoreName, ScoreSet};
use crate::error::{Error, Result};
use rayon::prelude::*;
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
                "first axis",
                "give at least one axis: --x KEY:MIN:MAX:STEP (or --axis)",
            ));
        }
        for (i, a) in axes.iter().enumerate() {
            if axes[..i].iter().any(|b| b.key == a.key) {
                return Err(Error::invalid(
                    "grid axes",
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
                "grid axes",
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
    let extras: Vec<ScoreName> = cells
        .iter()
        .find_map(|c| c.scores.as_ref())
        .map(|s| s.extra.iter().map(|(k, _)| *k).collect())
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
            let v = c.scores.as_ref().and_then(|sc| sc.get(*e));
            let _ = write!(o, ",{}", num(v.unwrap_or(f64::NAN)));
        }
        o.push('\n');
    }
    o
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
        s.extra.push((crate::metrics::ScoreName::AsetRed, a / 7.0));
        Ok(s)
    }

    #[test]
    fn order_shards_rows_and_merge_agree_with_the_two_axis_sweep() {
        let c = cfg();
        let x = Axis::parse("x axis", "crown_angle:33:36:1", &c).unwrap();
        let y = Axis::parse("y axis", "pavilion_angle:40:41:0.5", &c).unwrap();
        let t = Axis::parse("axis", "table:0.55:0.57:0.01", &c).unwrap();
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
            &SweepScore::FIRE,
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
        assert_eq!(Shard::parse("shard", "2/3").unwrap(), Shard { k: 2, n: 3 });
        for bad in ["0/3", "4/3", "3", "a/b", "1/0"] {
            assert!(Shard::parse("shard", bad)
                .unwrap_err()
                .to_string()
                .starts_with("shard:"));
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
