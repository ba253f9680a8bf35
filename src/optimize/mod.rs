//! The optimizer: argmin searches over a cut space's parameters (a family's proportions,
//! through [`CutSpace`](crate::cut::CutSpace)), sweeps, and a photon-tracer verification of the
//! winners. It draws no charts and writes no pages: the plots and the report are drawn from
//! what it returns, by functions the caller hands it ([`ConvergenceChart`], [`HeatmapChart`],
//! [`ProfileChart`], [`ParetoChart`], [`RunPage`], a [`CutWriter`] for the diagram).
//!
//! Data flows one way:
//!
//! - `config/` reads an `optim/*.toml` file into a validated [`Config`] (every error names the
//!   file and the field), with the cut space it searches;
//! - `problem.rs` turns a parameter vector into a [`Cut`] (built by the space), scores it with
//!   an [`Evaluator`] and returns a finite cost: `−(weighted score) + constraint penalties`;
//! - `nelder_mead.rs` (multi-start from a seeded Latin hypercube or Halton set,
//!   `sampling.rs`) and `pso.rs` (particle swarm) run argmin's solvers on it, stopped by
//!   `guard.rs` on the evaluation budget or Ctrl-C;
//! - `history.rs` keeps every evaluation (Nelder–Mead) or every particle position (swarm) as
//!   rows of `history.csv`;
//! - `search.rs` runs the method, picks distinct winners and has a [`Verifier`] (the photon
//!   tracer's cross-check of [`crate::verify`]) re-score them, flagging any disagreement with
//!   the beam tracer beyond 4 standard errors;
//! - `summary.rs` is the run's summary, `report.json` and `report.md`; `run.rs` writes the run
//!   folder (config as used, history, charts, best cut, summary, page);
//! - `sweep.rs` maps a score over two parameters or draws the scores along one; `grid/`
//!   sweeps any number of axes, in shards (`--shard K/N`) that a merge joins exactly;
//!   `pareto.rs` traces the trade-off between scores;
//! - `ratio_search.rs` retargets a design to another index: the tangent-ratio rule of
//!   [`crate::cut::retarget`] and a search for the two ratios that restore its light return.
//!
//! It may import the floors below it (`verify` and everything under it), never `plan`,
//! `plot`, `report` or the binary.
//!
//! The modules are private; what a caller needs is re-exported here: the config and its
//! sections, the two scorers made from a config ([`BeamEvaluator`], [`PhotonVerifier`]),
//! [`search`], [`verify`] and [`run()`] with their [`Hooks`] and [`RunOptions`], the sweep
//! ([`sweep()`], [`write_sweep`], [`sweep_path`], and the one-parameter [`profile()`] with
//! [`write_profile`]), and the verification types.
//!
//! The objective and the verifier are traits so the searches can be tested on analytic
//! functions and wired to the tracers separately.
//!
//! # Bounds
//!
//! Particle swarm takes the bounds itself (argmin clamps positions to the box). Nelder–Mead has
//! no bounds of its own: it works in an unbounded reparametrisation, each free parameter being
//! `x = lo + (hi − lo) · sigmoid(u)`, so every point it can ever propose is inside the box and
//! the cost stays smooth (no flat clamped regions that would stall the simplex).
//!
//! # Example
//!
//! ```
//! use facetlab::optimize::{search, Config, Evaluator, Hooks, ScoreSet};
//! use facetlab::cut::Cut;
//!
//! /// A smooth bump with its top at crown 34.5°, pavilion 40.8°.
//! struct Bump;
//! impl Evaluator for Bump {
//!     fn evaluate(&self, cut: &Cut) -> facetlab::Result<ScoreSet> {
//!         let (c, p) = (cut.params["crown_angle"], cut.params["pavilion_angle"]);
//!         let b = (-((c - 34.5) / 3.0).powi(2) - ((p - 40.8) / 1.0).powi(2)).exp();
//!         Ok(ScoreSet::new(b, 0.0, 0.0))
//!     }
//! }
//!
//! let text = r#"
//!     [cut]
//!     family = "round-brilliant"
//!     [free]
//!     crown_angle = [30.0, 38.0]
//!     pavilion_angle = [39.0, 42.5]
//!     [method]
//!     name = "nelder-mead"
//!     starts = 2
//!     max_evaluations = 200
//! "#;
//! let config = Config::from_str(text, "doc.toml").unwrap();
//! let outcome = search(&config, &Bump, &Hooks::default()).unwrap();
//! let best = &outcome.best().params;
//! assert!((best["crown_angle"] - 34.5).abs() < 0.1);
//! assert!((best["pavilion_angle"] - 40.8).abs() < 0.05);
//! ```

mod config;
mod engines;
mod grid;
mod guard;
mod history;
mod nelder_mead;
mod pareto;
mod problem;
mod pso;
mod ratio_search;
mod run;
mod sampling;
mod search;
mod summary;
mod sweep;

// The public surface. Everything else (the solvers, the problem wrappers, the start samples,
// the history and summary rows) is internal: reach it through these.

