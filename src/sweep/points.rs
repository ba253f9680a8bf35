//! The grid's points: the [`Grid`] (its axes, its order, a point's values), a point's
//! scores ([`GridCell`]), their evaluation in parallel and the sweep's CSV.

use super::map::{score_point, Axis, SweepScore, MAX_POINTS, SCORES};
use crate::error::{setting, Error, Result};
use crate::metrics::ScoreName;
use crate::optimize::{Config, Evaluator, ScoreSet};
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
                format!(
                    "give at least one axis: {} KEY:MIN:MAX:STEP (or {})",
                    setting("first axis"),
                    setting("grid axes")
                ),
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

pub(super) fn num(v: f64) -> String {
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
