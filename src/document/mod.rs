//! The JSON documents the commands write about cuts, each shaped here and nowhere else, so that
//! the binary, the web page and the Python package write the same bytes:
//!
//! * [`score`]: `facetlab score --json` (the scores, the settings as understood, and the photon
//!   tracer's checks of `--verify`; the table it prints; the JSON Lines of `--batch`);
//! * [`info`]: `facetlab info --json` (proportions, tiers, ratios, size and weight, checks,
//!   grade, instructions and meets), and the text `facetlab info` prints;
//! * [`render`]: `facetlab render --json` (a picture's or a photograph's statistics, per frame
//!   of an animation);
//! * [`materials`]: `facetlab materials --json` (the table of stones and coloured varieties);
//! * [`trace`]: `facetlab trace --json` (the photon tallies and the run's settings);
//! * [`scoring`]: `facetlab score` as one call (the stones, the scores, the photon tracer's
//!   checks, the document written);
//! * [`batch`]: `facetlab score --batch`'s JSON Lines written resumably (the lines of a batch
//!   file, what its output already holds, the scoring of the rest).
//!
//! Each takes the library's own results and settings (a [`Cut`](crate::cut::Cut), a
//! [`ScoreConfig`](crate::metrics::ScoreConfig), [`Scores`](crate::metrics::Scores), a
//! [`Tally`](crate::photon::Tally), …), never a command-line type. The folders of runs write
//! their own documents where they are written: an optimization's `report.json` in
//! [`crate::optimize`], a rough plan's `summary.json` in [`crate::plan`].

pub mod batch;
pub mod info;
pub mod materials;
pub mod render;
pub mod score;
pub mod scoring;
pub mod trace;