// Configs: the validated `Config`, its sections, and the file as written (`RawConfig`).
pub use config::{
    axis_label, defaults, Budget, Config, Constraints, FreeParam, Method, NelderMeadSettings,
    ParetoSpec, RawConfig, RawConstraints, RawCut, RawMethod, RawObjective, RawScore, RawVerify,
    Sampling, ScoreSettings, SwarmSettings, VerifySettings, Weights,
};
// The scorers of a config: the beam tracer's evaluator and the photon tracer's verifier.
pub use engines::{real_scorers, BeamEvaluator, PhotonVerifier, Scorers};
// Progress reports and why a search stopped.
pub use guard::{Progress, Status, Stop};
// Searches and run folders: `search` then `verify`, or both and the folder: `run`.
pub use run::{
    design_json, new_run_dir, run, run_files, ConvergenceChart, CutWriter, FnWriter, GemWriter,
    RunOptions, RunPage, RunSummary, TOML_WRITER,
};
pub use search::{search, verify, Hooks, Outcome};
// The trade-off between scores (`[objective] pareto`).
pub use pareto::{non_dominated, run_pareto, weight_grid, FrontPoint, ParetoChart, ParetoOutcome};
// Adapting a design to another index (tangent ratio, and its optimized variant).
pub use ratio_search::{retarget, Retarget, Variant};
// What a run keeps and reports.
pub use history::{History, Row, Track};
// The cost of a cut that cannot be built or scored.
pub use problem::{weight_retention, FAILED_COST};
// The run's summary (`report.json`, `report.md`): the start and the winners, how it went.
pub use summary::{Candidate, DesignJson, FoundAt, OpenedJson, Report};
// Sweeps: a score mapped over two parameters, or the scores along one (a profile).
pub use sweep::{
    output_paths as sweep_output_paths, profile, run_path as sweep_path, sweep,
    write as write_sweep, write_profile, Axis, Cell, Heatmap, HeatmapChart, Point, Profile,
    ProfileChart, ProfileLines, Sweep, SweepScore,
};
// N-axis sweeps, their shards (`--shard K/N`, job arrays) and the exact merge.
pub use grid::{
    assemble as assemble_shards, best as grid_best, evaluate as evaluate_grid, fixed_at,
    hash as config_hash, heatmap as grid_heatmap, map_axes, parse_at, profile_lines, read_rows,
    rows_header, shard_folder, shard_row, to_csv as grid_csv, AxisRecord, Grid, GridCell, Shard,
    ShardRecord, ShardRun,
};
// The photon-tracer check of the winners (all of it `crate::verify`'s).
pub use crate::verify::{Verification, Verifier, VerifyReport, VerifyRow};

use crate::cut::Cut;
use crate::error::Result;
pub use crate::metrics::ScoreName;
use serde::Serialize;

/// The scores of one cut, as the optimizer sees them.
///
/// `brilliance`, `fire` and `scintillation` are the objective's terms (each roughly in [0, 1],
/// higher is better). `extra` holds any further named scores the evaluator computes (ASET
/// shares, …); they are shown in the reports but not optimized.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ScoreSet {
    /// Light return under diffuse light.
    pub brilliance: f64,
    /// Colour seen under small light sources.
    pub fire: f64,
    /// How the face-up pattern changes as the stone tilts.
    pub scintillation: f64,
    /// Further named scores, shown in reports in this order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub extra: Vec<(ScoreName, f64)>,
    /// The beam tracer's whole scores behind these, when the evaluator keeps them
    /// ([`BeamEvaluator`]'s full evaluations do): a run's report draws its table and tilt chart
    /// from them instead of scoring the cut again. Not serialised.
    #[serde(skip)]
    pub detail: Option<std::sync::Arc<crate::metrics::Scores>>,
}

impl ScoreSet {
    /// The three objective scores, no extras.
    pub fn new(brilliance: f64, fire: f64, scintillation: f64) -> ScoreSet {
        ScoreSet {
            brilliance,
            fire,
            scintillation,
            extra: Vec::new(),
            detail: None,
        }
    }

    /// The score `name` (`brilliance`, `fire`, `scintillation` or an extra), if this set has it.
    pub fn get(&self, name: ScoreName) -> Option<f64> {
        match name {
            ScoreName::Brilliance => Some(self.brilliance),
            ScoreName::Fire => Some(self.fire),
            ScoreName::Scintillation => Some(self.scintillation),
            _ => self.extra.iter().find(|(k, _)| *k == name).map(|(_, v)| *v),
        }
    }

    /// Every score, name and value, the three objective scores first.
    pub fn all(&self) -> Vec<(ScoreName, f64)> {
        let mut out = vec![
            (ScoreName::Brilliance, self.brilliance),
            (ScoreName::Fire, self.fire),
            (ScoreName::Scintillation, self.scintillation),
        ];
        out.extend(self.extra.iter().cloned());
        out
    }
}

/// The objective's scorer: a cut in, its scores out.
///
/// It must be deterministic (same cut, same scores) so that runs repeat, and `Sync`, because
/// particle swarms and multi-start searches evaluate cuts on several threads. An `Err` is not
/// fatal: the optimizer gives that cut a finite penalty cost and moves on.
pub trait Evaluator: Sync {
    /// Score one cut, every score.
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet>;

    /// Score one cut for the search: the scores the objective weighs must be right; the
    /// others may be left out as NaN (they weigh 0). The start and the winners are scored
    /// again with [`Evaluator::evaluate`] for the reports. By default the same as `evaluate`.
    fn evaluate_for_search(&self, cut: &Cut) -> Result<ScoreSet> {
        self.evaluate(cut)
    }
}

impl<F> Evaluator for F
where
    F: Fn(&Cut) -> Result<ScoreSet> + Sync,
{
    fn evaluate(&self, cut: &Cut) -> Result<ScoreSet> {
        self(cut)
    }
}

#[cfg(test)]
mod tests;
