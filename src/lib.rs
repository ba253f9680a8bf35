//! facetlab: design, score and optimize cut gemstones with real optics.
//!
//! Data flows one way: [`geometry`] → [`cut`] → [`io`] → [`optics`] → tracers → metrics → the
//! photon cross-check of the beam tracer ([`verify`]) → optimizer → plots; the `facetlab`
//! binary (its own `cli` module) sits on top. The library knows nothing of the command line:
//! clap, indicatif and ctrlc are the binary's, behind the default `cli` feature.
#![warn(missing_docs)]

pub mod beam;
pub mod cut;
pub mod error;
pub mod geometry;
pub mod io;
pub mod metrics;
pub mod optics;
pub mod optimize;

pub mod photon;
pub mod plot;
pub mod verify;

pub use error::{Error, Result};
