//! Rough planning: the largest, best cut inside a rough stone (issue 26, `facetlab plan`). The
//! room is empty for now; this says what will land here and what it may use.
//!
//! What lands here:
//!
//! - the rough: a convex hull of a scanned mesh (OBJ/STL, millimetres) or a bundled crystal
//!   form, as half-spaces, with how much volume the hull adds to a mesh that is not convex;
//! - containment: for one orientation and one set of proportions, the largest copy of a cut
//!   inside the rough is a linear program in the scale and the translation (every vertex of
//!   the cut inside every half-space of the rough), solved exactly;
//! - the search: orientation and proportions around that program, run by the optimizer
//!   (multi-start, seeded, deterministic on any thread count) over a cut space's parameters
//!   ([`crate::cut::CutSpace`]), with the objective of a plan config (weight, weight under a
//!   grade or brilliance constraint, or value from a price table);
//! - the plan's results as data: each plan's cut in the rough's coordinates, yield, carats,
//!   proportions, grade estimate and scores, for the binary to write as a run folder and for
//!   the plots and the report to draw.
//!
//! What it may import: [`crate::optimize`] and every floor below it (`verify`, `metrics`,
//! `render`, the tracers, `optics`, `io`, `cut`, `geometry`, `error`). Never `plot`, `report`
//! or the binary: pictures and pages of a plan are drawn from what the planner returns, as
//! the optimizer's are.
//!
//! Files: `mesh.rs` reads a rough's triangles, `rough.rs` makes the rough (hull or crystal
//! form), `fit.rs` is the containment program, `search.rs` the search over orientation and
//! proportions, `config.rs` the plan config (objective, bounds, price table), `sample.rs` the
//! example rough (a distorted octahedron mesh).

pub mod config;
pub mod fit;
pub mod mesh;
pub mod rough;
pub mod sample;
pub mod search;

pub use config::{Bound, Objective, PlanConfig, PriceTable, DEFAULT_FAMILIES};
pub use fit::{largest_copy, Fit};
pub use rough::{load_rough, Rough, CRYSTALS};
pub use search::{Plan, Planner};
