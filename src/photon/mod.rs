//! The photon tracer: the thesis's forward Monte Carlo from the light.
//!
//! Photons leave a square [`Light`] (directed: all parallel to the light's axis; undirected:
//! uniform over the hemisphere in front of it), get a wavelength ([`WavelengthSampling`]) and
//! the material's refractive index at it, and meet the stone's facets. At every surface
//! Fresnel's equations choose reflection or refraction by roulette (with the photon's Stokes
//! vector and Mueller matrices when [`TraceConfig::polarization`] is on, else the unpolarized
//! average); Snell's law gives the new direction; total internal reflection reflects.
//! [`Absorption`] removes photons inside the stone; a depth limit stops the rest.
//!
//! Photons carry unit weight, so the bookkeeping is exact in whole numbers
//! (see [`Counts::check`]):
//!
//! * shot = missed + hit,
//! * hit = exited + absorbed + depth-limited,
//! * exited = the sum over the four face categories = the sum over facets.
//!
//! **Depth.** The surface interactions of a photon are counted, the first hit on the stone
//! included. With `depth: Some(n)` a photon that is still inside the stone after its n-th
//! interaction is counted as depth-limited (the thesis: 6). `depth: None` is "unlimited", with a
//! safety cap of [`UNLIMITED_CAP`] interactions (photons trapped by total internal reflection
//! in a loop would otherwise never end); photons reaching it are also counted as
//! depth-limited.
//!
//! **Determinism.** Work is split into chunks of [`CHUNK`] photons. A chunk traces its photons
//! eight at a time in lanes (one batched exit search serves all eight, so their dependent
//! chains overlap); lane `l` of chunk `c` draws from its own RNG seeded from `(seed, c, l)`
//! (each 64-bit draw giving two 32-bit uniforms), so the order in which its photons finish
//! follows from those streams alone. Tallies are integer counts, so their sum does not depend
//! on the order or the thread count: the same seed gives the same numbers on any number of
//! threads. Chunks are traced in parallel a wave at a time and their counts added in chunk
//! order as each wave finishes (so the float sums of [`trace_weighted`] are the same on any
//! thread count too, and memory does not grow with the photon count). At most
//! [`MAX_PHOTONS`] photons per run.
//!
//! ```
//! use facetlab::photon::{trace, Light, TraceConfig};
//! let cut = facetlab::io::load_cut("tolkowsky").unwrap();
//! let cfg = TraceConfig { photons: 2_000, ..TraceConfig::thesis() };
//! let t = trace(&cut.solid, &Light::directed(0.0), &cfg, None).unwrap();
//! assert_eq!(t.counts.shot, 2_000);
//! assert!(t.light_return().0 > 0.3);
//! ```

mod absorption;
mod chunks;
mod config;
mod crystal;
mod crystal_setup;
mod entry_grid;
mod kernel;
mod lanes;
mod light;
mod reach;
mod run;
mod singly;
mod solid;
mod tally;
#[cfg(test)]
mod tests;

pub use crate::optics::{Absorption, THESIS_ABSORPTION};
pub use config::{
    check_photons, ExitWeights, TraceConfig, WavelengthSampling, CHUNK, MAX_PHOTONS, UNLIMITED_CAP,
    WEIGHTS,
};
pub use light::{
    Light, LightChoice, LightKind, LightSize, LIGHT_DISTANCE, LIGHT_SIDE, ROTATION_ANGLES,
};
pub use run::{
    rotation_sweep, trace, trace_choice, trace_choice_until, trace_cut, trace_weighted,
    trace_weights, WeightedTally, WeightsTally, STOPPED,
};
pub use solid::{face_category, TraceSolid};
pub use tally::{share, Counts, Fate, PhotonPath, Tally, CATEGORY_KEYS, CATEGORY_LABELS};
