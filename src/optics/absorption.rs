//! Absorption inside the stone: how light is lost along its path through the material.
//!
//! [`Absorption`] is the photon tracer's model: none, the thesis's flat roulette, Beer–Lambert
//! with one coefficient for every wavelength, or Beer–Lambert by the material's body colour
//! α(λ) ([`BodyColour`](super::BodyColour), `body_colour.rs`) at the stone's size in mm.

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
    /// Beer–Lambert by the material's body colour ([`BodyColour`](super::BodyColour), α(λ)
    /// per mm) in a stone `width_mm` millimetres wide: a photon of wavelength λ survives a path
    /// of L widths with probability exp(−α(λ)·L·width_mm). A colourless material absorbs
    /// nothing.
    Body {
        /// The stone's width W in mm (1 unit of the solid's coordinates).
        width_mm: f64,
    },
}

impl Absorption {
    /// The Beer–Lambert coefficient per unit of path (girdle diameters) for a photon of
    /// wavelength `nm` in a stone of `colour`, or `None` when this model is not Beer–Lambert.
    #[inline]
    pub fn beer_per_width(&self, colour: Option<&super::BodyColour>, nm: f64) -> Option<f64> {
        match *self {
            Absorption::Beer(k) => Some(k),
            Absorption::Body { width_mm } => Some(colour.map_or(0.0, |c| c.alpha(nm)) * width_mm),
            Absorption::None | Absorption::Thesis => None,
        }
    }
}

/// Probability of absorption per internal segment in [`Absorption::Thesis`].
pub const THESIS_ABSORPTION: f64 = 0.1;
