//! `facetlab render CUT... --light tent|darkfield|daylight|office|ring|studio|env:FILE`:
//! photographs of stones ([`facetlab::render::photo`]), side by side, each captioned; with
//! `--turn FRAMES` (or `--rock`) an animation, as animated PNG or GIF (by `-o`'s extension).
//! The flags are parsed here into [`PhotoOptions`]; the pictures, captions and JSON records
//! come from the library ([`facetlab::plot::render::draw`]).

use super::{check_animation, check_rock, RenderArgs};
use crate::cli::flags;
use crate::cli::outputs::{cut_files, refuse_overwrite};
use facetlab::error::{Error, Result};
use facetlab::metrics::StoneChoice;
use facetlab::plot::render::PhotoPictures;
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
    #[arg(long, value_name = "MM", allow_hyphen_values = true)]
    pub distance: Option<String>,
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
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub ground_gap: Option<String>,
    /// Photographs: turn the light about the vertical, degrees (counter-clockwise seen from
    /// above).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub light_rotation: Option<String>,
    /// Photographs: a turntable animation of FRAMES frames (2–360), the stone turned a full
    /// circle under the camera and lights.
    #[arg(long, value_name = "FRAMES", allow_hyphen_values = true)]
    pub turn: Option<String>,
    /// Photographs: the tone curve from linear radiance to the picture: filmic (default) or
    /// clip.
    #[arg(long, value_name = "filmic|clip", value_parser = flags::parsed("--tone", Tone::parse))]
    pub tone: Option<Tone>,
    /// Photographs: also write the linear picture (before exposure and tone) as OpenEXR
    /// (.exr) or Radiance HDR (.hdr); frame 0 of an animation, the first cut.
    #[arg(long, value_name = "FILE.exr")]
    pub hdr_out: Option<PathBuf>,
    /// Photographs: wavelength bands of a dispersive or coloured stone (3–64; default 8).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub bands: Option<String>,
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
    o.size = a.size as usize;
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
    if let Some(g) = &p.ground_gap {
        o.ground.gap = flags::number("--ground-gap", g, 0.0, 10.0, "girdle diameters")?;
    }
    if let Some(r) = &p.light_rotation {
        o.light_rotation_deg = flags::number("--light-rotation", r, -360.0, 360.0, "degrees")?;
    }
    if let Some(t) = p.tone {
        o.tone = t;
    }
    if let Some(b) = &p.bands {
        o.bands = flags::count("--bands", b, 3, 64)? as usize;
    }
    if let Some(d) = &p.distance {
        o.distance_mm = Some(flags::number("--distance", d, 0.0, 1e5, "millimetres")?);
    }
    let turn = p
        .turn
        .as_deref()
        .map(|t| flags::count("--turn", t, 2, 360).map(|n| n as usize))
        .transpose()?;
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

/// Whether `path` ends in `ext` (any case).
fn has_ext(path: &std::path::Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Check the outputs before any work.
pub fn check_outputs(a: &RenderArgs) -> Result<()> {
    let mut outs = vec![("-o", a.output.clone())];
    if let Some(j) = &a.json {
        outs.push(("--json", j.clone()));
    }
    if let Some(h) = &a.photo.hdr_out {
        outs.push(("--hdr-out", h.clone()));
    }
    refuse_overwrite(&outs, &cut_files(&a.cuts))?;
    if !(has_ext(&a.output, "png") || has_ext(&a.output, "gif")) {
        return Err(Error::invalid(
            "-o",
            format!(
                "{} does not end in .png or .gif; a photograph is a PNG, an animation an animated PNG or GIF",
                a.output.display()
            ),
        ));
    }
    if let Some(h) = &a.photo.hdr_out {
        if !facetlab::io::hdr::is_hdr_path(h) {
            return Err(Error::invalid(
                "--hdr-out",
                format!("{} does not end in .exr or .hdr", h.display()),
            ));
        }
    }
    for (i, (fa, pa)) in outs.iter().enumerate() {
        for (fb, pb) in &outs[i + 1..] {
            if crate::cli::outputs::resolved(pa) == crate::cli::outputs::resolved(pb) {
                return Err(Error::invalid(
                    *fb,
                    format!("{} is also the {fa} file; give another file", pb.display()),
                ));
            }
        }
    }
    for (flag, p) in &outs {
        crate::cli::outputs::check_new_file(flag, p, a.force)?;
    }
    Ok(())
}
