//! The search history: one row per evaluated point, written as `history.csv`.
//!
//! Columns: `start` (Nelder–Mead: which start, from 0) or `particle` (swarm: which particle,
//! from 0), `iteration` (0 = the initial simplex or swarm), `evaluations` (the running count of
//! evaluations over the whole run; Nelder–Mead starts are counted one after another in start
//! order, whatever ran in parallel), `cost` (of this point), `best_cost` (lowest cost so far:
//! within this start for Nelder–Mead, over the swarm for particle swarm), then one column per
//! free parameter (the point itself).
//!
//! Numbers are written in Rust's shortest round-trip form, so the file reads back to the same
//! bits and two runs with the same seed give byte-identical files.

use crate::error::{Error, Result};
use argmin::core::observers::Observe;
use argmin::core::{Error as ArgminError, PopulationState, State, KV};
use argmin::solver::particleswarm::Particle;
use std::fmt::Write;
use std::sync::{Arc, Mutex};

/// Whether rows belong to Nelder–Mead starts or swarm particles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Track {
    /// Rows are Nelder–Mead evaluations; `track` is the start.
    Start,
    /// Rows are particle positions; `track` is the particle.
    Particle,
}

impl Track {
    /// The first column's name.
    pub fn column(self) -> &'static str {
        match self {
            Track::Start => "start",
            Track::Particle => "particle",
        }
    }
}

/// One evaluated point.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Start or particle number.
    pub track: usize,
    /// Iteration (0 = initial simplex or swarm).
    pub iteration: u64,
    /// Running evaluation count over the run.
    pub evaluations: u64,
    /// Cost of this point.
    pub cost: f64,
    /// Lowest cost so far (within the start, or over the swarm).
    pub best_cost: f64,
    /// The free parameters.
    pub x: Vec<f64>,
}

/// A search history.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// Starts or particles.
    pub track: Track,
    /// Free parameter keys (the last columns).
    pub keys: Vec<String>,
    /// Rows in order.
    pub rows: Vec<Row>,
}

impl History {
    /// An empty history.
    pub fn new(track: Track, keys: Vec<String>) -> History {
        History {
            track,
            keys,
            rows: Vec::new(),
        }
    }

    /// The CSV text.
    pub fn to_csv(&self) -> String {
        let mut o = String::new();
        let _ = write!(
            o,
            "{},iteration,evaluations,cost,best_cost",
            self.track.column()
        );
        for k in &self.keys {
            let _ = write!(o, ",{k}");
        }
        o.push('\n');
        for r in &self.rows {
            let _ = write!(
                o,
                "{},{},{},{},{}",
                r.track, r.iteration, r.evaluations, r.cost, r.best_cost
            );
            for v in &r.x {
                let _ = write!(o, ",{v}");
            }
            o.push('\n');
        }
        o
    }

    /// Read a `history.csv`; `source` names the file in errors.
    pub fn from_csv(text: &str, source: &str) -> Result<History> {
        let mut lines = text.lines().enumerate();
        let Some((_, head)) = lines.next() else {
            return Err(Error::parse(
                source,
                "empty file; expected a history.csv header",
            ));
        };
        let cols: Vec<&str> = head.split(',').map(str::trim).collect();
        let track = match cols.first().copied() {
            Some("start") => Track::Start,
            Some("particle") => Track::Particle,
            _ => {
                return Err(Error::parse(
                    format!("{source}:1"),
                    "not a history.csv: the first column must be `start` or `particle`",
                ))
            }
        };
        if cols.len() < 5 || cols[1..5] != ["iteration", "evaluations", "cost", "best_cost"] {
            return Err(Error::parse(
                format!("{source}:1"),
                "not a history.csv: expected columns iteration,evaluations,cost,best_cost after the first",
            ));
        }
        let keys: Vec<String> = cols[5..].iter().map(|s| s.to_string()).collect();
        let mut h = History::new(track, keys);
        for (i, line) in lines {
            if line.trim().is_empty() {
                continue;
            }
            let at = format!("{source}:{}", i + 1);
            let f: Vec<&str> = line.split(',').map(str::trim).collect();
            if f.len() != cols.len() {
                return Err(Error::parse(
                    at,
                    format!("{} fields, expected {}", f.len(), cols.len()),
                ));
            }
            let int = |s: &str| {
                s.parse::<u64>()
                    .map_err(|_| Error::parse(&at, format!("`{s}` is not a whole number")))
            };
            let num = |s: &str| {
                s.parse::<f64>()
                    .map_err(|_| Error::parse(&at, format!("`{s}` is not a number")))
            };
            h.rows.push(Row {
                track: int(f[0])? as usize,
                iteration: int(f[1])?,
                evaluations: int(f[2])?,
                cost: num(f[3])?,
                best_cost: num(f[4])?,
                x: f[5..].iter().map(|s| num(s)).collect::<Result<_>>()?,
            });
        }
        Ok(h)
    }

