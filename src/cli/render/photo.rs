//! `facetlab render CUT... --light tent|darkfield|daylight|office|ring|studio|env:FILE`:
//! photographs of stones ([`facetlab::render::photo`]), side by side, each captioned; with
//! `--turn FRAMES` (or `--rock`) an animation, as animated PNG or GIF (by `-o`'s extension).
//! The flags are parsed here into the library's picture settings (`super::settings`); the
//! pictures, captions and JSON records
//! come from the library ([`facetlab::plot::render::draw`]).

use super::RenderArgs;
use crate::cli::flags;
use facetlab::error::Result;
use facetlab::io::guard::{cut_files, PictureFiles};
use facetlab::render::photo::{parse_view, GroundKind, Tone, View};
use facetlab::render::settings as picture;
use std::path::PathBuf;

/// The photographic flags of `render` (they need a photographic `--light`).
#[derive(clap::Args, Debug, Clone, Default)]
pub struct PhotoArgs {
    /// Photographs: where the camera looks from, ELEV degrees above the horizon (90 =
    /// straight above, 0 = a side view, negative = from below) and azimuth AZ (degrees
    /// counter-clockwise from the front); default 30@0.
    #[arg(long, value_name = "ELEV[@AZ]", allow_hyphen_values = true, value_parser = flags::parsed("--view", parse_view))]
    pub view: Option<View>,
    /// Photographs: a perspective camera this many mm from the stone's centre (the stone's
    /// width from --diameter-mm, default 6.5 mm); default: orthographic.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = flags::parsed("--distance", picture::parse_distance))]
    pub distance: Option<f64>,
    /// Photographs: the camera's (or eye's) entrance pupil, MM across: the light is seen
    /// through the angle it subtends from the stone, ±atan(MM / 2 / distance), each edge of
    /// the light ramped over it; 0 = a pinhole (no filter: lights' sharp rims, a map's own
    /// texels, bilinear). Without --distance it is read at 250 mm (the near point). Default:
    /// a human pupil, 4 mm, with --distance (±0.46° at 250 mm); without, ±1° (the scores'
    /// filter). At most ±10°.
    #[arg(long, value_name = "MM", allow_hyphen_values = true, value_parser = flags::parsed("--aperture", picture::parse_aperture))]
    pub aperture: Option<f64>,
    /// Photographs: the ground the stone rests on, culet-down: white (paper), black
    /// (velvet) or none (default), with its shadow and caustics.
    #[arg(
        long,
        value_name = "white|black|none",
        value_parser = flags::parsed("--ground", GroundKind::parse)
    )]
    pub ground: Option<GroundKind>,
    /// Photographs: height of the stone's lowest point above the ground, girdle diameters
    /// (0–10; default 0: resting on it).
    #[arg(long, value_name = "X", allow_hyphen_values = true, value_parser = flags::parsed("--ground-gap", picture::parse_ground_gap))]
    pub ground_gap: Option<f64>,
    /// Photographs: turn the light about the vertical, degrees (counter-clockwise seen from
    /// above).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true, value_parser = flags::parsed("--light-rotation", picture::parse_light_rotation))]
    pub light_rotation: Option<f64>,
    /// Photographs: a turntable animation of FRAMES frames (2–360), the stone turned a full
    /// circle under the camera and lights.
    #[arg(long, value_name = "FRAMES", allow_hyphen_values = true, value_parser = flags::whole("--turn", 2, 360))]
    pub turn: Option<u64>,
    /// Photographs: the tone curve from linear radiance to the picture: filmic (default) or
    /// clip.
    #[arg(long, value_name = "filmic|clip", value_parser = flags::parsed("--tone", Tone::parse))]
    pub tone: Option<Tone>,
    /// Photographs: also write the linear picture (before exposure and tone) as OpenEXR
    /// (.exr) or Radiance HDR (.hdr); frame 0 of an animation, the first cut.
    #[arg(long, value_name = "FILE.exr")]
    pub hdr_out: Option<PathBuf>,
    /// Photographs: wavelength bands of a dispersive or coloured stone (3–64; default 8).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = flags::parsed("--bands", picture::parse_bands))]
    pub bands: Option<usize>,
}

impl PhotoArgs {
    /// The first photographic flag given, if any (to refuse it with a laboratory light).
    pub fn first_given(&self) -> Option<&'static str> {
        [
            (self.view.is_some(), "--view"),
            (self.distance.is_some(), "--distance"),
            (self.aperture.is_some(), "--aperture"),
            (self.ground.is_some(), "--ground"),
            (self.ground_gap.is_some(), "--ground-gap"),
            (self.light_rotation.is_some(), "--light-rotation"),
            (self.turn.is_some(), "--turn"),
            (self.tone.is_some(), "--tone"),
            (self.hdr_out.is_some(), "--hdr-out"),
            (self.bands.is_some(), "--bands"),
        ]
        .into_iter()
        .find(|x| x.0)
        .map(|x| x.1)
    }
}

/// Check a photograph's outputs before any work ([`PictureFiles::check_photograph`]): none
/// of them a cut's file or the environment map.
pub fn check_outputs(a: &RenderArgs) -> Result<()> {
    let mut inputs = cut_files(&a.cuts);
    inputs.extend(a.light.file());
    PictureFiles {
        picture: &a.output,
        json: a.json.as_deref(),
        hdr: a.photo.hdr_out.as_deref(),
    }
    .check_photograph(&inputs, a.force)
}
