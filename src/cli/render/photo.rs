//! `facetlab render CUT... --light tent|darkfield|daylight|office|ring|studio|env:FILE`:
//! photographs of stones ([`facetlab::render::photo`]), side by side, each captioned; with
//! `--turn FRAMES` (or `--rock`) an animation, as animated PNG or GIF (by `-o`'s extension).
//! The flags are parsed here into [`PhotoOptions`]; the pictures, captions and JSON records
//! come from the library ([`facetlab::plot::render::draw`]).

use super::{check_animation, check_rock, RenderArgs};
use crate::cli::flags;
use facetlab::error::{Error, Result};
use facetlab::io::guard::{cut_files, PictureFiles};
use facetlab::metrics::StoneChoice;
use facetlab::plot::render::{settings as picture, PhotoPictures};
use facetlab::render::photo::{
    parse_view, Ground, GroundKind, PhotoLight, PhotoOptions, Tone, View,
};
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

/// Validate the flags into the library's options: the photographs and the stones.
pub fn settings(a: &RenderArgs, light: PhotoLight) -> Result<(PhotoPictures, StoneChoice)> {
    let p = &a.photo;
    let mut o = PhotoOptions::new(light);
    o.size = a.size;
    if let Some(v) = p.view {
        o.view = v;
    }
    if let Some(t) = a.tilt {
        o.tilt = t;
    }
    if a.head_shadow.is_some() {
        return Err(Error::invalid(
            "--head-shadow",
            "is for the laboratory lights; a photograph's camera casts no head shadow",
        ));
    }
    let mut stone = flags::stone_choice(a.material.material()?, &a.material, &a.colour, None)?;
    o.material = stone.material.clone();
    // A birefringent stone is photographed as it is traced elsewhere: its crystal settings
    // (--birefringence, --optic-axis, --colour-e) apply, its note giving the indices at the
    // sodium D line.
    stone.crystal = Some(a.crystal.choice(facetlab::metrics::REFERENCE_WAVELENGTH_NM));
    o.polarization = a.polarization;
    if let Some(kind) = p.ground {
        o.ground = Ground { kind, gap: 0.0 };
    }
    if let Some(g) = p.ground_gap {
        o.ground.gap = g;
    }
    if let Some(r) = p.light_rotation {
        o.light_rotation_deg = r;
    }
    if let Some(t) = p.tone {
        o.tone = t;
    }
    if let Some(b) = p.bands {
        o.bands = b;
    }
    if p.distance.is_some() {
        o.distance_mm = p.distance;
    }
    let turn = p.turn.map(|n| n as usize);
    let rock = a.rock;
    if turn.is_some() && rock.is_some() {
        return Err(Error::invalid(
            "--turn",
            "give either --turn (a turntable) or --rock, not both",
        ));
    }
    check_rock(o.tilt, rock)?;
    let frames = turn.or(rock.map(|r| r.1)).unwrap_or(1);
    if frames > 1 {
        let flag = if turn.is_some() { "--turn" } else { "--rock" };
        check_animation(flag, frames, a.cuts.len(), o.size)?;
    }
    let exposure = a.exposure;
    // The width the stone is seen at (for a perspective camera and absorption).
    if let facetlab::optics::StoneSize::Width(w) = stone.size {
        o.width_mm = w;
    }
    o.validate()
        .map_err(|e| flags::picture_to_flags(e, &a.material))?;
    Ok((
        PhotoPictures {
            opts: o,
            turn,
            rock,
            exposure,
        },
        stone,
    ))
}

/// Check a photograph's outputs before any work ([`PictureFiles::check_photograph`]).
pub fn check_outputs(a: &RenderArgs) -> Result<()> {
    PictureFiles {
        picture: &a.output,
        json: a.json.as_deref(),
        hdr: a.photo.hdr_out.as_deref(),
    }
    .check_photograph(&cut_files(&a.cuts), a.force)
}
