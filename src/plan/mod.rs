//! Rough planning: the largest, best cut inside a rough stone (issue 26, `facetlab plan`).
//!
//! - the rough ([`Rough`]): the convex hull of a closed scanned mesh (OBJ/STL, millimetres) or
//!   a bundled crystal form ([`CRYSTALS`]), as half-spaces, with how much volume the hull adds
//!   to a mesh that is not convex ([`Rough::hull_excess`]);
//! - containment ([`largest_copy`]): for one orientation and one set of proportions, the
//!   largest copy of a cut inside the rough is a linear program in the scale and the
//!   translation, reduced exactly to one constraint per rough plane by the cut's support
//!   numbers and solved by an active-set simplex;
//! - the search ([`Planner::plan_family`]): orientation (a rotation vector in the rough's
//!   principal frame) and the free parameters of a family within the config's bounds, by
//!   seeded multi-start Nelder–Mead (argmin), deterministic on any thread count, maximising the
//!   objective of a plan config ([`PlanConfig`]: weight, weight under a grade or a minimum
//!   brilliance, or value from a price table, [`PriceTable`]); a coloured rough's plans can
//!   then be ranked by their face-up colour ([`colour`]);
//! - the plans as data ([`Plan`]): the family's cut, its pose and scale, the placed cut in the
//!   rough's coordinates, carats, yield, grade and objective, for the run folder and for the
//!   plot floor to draw;
//! - several stones ([`layout`]): a rough sawn into pieces with the kerf, one cut in each
//!   kept an allowance inside its piece and off the inclusions, ranked by total value;
//! - the run ([`run`]): the families planned in turn ([`plan_families`]) and the run folder
//!   written from them with scores ([`write_folder`]: OBJ, TOML, GemCad, glTF, the
//!   `summary.json` document of [`summary`], and the pictures and page that a [`Drawings`]
//!   from the floors above draws).
//!
//! What it may import: [`crate::optimize`] and every floor below it (`verify`, `metrics`,
//! `render`, the tracers, `optics`, `io`, `cut`, `geometry`, `error`). Never `plot`, `report`
//! or the binary: pictures and pages of a plan are drawn from what the planner returns, as
//! the optimizer's are.
//!
//! Files: `mesh.rs` reads a rough's triangles, `rough.rs` makes the rough (hull or crystal
//! form), `fit.rs` is the containment program, `search.rs` the search over orientation and
//! proportions, `config.rs` the plan config (objective, bounds, price table), `sample.rs` the
//! example rough (a distorted octahedron mesh), `run.rs` the run and its folder, `summary.rs`
//! the folder's `summary.json`, `colour.rs` the face-up colour objective.

pub mod ball;
pub mod colour;
pub mod config;
pub mod fit;
pub mod layout;
pub mod mesh;
pub mod out;
pub mod rough;
pub mod run;
pub mod sample;
pub mod search;
pub mod summary;

pub use ball::{enclosing_ball, Ball};
pub use config::{Bound, Cutter, Objective, PlanConfig, PriceTable, DEFAULT_FAMILIES};
pub use fit::{largest_copy, Fit};
pub use layout::{plan_layout, ColourWorth, Inclusion, Layout, LayoutPlanner, SawCut, Stone};
pub use out::check_out;
pub use rough::{load_rough, parse_rough_size_mm, rough_size_mm, Rough, CRYSTALS, ROUGH_MAX_MM};
pub use run::{plan_families, write_folder, Drawings, PlacedPlan, Run};
pub use search::{plan_warnings, Plan, Planner};
