//! facetlab: design, score and optimize cut gemstones with real optics.
//!
//! Data flows one way: [`geometry`] → [`cut`] → [`design`] → [`io`] → [`optics`] → tracers
//! ([`photon`], [`beam`]) → pictures ([`render`]) → scores ([`metrics`]) → the photon
//! cross-check of the beam tracer ([`verify`]) → the optimizer ([`optimize`]) → sweeps and
//! grids ([`sweep`]) → rough planning ([`plan`]) → plots ([`plot`]) → one-page reports
//! ([`report`]); the `facetlab` binary (its
//! own `cli` module, with the `serve` web page) sits on top. The library knows nothing of the
//! command line or the web: clap, indicatif, ctrlc, axum and tokio are the binary's, behind
//! the default `cli` feature.
//!
//! # A short tour
//!
//! Load a preset (or a `.toml`, `.asc`, `.gem`, `.obj`, `.stl` file) with [`io::load_cut`], change its
//! parameters with [`cut::Cut::with_params`] (or build any family with
//! [`cut::Cut::from_family`]), and score it with [`metrics::score`]:
//!
//! ```
//! use facetlab::metrics::{score, ScoreConfig};
//! use std::collections::BTreeMap;
//!
//! let tolkowsky = facetlab::io::load_cut("tolkowsky").unwrap();
//! let deeper = tolkowsky
//!     .with_params(&BTreeMap::from([("pavilion_angle".to_string(), 42.0)]))
//!     .unwrap();
//! assert!(deeper.proportions().pavilion_depth > tolkowsky.proportions().pavilion_depth);
//!
//! let s = score(&tolkowsky.solid, &ScoreConfig::default());
//! // An ideal round brilliant returns most of the light a viewer (whose head shadows the
//! // 15° about the line of sight) can see, and leaks little face-up.
//! assert!(s.brilliance > 0.6 && s.aset.leak < 0.15, "{s:?}");
//! assert!(s.fire > 0.0 && s.scintillation > 0.0);
//! let a = s.aset;
//! assert!((a.blue + a.red + a.green + a.leak + a.port - 1.0).abs() < 1e-12);
//! ```
//!
//! Solids come from half-spaces ([`geometry::Polyhedron::from_planes`]); GemCad designs are
//! read and written by [`io::asc`].
#![warn(missing_docs)]

pub mod beam;
pub mod cut;
pub mod design;
pub mod document;
pub mod error;
pub mod geometry;
pub mod io;
pub mod metrics;
pub mod optics;
pub mod optimize;
pub mod plan;

pub mod photon;
pub mod plot;
pub mod render;
pub mod report;
pub mod sweep;
pub mod verify;

// The Python package's native module (feature `python`; see pyproject.toml): a face on top of
// the library like the binary's `cli`, imported by nothing in the library.
#[cfg(feature = "python")]
mod python;

#[cfg(test)]
pub(crate) mod testkit;

pub use error::{Error, Result};
