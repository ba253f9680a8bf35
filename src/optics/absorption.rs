//! Absorption inside the stone: how light is lost along its path through the material.
//!
//! Today this is [`Absorption`], the photon tracer's model (none, the thesis's flat roulette,
//! or Beer–Lambert with one coefficient for every wavelength). Body colour lands here: a
//! coloured variety's absorption spectrum α(λ), a user's colour upsampled to such a spectrum,
//! and the stone's CIE colour from it (with [`color`](super::color) for the colour maths).

/// Absorption inside the stone.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Absorption {
    /// None (a clear stone).
    None,
    /// The thesis's flat roulette: before each surface interaction from inside the stone a
    /// photon is absorbed with probability 0.1.
    Thesis,
    /// Beer–Lambert with this attenuation coefficient per girdle diameter of path: a photon
    /// survives a path of length L with probability exp(−k·L).
    Beer(f64),
}

/// Probability of absorption per internal segment in [`Absorption::Thesis`].
pub const THESIS_ABSORPTION: f64 = 0.1;