    /// The path of the best point: each point that lowered the run's best cost, in order. For
    /// Nelder–Mead only the start that found the overall best is followed (other starts' paths
    /// would cross it); for a swarm, the swarm's best.
    pub fn best_path(&self) -> Vec<Vec<f64>> {
        let rows: Vec<&Row> = match self.track {
            Track::Particle => self.rows.iter().collect(),
            Track::Start => {
                let Some(win) = self.best_row() else {
                    return Vec::new();
                };
                self.rows.iter().filter(|r| r.track == win.track).collect()
            }
        };
        let mut best = f64::INFINITY;
        let mut out = Vec::new();
        for r in rows {
            if r.cost < best {
                best = r.cost;
                out.push(r.x.clone());
            }
        }
        out
    }

    /// The row with the lowest cost (the first such).
    pub fn best_row(&self) -> Option<&Row> {
        self.rows.iter().fold(None, |b: Option<&Row>, r| match b {
            Some(b) if b.cost <= r.cost => Some(b),
            _ => Some(r),
        })
    }

    /// The number of tracks (starts or particles).
    pub fn tracks(&self) -> usize {
        self.rows.iter().map(|r| r.track + 1).max().unwrap_or(0)
    }
}

/// An argmin observer that records every particle of a swarm after each iteration, into a
/// shared history (keep a clone of the `Arc` to read it after the run).
pub struct SwarmObserver {
    /// The history being filled.
    pub history: Arc<Mutex<History>>,
}

impl SwarmObserver {
    fn record(&self, iteration: u64, particles: Option<&Vec<Particle<Vec<f64>, f64>>>) {
        let Some(ps) = particles else { return };
        let mut h = match self.history.lock() {
            Ok(g) => g,
            Err(p) => p.into_inner(),
        };
        let mut best = h.rows.last().map(|r| r.best_cost).unwrap_or(f64::INFINITY);
        let first = h.rows.last().map(|r| r.evaluations).unwrap_or(0) + 1;
        for (evals, (i, p)) in (first..).zip(ps.iter().enumerate()) {
            best = best.min(p.cost);
            h.rows.push(Row {
                track: i,
                iteration,
                evaluations: evals,
                cost: p.cost,
                best_cost: best,
                x: p.position.clone(),
            });
        }
    }
}

type SwarmState = PopulationState<Particle<Vec<f64>, f64>, f64>;

impl Observe<SwarmState> for SwarmObserver {
    fn observe_init(
        &mut self,
        _name: &str,
        state: &SwarmState,
        _kv: &KV,
    ) -> std::result::Result<(), ArgminError> {
        self.record(0, state.get_population());
        Ok(())
    }

    fn observe_iter(
        &mut self,
        state: &SwarmState,
        _kv: &KV,
    ) -> std::result::Result<(), ArgminError> {
        // argmin observes before it increments the iteration counter: the first iteration
        // after the initial swarm is reported as 0.
        self.record(state.get_iter() + 1, state.get_population());
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_round_trips_exactly_and_finds_the_best_path() {
        let mut h = History::new(Track::Start, vec!["crown_angle".into(), "table".into()]);
        let pts = [
            (0, 1.0, [30.0, 0.5]),
            (0, 0.5, [31.0, 0.51]),
            (0, 0.7, [32.0, 0.52]),
            (0, 0.1 + 0.2, [33.1, 0.53]),
            (1, 0.2, [35.0, 0.6]),
            (1, -0.25, [36.0, 0.61]),
            (1, 0.0, [37.0, 0.62]),
        ];
        let mut best = [f64::INFINITY; 2];
        for (i, (t, c, x)) in pts.iter().enumerate() {
            best[*t] = best[*t].min(*c);
            h.rows.push(Row {
                track: *t,
                iteration: i as u64 / 2,
                evaluations: i as u64 + 1,
                cost: *c,
                best_cost: best[*t],
                x: x.to_vec(),
            });
        }
        let csv = h.to_csv();
        assert!(csv.starts_with("start,iteration,evaluations,cost,best_cost,crown_angle,table\n"));
        let back = History::from_csv(&csv, "h.csv").unwrap();
        assert_eq!(back, h);
        assert_eq!(back.to_csv(), csv);
        assert_eq!(h.tracks(), 2);
        assert_eq!(h.best_row().unwrap().cost, -0.25);
        assert_eq!(h.best_path(), vec![vec![35.0, 0.6], vec![36.0, 0.61]]);
        let e = History::from_csv("a,b\n", "x.csv").unwrap_err().to_string();
        assert!(e.starts_with("x.csv:1: not a history.csv"), "{e}");
        let bad = csv.replace("33.1", "abc");
        let e = History::from_csv(&bad, "h.csv").unwrap_err().to_string();
        assert!(e.starts_with("h.csv:5: `abc` is not a number"), "{e}");
    }
}
