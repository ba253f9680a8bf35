//! Pictures of a stone: images from beam footprints under a lighting environment, with exact
//! area coverage.
//!
//! An orthographic viewer straight above the (possibly tilted) stone is traced backwards by
//! the [beam tracer](crate::beam): every exit beam is a bundle of the viewer's sight lines
//! that leave the stone in one direction `w`, and its footprint is the part of the picture
//! those sight lines start from. Each footprint adds the radiance the environment sends from
//! `w`, times the beam's Fresnel weight (its power per unit of footprint, relative to the
//! incoming light's), to the pixels it covers, in proportion to the exact area it covers in
//! each ([`raster`]). A pixel is so the exact mean of the light over its square: edges are
//! anti-aliased for free, and the picture changes continuously with the cut.
//!
//! # Lights
//!
//! [`Light`] names the environments cutters use (GemRay's ISO and COS, ASET, IdealScope, the
//! hearts & arrows viewer, spot lights for fire); [`Light::shade`] gives each one's colour as a
//! function of the direction light arrives from. Values are linear and relative to a white
//! diffuser under the ISO sky (radiance 1 over the upper hemisphere): a white diffuser of the
//! stone's outline would show 1 everywhere. COS lighting is GemRay's, radiance = cos(zenith
//! angle), so a stone under it reads the zenith-relative value (a white diffuser under the COS
//! sky itself would read 2/3).
//!
//! # Statistics
//!
//! [`Stats`] are computed from the same exit beams by the same code that fills the pixels:
//! `mean` is the image's integral over the stone's outline divided by the outline's area (the
//! pose's brilliance value for `iso` and `cos`: the number [`crate::metrics::score`] averages
//! over poses); the ASET shares are the shares of the picture in each colour; fire is
//! [`fire_of`] over the band images.

mod draw;
mod image;
mod layer;
mod light;
pub mod lighting;
pub mod lights;
mod options;
pub mod photo;
pub mod pose;
pub mod raster;
pub mod settings;

#[cfg(test)]
mod tests;

pub(crate) use draw::outline_coverage;
pub use draw::render;
pub use image::{fire_of, AsetShares, ColourStats, Image, Stats, COLOUR_GRID, EXTINCTION_L};
pub use light::{
    Light, ASET_COLOURS, HEARTS_APERTURE_DEG, IDEALSCOPE_COLOURS, PORT_DEG, SCOPE_TUBE_DEG,
    SCOPE_WALL_DEG,
};
pub use options::RenderOptions;
pub use pose::{picture_half, view_rotation, Tilt};
pub use settings::{LabPictures, LightChoice, PhotoPictures, PictureSettings, Pictures};
