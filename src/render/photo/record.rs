//! A photograph's captions ([`caption`]) and the poses of its animations ([`turntable`],
//! and the frames a turntable repeats, [`turntable_period`]).

use super::options::PhotoOptions;
use super::PhotoStats;
use crate::beam::Stone;
use crate::geometry::canonical::canonical;
use crate::geometry::Polyhedron;

/// The options of frame `k` of a turntable of `frames` frames: the stone turned
/// `360° · k / frames` about the vertical under the camera and lights.
pub fn turntable(opts: &PhotoOptions, frames: usize, k: usize) -> PhotoOptions {
    PhotoOptions {
        turn_deg: opts.turn_deg + 360.0 * k as f64 / frames.max(1) as f64,
        ..opts.clone()
    }
}

/// The frames of a turntable of `frames` frames that differ: frame `k` is the picture of
/// frame `k % period`. Turning the stone by `360° · period / frames` is then a rotation of its
/// own symmetry about the vertical, which maps the solid onto itself under the same camera,
/// lights and ground, so the two pictures are the same up to rounding (a round brilliant's
/// 36 frames are 9 pictures, each shown four times). That holds when the stone stands with
/// its axis vertical (face-up or face-down) and a birefringent stone's optic axis lies along
/// that axis; otherwise every frame differs (`period == frames`).
///
/// ```
/// use facetlab::render::photo::{turntable_period, PhotoLight, PhotoOptions};
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let opts = PhotoOptions::new(PhotoLight::studio());
/// // Eight-fold: a turn of 90° (9 of 36 frames) or 45° (3 of 24) repeats the picture.
/// assert_eq!(turntable_period(&cut.solid, &opts, 36), 9);
/// assert_eq!(turntable_period(&cut.solid, &opts, 24), 3);
/// assert_eq!(turntable_period(&cut.solid, &opts, 7), 7);
/// ```
pub fn turntable_period(solid: &Polyhedron, opts: &PhotoOptions, frames: usize) -> usize {
    let frames = frames.max(1);
    // The pose keeps the stone's axis vertical (face-up, or turned over).
    let axis = opts.tilt.rotation() * glam::DVec3::Z;
    let upright = axis.truncate().length() <= 1e-12;
    // A birefringent stone's optic axis must turn into itself too.
    let optic = !opts.material.birefringent()
        || crate::render::pose::canonical_optic_axis(solid, &opts.material)
            .truncate()
            .length()
            <= 1e-12;
    if !(upright && optic) {
        return frames;
    }
    let order = Stone::new(&canonical(solid)).symmetry().0.max(1);
    frames / gcd(frames, order)
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// Caption lines of a photograph (after the cut's name): the light, view and ground, and
/// the material the stone is traced in with its mean luminance.
pub fn caption(opts: &PhotoOptions, stats: &PhotoStats) -> Vec<String> {
    let v = opts.view;
    let view = if v.elevation_deg == 90.0 {
        "from above".to_string()
    } else if v.elevation_deg == 0.0 {
        "side view".to_string()
    } else {
        format!("{:.0}° above", v.elevation_deg)
    };
    let mut cam = match opts.distance_mm {
        Some(d) => format!("{view}, {d:.0} mm away"),
        None => view,
    };
    match opts.aperture_mm {
        Some(0.0) => cam.push_str(", pinhole"),
        Some(a) => cam.push_str(&format!(", {a} mm aperture")),
        None => {}
    }
    let mut first = format!("{}, {cam}", opts.light.name());
    if opts.ground.kind != super::GroundKind::None {
        first.push_str(&format!(", {} ground", opts.ground.kind.name()));
    }
    vec![
        first,
        format!("{}, mean {:.1} %", opts.material.name, 100.0 * stats.mean),
    ]
}
