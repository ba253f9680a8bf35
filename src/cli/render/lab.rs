//! A laboratory picture's flags validated into the library's options, and the rock's and
//! animation's limits both kinds of picture share.

use super::RenderArgs;
use crate::cli::flags;
use facetlab::error::{Error, Result};
use facetlab::metrics::StoneChoice;
use facetlab::plot::render::LabPictures;

use facetlab::render::{Light, RenderOptions, Tilt};

/// Largest animation: frames × cuts × size² pixels (about 1.2 GB of 8-bit RGB in memory).
pub const MAX_ANIMATION_PIXELS: f64 = 400e6;

/// Refuse an animation (`flag`: --rock or --turn) of `frames` frames of `cuts` pictures of
/// `size` px larger than [`MAX_ANIMATION_PIXELS`]: every frame is held in memory until the
/// file is written.
pub(super) fn check_animation(flag: &str, frames: usize, cuts: usize, size: usize) -> Result<()> {
    let pixels = (frames * cuts) as f64 * (size as f64).powi(2);
    if pixels > MAX_ANIMATION_PIXELS {
        return Err(Error::invalid(
            flag,
            format!(
                "{frames} frames of {cuts} picture(s) of {size} px would hold {:.0} million pixels; allowed {:.0} million: use fewer frames or a smaller --size",
                pixels / 1e6,
                MAX_ANIMATION_PIXELS / 1e6
            ),
        ));
    }
    Ok(())
}

/// Refuse a rock that would tip the stone past 90° from its `--tilt`.
pub(super) fn check_rock(tilt: Tilt, rock: Option<(f64, usize)>) -> Result<()> {
    if let Some((deg, _)) = rock {
        if tilt.tilt_deg.abs() + deg > 90.0 {
            return Err(Error::invalid(
                "--rock",
                format!(
                    "rocking {deg}° about the --tilt of {}° would pass 90°; keep |tilt| + DEG <= 90",
                    tilt.tilt_deg
                ),
            ));
        }
    }
    Ok(())
}

/// Validate the flags into the library's types: the pictures and the stones.
pub fn settings(a: &RenderArgs) -> Result<(LabPictures, StoneChoice)> {
    let light = Light::parse(a.light.trim().to_ascii_lowercase().as_str()).map_err(|_| {
        Error::invalid(
            "--light",
            format!(
                "`{}` is not allowed; use {}, {} or env:FILE",
                a.light,
                Light::ALL.map(Light::name).join(", "),
                facetlab::render::photo::PhotoLight::names().join(", ")
            ),
        )
    })?;
    let mut opts = RenderOptions::new(light);
    opts.size = a.size;
    if let Some(t) = a.tilt {
        opts.tilt = t;
    }
    opts.head_shadow_deg = a.head_shadow;
    let mut stone = flags::stone_choice(a.material.material()?, &a.material, &a.colour, None)?;
    opts.material = stone.material.clone();
    opts.trace.polarization = a.polarization;
    let rock = a.rock;
    check_rock(opts.tilt, rock)?;
    if let Some((_, n)) = rock {
        check_animation("--rock", n, a.cuts.len(), opts.size)?;
    }
    let exposure = a.exposure;
    opts.validate()
        .map_err(|e| flags::picture_to_flags(e, &a.material))?;
    stone.crystal = Some(a.crystal.choice(opts.wavelength_nm));
    Ok((
        LabPictures {
            opts,
            rock,
            exposure,
        },
        stone,
    ))
}
