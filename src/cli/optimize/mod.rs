//! `optimize` and `sweep`: flags, progress bars, Ctrl-C and SIGTERM, the checks of the output
//! folder before any work, and the summary printed at the end.
//!
//! Both take the objective's scorer as an [`Evaluator`] (and `optimize` the photon tracer as a
//! [`Verifier`]), so the command line stays thin and the scorers are wired in one place. `run.rs`
//! is `optimize` (a run folder, or a trade-off with `[objective] pareto`), `print.rs` its summary
//! lines; `sweep.rs` is `sweep` and its shards.

mod print;
mod run;
mod sweep;

use super::progress::bar;
pub use facetlab::optimize::{real_scorers, Scorers};
use run::{install_ctrl_c, STOP};
pub use run::{run_optimize, OptimizeArgs};
pub(crate) use sweep::{choose_shard, write_sweep_outputs, Names};
pub use sweep::{run_sweep, SweepArgs};

#[cfg(test)]
mod tests;
