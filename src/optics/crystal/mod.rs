//! Light in a uniaxial crystal and at its facets, exactly: the two modes a plane wave has
//! inside (ordinary and extraordinary) for a given wave vector along a facet, their ray
//! (Poynting) directions, and the Fresnel coefficients of every mode on entry, on exit and
//! on internal reflection from the full boundary conditions.
//!
//! Units: wave vectors in units of the vacuum wave number k₀, so that `|k| = n` for a wave of
//! index `n`; fields with `H = k × E` (impedance of free space 1). The crystal has principal
//! dielectric constants `ε_o = n_o²` (for E ⊥ ĉ) and `ε_e = n_e²` (E ∥ ĉ), optic axis ĉ.
//!
//! **Modes.** At a plane facet with unit normal ν the tangential part `K` of the wave vector
//! is the same for every wave (phase matching), so each mode's wave vector is `k = K + q ν`
//! with one unknown `q`:
//!
//! * ordinary: `|k|² = ε_o`, so `q = ±√(ε_o − K²)`; E ∝ k × ĉ;
//! * extraordinary: `(|k|² − (k·ĉ)²)/ε_e + (k·ĉ)²/ε_o = 1`, a quadratic
//!   `A q² + 2B q + C = 0` with `A = ε_o + Δ b²`, `B = Δ a b`, `C = ε_o K² + Δ a² − ε_o ε_e`
//!   (`a = K·ĉ`, `b = ν·ĉ`, `Δ = ε_e − ε_o`). Its roots are not mirror images of each other:
//!   `q = (−B ± √(B² − A C))/A`. The field: D ∝ (k·ĉ) k − (k·k) ĉ, E = ε⁻¹ D.
//!
//! A negative discriminant makes the mode evanescent (a complex `q` decaying away from the
//! facet): total internal reflection is decided per mode, on its wave vector. Of the two
//! roots, the one whose energy flows away from the facet on the side in question is the one
//! that exists there: for the extraordinary wave the flux along ν is proportional to
//! `A q + B = ±√(B² − A C)`, so the sign in front of the root is the direction.
//!
//! **Rays.** Energy travels along the Poynting vector `S = Re(E × H*)`, which for the
//! extraordinary wave is `k/ε_e + (k·ĉ) ĉ (1/ε_o − 1/ε_e)` up to a factor, off the wave
//! vector by the walk-off angle. A parallel beam moves along S; its wave vector stays fixed
//! between facets.
//!
//! **Boundary conditions.** An incoming wave of either mode meets a facet and sends out two
//! reflected waves (the two modes on its own side) and two transmitted waves (the two modes,
//! or the s and p waves of an isotropic medium, on the other side). Continuity of the
//! tangential E and H (four complex equations) gives their four amplitudes
//! ([`Crystal::enter`], [`Crystal::meet`]); each propagating wave's power is its amplitude
//! squared times its Poynting flux through the facet, over the incoming wave's. What is
//! reflected plus what is transmitted is 1 (tested to 1e-12; Berreman's 4×4 transfer-matrix
//! method, written independently in the tests, gives the same powers to 1e-10).
//!
//! **Absorption (pleochroism).** A weakly absorbing uniaxial crystal has absorption
//! coefficients α_o (E ⊥ ĉ) and α_e (E ∥ ĉ) as measured along principal directions. A mode
//! with unit field E and wave vector k loses power along its ray at the rate
//! `(α_o n_o |E⊥|² + α_e n_e |E∥|²) / |E × (k × E)|` (absorbed power density `½ E·ε''·E`,
//! with `ε''_j = α_j n_j` from the principal measurements, over the energy flux): α_o for
//! every ordinary wave, α_e for an extraordinary wave travelling ⊥ ĉ, in between otherwise
//! ([`Crystal::absorption`]). It is constant along a beam, so Beer–Lambert over a beam's
//! footprint stays exact.
//!
//! References: J. Lekner, "Reflection and refraction by uniaxial crystals", J. Phys.:
//! Condens. Matter 3, 6121–6133 (1991); P. Yeh, "Electromagnetic propagation in birefringent
//! layered media", J. Opt. Soc. Am. 69, 742–756 (1979); D. W. Berreman, "Optics in
//! stratified and anisotropic media: 4×4-matrix formulation", J. Opt. Soc. Am. 62, 502–510
//! (1972).

mod boundary;
mod complex;
mod entry;
mod meeting;
mod modes;
#[cfg(test)]
mod tests;
mod uniaxial;
mod wave;

pub use complex::{CVec3, C};
pub use entry::Entry;
pub use meeting::Meeting;
pub(crate) use meeting::RawMeeting;
pub use uniaxial::Crystal;
pub use wave::{Wave, WaveMode};
