//! facetlab: design, score and optimize cut gemstones with real optics.
//!
//! Data flows one way: [`geometry`] → [`cut`] → [`io`] → [`optics`] → tracers → metrics →
//! optimizer → plots → CLI. The library knows nothing of the command line.
#![warn(missing_docs)]

pub mod error;
pub mod cut;
pub mod geometry;
pub mod io;

pub use error::{Error, Result};
