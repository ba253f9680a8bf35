//! Optimization configs (`optim/*.toml`): parsed with unknown keys refused, then validated into
//! typed settings. Every error is one line naming the file and the field, e.g.
//! `round.toml: free.table: bounds [0.8, 0.5] are reversed; write [min, max]`.
//!
//! ```toml
//! name = "round-brilliance"          # run folder prefix; default: the file's stem
//! seed = 1                           # every random choice (start points, swarm) follows it
//!
//! [cut]
//! family = "round-brilliant"
//! [cut.params]                       # the start cut; missing keys take the family's defaults
//! girdle = 0.03
//!
//! [free]                             # what the optimizer varies: key = [min, max]
//! crown_angle = [30.0, 38.0]
//! pavilion_angle = [39.0, 42.5]
//!
//! [objective]                        # score = Σ weight · score; cost = −score + penalties
//! brilliance = 1.0
//!
//! [constraints]
//! total_depth = [0.56, 0.64]
//!
//! [method]
//! name = "nelder-mead"
//! starts = 4
//! max_evaluations = 400
//!
//! [verify]
//! winners = 3
//! photons = 100000
//! ```
//!
//! The full list of fields with their defaults is the config-file table in `docs/optimize.md`
//! (section "The config file").
//!
//! `file.rs` holds the file as a whole: [`RawConfig`] as written and [`Config`] as validated.
//! Each section has its own file with its raw form, its validated form and its validator
//! (`cut.rs`, `free.rs`, `objective.rs`, `constraints.rs`, `method.rs`, `verify.rs`,
//! `score.rs`); [`Config::from_raw`] runs them in the file's order. `search_box.rs` is the box
//! a validated config's search moves in ([`Config::search_box`]).

mod constraints;
mod cut;
mod fields;
mod file;
mod free;
mod meets;
mod method;
mod objective;
mod score;
mod search_box;
mod verify;

pub use constraints::{Constraints, RawConstraints};
pub use cut::RawCut;
pub use fields::defaults;
pub use file::{Config, RawConfig};
pub use free::{axis_label, FreeParam, OPTIC_AXIS};
pub use meets::MEETS_LISTING;
pub use method::{Budget, Method, NelderMeadSettings, RawMethod, Sampling, SwarmSettings};
pub use objective::{ParetoSpec, RawObjective, Weights};
pub use score::{RawScore, ScoreSettings};
pub use search_box::SearchBox;
pub use verify::{RawVerify, VerifySettings};
