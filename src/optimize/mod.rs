//! The optimizer: argmin searches over a cut space's parameters (a family's proportions,
//! through [`CutSpace`](crate::cut::CutSpace)) and a photon-tracer verification of the
//! winners. It draws no charts and writes no pages: the plots and the report are drawn from
//! what it returns, by functions the caller hands it ([`ConvergenceChart`], [`ParetoChart`],
//! [`RunPage`], a [`CutWriter`] for the diagram). Sweeps and grids over a config's
//! parameters are the room above it, [`crate::sweep`].
//!
//! Data flows one way:
//!
//! - `config/` reads an `optim/*.toml` file into a validated [`Config`] (every error names the
//!   file and the field), with the cut space it searches;
//! - `config/search_box.rs` is the box a search moves in ([`SearchBox`]): the free parameters
//!   and the space that builds the cut at a point of it;
//! - `problem.rs` holds the objective: it turns a point of the box into a
//!   [`Cut`](crate::cut::Cut), scores it with an [`Evaluator`] (`evaluator.rs`; the scores are
//!   a [`ScoreSet`], `score_set.rs`) and returns a finite cost: `−(weighted score) +
//!   constraint penalties`;
//! - `nelder_mead.rs` (multi-start from a seeded Latin hypercube or Halton set,
//!   `sampling.rs`) and `pso.rs` (particle swarm) run argmin's solvers on it, each method
//!   holding its own settings, budget and seed; `guard.rs` stops them on the evaluation
//!   budget or Ctrl-C;
//! - `history.rs` keeps every evaluation (Nelder–Mead) or every particle position (swarm) as
//!   rows of `history.csv`;
//! - `search.rs` runs the method, picks distinct winners and has a [`Verifier`] (the photon
//!   tracer's cross-check of [`crate::verify`]) re-score them, flagging any disagreement with
//!   the beam tracer beyond 4 standard errors;
//! - `summary.rs` is the run's summary, `report.json` and `report.md`; `run.rs` writes the run
//!   folder (config as used, history, charts, best cut, summary, page);
//! - `pareto.rs` traces the trade-off between scores;
//! - `ratio_search.rs` retargets a design to another index: the tangent-ratio rule of
//!   [`crate::cut::retarget`] and a search for the two ratios that restore its light return.
//!
//! It may import the floors below it (`verify` and everything under it), never `sweep`,
//! `plan`, `plot`, `report` or the binary.
//!
//! The modules are private; what a caller needs is re-exported here: the config and its
//! sections, the two scorers made from a config ([`BeamEvaluator`], [`PhotonVerifier`]),
//! [`search`], [`verify`] and [`run()`] with their [`Hooks`] and [`RunOptions`], the objective
//! a sweep maps ([`objective_of`]), and the verification types.
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
mod evaluator;
mod guard;
mod history;
mod nelder_mead;
mod pareto;
mod problem;
mod pso;
mod ratio_search;
mod run;
mod sampling;
mod score_set;
mod search;
mod slopes;
mod summary;

// The public surface. Everything else (the solvers, the problem wrappers, the start samples,
// the history and summary rows) is internal: reach it through these.

// Configs: the validated `Config`, its sections, and the file as written (`RawConfig`).
pub use config::{
    axis_label, defaults, Budget, Config, Constraints, FreeParam, Method, NelderMeadSettings,
    ParetoSpec, RawConfig, RawConstraints, RawCut, RawMethod, RawObjective, RawScore, RawVerify,
    Sampling, ScoreSettings, SearchBox, SwarmSettings, VerifySettings, Weights, MEETS_LISTING,
};
// The scores of one cut and the scorer the objective calls.
pub use evaluator::Evaluator;
pub use score_set::ScoreSet;
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
pub use slopes::{tier_slopes, TierSlope};
// The trade-off between scores (`[objective] pareto`).
pub use pareto::{non_dominated, run_pareto, weight_grid, FrontPoint, ParetoChart, ParetoOutcome};
// Adapting a design to another index (tangent ratio, and its optimized variant).
pub use ratio_search::{retarget, Retarget, Variant};
// What a run keeps and reports.
pub use history::{History, Row, Track};
// The cost of a cut that cannot be built or scored.
pub use problem::{objective_of, weight_retention, FAILED_COST};
// The run's summary (`report.json`, `report.md`): the start and the winners, how it went.
pub use summary::{Candidate, DesignJson, FoundAt, OpenedJson, RunReport};
// The photon-tracer check of the winners (all of it `crate::verify`'s).
pub use crate::verify::{Verification, Verifier, VerifyReport, VerifyRow};
// The names of the scores (all of them `crate::metrics`').
pub use crate::metrics::ScoreName;

#[cfg(test)]
mod tests;
