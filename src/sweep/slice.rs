//! Views of an N-axis grid: the one or two axes mapped (`--map`), the others held at grid
//! values (`--at KEY=VALUE`, default the middle of each axis), as a heatmap or as the scores
//! along one axis.

use super::map::{Heatmap, ProfileLines, SweepScore, SCORES};
use super::points::{Grid, GridCell};
use crate::error::{Error, Result};

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
                "slice point",
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
                "slice point",
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
                .ok_or_else(|| Error::invalid("slice point", format!("`{s}` is not KEY=VALUE")))?;
            let v: f64 = v.trim().parse().map_err(|_| {
                Error::invalid("slice point", format!("`{v}` in `{s}` is not a number"))
            })?;
            Ok((k.trim().to_string(), v))
        })
        .collect()
}

/// A swept grid and its scores: the grid, every cell of it in grid order, and the axes'
/// labels (as a sweep names them, or as its shards recorded them).
#[derive(Clone, Copy, Debug)]
pub struct Swept<'a> {
    /// The grid.
    pub grid: &'a Grid,
    /// Every cell, in grid order.
    pub cells: &'a [GridCell],
    /// The axes' labels, in axis order.
    pub labels: &'a [String],
}

/// What a map shows: the mapped axes (one: a profile; two: a heatmap) and where the others
/// are held (value indices; see [`fixed_at`]).
#[derive(Clone, Debug, PartialEq)]
pub struct MapSpec {
    /// The mapped axes (indices into the grid's axes).
    pub axes: Vec<usize>,
    /// Every axis' held value index (the mapped axes' are not used).
    pub fixed: Vec<usize>,
}

impl MapSpec {
    /// The map of `map` (`KEY1[,KEY2]`, see [`map_axes`]) with the other axes held at `at`
    /// (`KEY=VALUE` each, see [`fixed_at`]).
    pub fn new(grid: &Grid, map: Option<&str>, at: &[String]) -> Result<MapSpec> {
        let axes = map_axes(grid, map)?;
        let fixed = fixed_at(grid, &parse_at(at)?)?;
        Ok(MapSpec { axes, fixed })
    }
}

impl Swept<'_> {
    /// A heatmap of `score` over the axes `mx`, `my` with the others at `fixed` (value
    /// indices; see [`fixed_at`]), with an optimizer's `path` drawn on it.
    pub fn heatmap(
        &self,
        score: &SweepScore,
        (mx, my): (usize, usize),
        fixed: &[usize],
        title: String,
        path: Option<Vec<(f64, f64)>>,
    ) -> Heatmap {
        let (grid, cells, labels) = (self.grid, self.cells, self.labels);
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
    pub fn profile_lines(&self, ax: usize, fixed: &[usize], title: String) -> ProfileLines {
        let (grid, cells, labels) = (self.grid, self.cells, self.labels);
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
}

/// The map axes from `--map KEY1[,KEY2]` (default: the first two axes).
pub fn map_axes(grid: &Grid, map: Option<&str>) -> Result<Vec<usize>> {
    let Some(m) = map else {
        return Ok((0..grid.axes.len().min(2)).collect());
    };
    let keys: Vec<&str> = m.split(',').map(str::trim).collect();
    if keys.is_empty() || keys.len() > 2 {
        return Err(Error::invalid(
            "map axes",
            format!("`{m}` is not KEY1,KEY2 (or one KEY for a profile)"),
        ));
    }
    let mut out = Vec::new();
    for k in &keys {
        let Some(i) = grid.axis(k) else {
            let all: Vec<&str> = grid.axes.iter().map(|a| a.key.as_str()).collect();
            return Err(Error::invalid(
                "map axes",
                format!(
                    "`{k}` is not an axis of this sweep; axes: {}",
                    all.join(", ")
                ),
            ));
        };
        if out.contains(&i) {
            return Err(Error::invalid(
                "map axes",
                format!("`{k}` twice; give two different axes"),
            ));
        }
        out.push(i);
    }
    Ok(out)
}
