//! `render`'s flags validated into the library's picture settings
//! ([`PictureSettings::pictures`] makes the options of a laboratory picture or a
//! photograph), and the rock's and animation's limits both kinds of picture share.

use super::RenderArgs;
use crate::cli::flags;
use facetlab::error::{Error, Result};
use facetlab::metrics::StoneChoice;
use facetlab::render::{PictureSettings, Pictures, Tilt};

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

/// The picture settings the flags give, as the library's values.
fn picture_settings(a: &RenderArgs) -> PictureSettings {
    let p = &a.photo;
    PictureSettings {
        light: a.light.clone(),
        size: Some(a.size),
        tilt: a.tilt,
        head_shadow: a.head_shadow,
        exposure: Some(a.exposure),
        polarization: a.polarization,
        view: p.view,
        distance: p.distance,
        aperture: p.aperture,
        ground: p.ground,
        ground_gap: p.ground_gap,
        light_rotation: p.light_rotation,
        tone: p.tone,
        bands: p.bands,
    }
}

/// Validate the flags into the library's types: the pictures, their rock or turntable, and
/// the stones.
pub fn settings(a: &RenderArgs) -> Result<(Pictures, StoneChoice)> {
    let mut stone = flags::stone_choice(a.material.material()?, &a.material, &a.colour, None)?;
    let pictures = picture_settings(a)
        .pictures(&stone.material, stone.size)
        .map_err(|e| flags::picture_to_flags(e, &a.material))?;
    let rock = a.rock;
    Ok(match pictures {
        Pictures::Lab(mut p) => {
            check_rock(p.opts.tilt, rock)?;
            if let Some((_, n)) = rock {
                check_animation("--rock", n, a.cuts.len(), p.opts.size)?;
            }
            p.rock = rock;
            stone.crystal = Some(a.crystal.choice(p.opts.wavelength_nm));
            (Pictures::Lab(p), stone)
        }
        Pictures::Photo(mut p) => {
            // A birefringent stone is photographed as it is traced elsewhere: its crystal
            // settings (--birefringence, --optic-axis, --colour-e) apply, its note giving the
            // indices at the sodium D line.
            stone.crystal = Some(a.crystal.choice(facetlab::metrics::REFERENCE_WAVELENGTH_NM));
            let turn = a.photo.turn.map(|n| n as usize);
            if turn.is_some() && rock.is_some() {
                return Err(Error::invalid(
                    "--turn",
                    "give either --turn (a turntable) or --rock, not both",
                ));
            }
            check_rock(p.opts.tilt, rock)?;
            let frames = turn.or(rock.map(|r| r.1)).unwrap_or(1);
            if frames > 1 {
                let flag = if turn.is_some() { "--turn" } else { "--rock" };
                check_animation(flag, frames, a.cuts.len(), p.opts.size)?;
            }
            p.turn = turn;
            p.rock = rock;
            (Pictures::Photo(p), stone)
        }
    })
}
