//! Optics shared by both tracers, as pure functions: materials with Sellmeier dispersion,
//! Fresnel amplitudes and reflectances, total internal reflection with its s–p phase, Mueller
//! matrices and Stokes vectors, absorption inside the stone, and colour (CIE 1931, D65, sRGB).
//!
//! Materials: `material.rs` holds the index model (dispersion formulas, [`Material`]),
//! `table.rs` the named stones with their coefficients and citations, `choose.rs` the ways to
//! pick one (by name, by flag, by a cut's index: [`Material::for_index`]). Absorption
//! ([`Absorption`], `absorption.rs`) is the photon tracer's loss model. Body colour — α(λ) per
//! mm, the colour seen through a path, a user's colour upsampled to a spectrum — is
//! [`BodyColour`] (`body_colour.rs`); the coloured varieties with published spectra
//! ([`Variety`]: ruby, emerald, …) are in `varieties.rs`.
//!
//! Polarization convention: a Stokes vector `(I, Q, U, V)` is given in a frame whose reference
//! axis `e_s` is a unit vector perpendicular to the propagation direction; `Q = I_s − I_p`
//! with `p = d × e_s`. At an interface the natural frame has `e_s` perpendicular to the plane of
//! incidence, and there the Mueller matrices have the block form of [`Mueller`].

mod absorption;
mod birefringence;
mod body_colour;
mod choose;
pub mod color;
pub mod crystal;
mod fresnel;
mod material;
mod polarization;
mod table;
pub mod upsample;
mod varieties;

pub use absorption::{Absorption, THESIS_ABSORPTION};
pub use birefringence::{BirefringenceJson, CrystalFields, BIAXIAL_REASON};
pub use body_colour::{
    fit_sigmoid, BodyColour, ColourFields, StoneSize, UserColour, COLOUR_FORMS, DEFAULT_PATH_MM,
    DENSITY_MAX, FIT_TOLERANCE, SAMPLES, STEP_NM,
};
pub use fresnel::{critical_angle, fresnel, reflect, refract, Complex, Interface};
pub use material::{Dispersion, Material, MaterialFields, OpticAxis, Uniaxial};
pub use polarization::{rotate_stokes, s_axis, Mueller, Stokes};
pub use varieties::Variety;
