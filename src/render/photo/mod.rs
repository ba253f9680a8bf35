//! Photographs of a stone: exact renders under studio lights and HDR environments, from any
//! view, orthographic or in perspective, on a ground with the stone's shadow and caustics.
//!
//! The laboratory pictures ([`render`](crate::render::render)) look straight down under
//! lights made for judging cuts; a photograph shows the stone as a person sees it. The beam
//! tracer does the same work for both: traced backwards from the camera, every exit beam is
//! a bundle of sight lines leaving the stone in one direction `w`, and its footprint the part
//! of the picture they start from, so the picture is exact:
//!
//! * the light an exit beam sees is the [environment's](mod@env) filtered radiance from `w`
//!   (the rigs of [`rigs`], an equirectangular map, [`envmap`]), per wavelength band (fire's
//!   bands: each traced at its own index, with the body colour's exact absorption), with its
//!   polarization tracked through the stone;
//! * sight lines leaving downward onto a [ground](mod@ground) see its radiance where they
//!   land: each beam's exact coverage of every pixel times the ground's (bilinear) radiance
//!   sampled at that pixel's part of the beam, mapped onto the ground by the beam's affine
//!   map (on a grid of up to 4 × 4 points where a pixel sees more than a ground cell);
//! * the ground's shadow and caustics are the lights' own beam traces: exit beams projected
//!   onto the plane with their power;
//! * a [perspective camera](camera) is traced in tiles of parallel beams;
//! * the picture is summed in CIE XYZ and shown through a [tone curve](tone).
//!
//! Values are linear and relative to a white diffuser under the ISO sky (radiance 1 over the
//! upper hemisphere), as in the laboratory pictures.

pub mod camera;
mod draw;
pub mod env;
pub mod envmap;
pub mod ground;
mod options;
mod record;
pub mod rigs;
mod sky;
pub mod tone;

#[cfg(test)]
mod tests;

pub use camera::{parse_view, Projection, View};
pub use draw::photo;
pub use env::{Disc, Environment, LightSample, Part, MAX_EDGE_DEG};
pub use envmap::EnvMap;
pub use ground::{Ground, GroundKind, GroundStats};
pub use options::{PhotoLight, PhotoOptions, NEAR_POINT_MM, PUPIL_MM, STUDIO};
pub use record::{caption, turntable, turntable_period};
pub use rigs::Rig;
pub use tone::Tone;

use crate::render::raster::Raster;
use serde::{Deserialize, Serialize};

/// Statistics of a photograph.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhotoStats {
    /// The light's name.
    pub light: String,
    /// Pixels per side.
    pub size: usize,
    /// Mean luminance of the stone's light over its outline, relative to a white diffuser
    /// under the ISO sky.
    pub mean: f64,
    /// Whether it was traced band by band (a dispersive or coloured stone).
    pub spectral: bool,
    /// Wavelength bands traced (0 when not spectral).
    pub bands: usize,
    /// Traces of the picture (bands × tiles).
    pub traces: usize,
    /// Share of the light cut off by the tracer's thresholds (largest over the bands).
    pub cut_off: f64,
    /// Exit beams drawn (all bands and tiles).
    pub exits: usize,
    /// The ground's bookkeeping, with a ground.
    pub ground: Option<GroundStats>,
}

/// A photograph: linear CIE XYZ (Y relative to a white diffuser under the ISO sky), the
/// stone's own light, the outline's coverage.
#[derive(Clone, Debug)]
pub struct Photo {
    /// X, Y, Z, rows from the bottom.
    pub xyz: [Raster; 3],
    /// Luminance of the light the stone sends (the background left out), rows from the
    /// bottom.
    pub stone: Raster,
    /// Share of each pixel the stone's outline covers.
    pub coverage: Raster,
    /// Statistics.
    pub stats: PhotoStats,
}

impl Photo {
    /// Pixels per side.
    pub fn size(&self) -> usize {
        self.coverage.n
    }
}
