//! facetlab: design, score and optimize cut gemstones with real optics.
//!
//! Data flows one way: [`geometry`] → [`cut`] → [`io`] → [`optics`] → tracers → metrics →
//! optimizer → plots → CLI. The library knows nothing of the command line.
#![warn(missing_docs)]

pub mod beam;
pub mod cli;
pub mod cut;
pub mod error;
pub mod geometry;
pub mod io;
pub mod metrics;
pub mod optics;
pub mod optimize;

pub mod photon;
pub mod plot;

pub use error::{Error, Result};
