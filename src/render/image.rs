//! A rendered picture ([`Image`]) and what is measured on it: its [`Stats`], the ASET shares
//! and the fire of a spectral picture ([`fire_of`]).

use super::light::Light;
use super::raster::Raster;
use crate::optics::color;
use glam::DVec3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// ASET shares of a picture: the share of the stone's outline (by light, each sight line
/// weighted by its Fresnel power) in each colour. They add up to 1 with the light cut off by
/// the tracer's thresholds (a few 1e-6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AsetShares {
    /// Light from 75–80° elevation (75–90° outside the port).
    pub blue: f64,
    /// Light from 45–75°.
    pub red: f64,
    /// Light from 0–45°.
    pub green: f64,
    /// Light from below the horizon.
    pub leak: f64,
    /// The viewer's dark port at the top (0 with a head shadow of 0).
    pub port: f64,
}

/// Light through the stone darker than this CIELAB lightness L* counts as extinct in
/// [`ColourStats::extinction`] (about the lightness of a dark charcoal grey beside a white
/// diffuser).
pub const EXTINCTION_L: f64 = 20.0;

/// Pixels per side of the grid every colour statistic ([`ColourStats`]) is measured on,
/// whatever the picture's size or the scores' resolution: one value per name. The
/// extinction, a share of pixels (each pixel's light averaged over it, then compared with
/// [`EXTINCTION_L`]), converges with the grid; a 9 mm tourmaline oval (`#1f5a36@10mm`) under
/// ISO light measured 0.0956, 0.1058, 0.1086, 0.1098, 0.1101, 0.1103 at 64 to 2048 pixels
/// (the error falling about 2.5× per doubling): at this grid 0.1086, within 0.002 of the
/// limit (about 0.1104). 512 pixels would come within 0.0006, but drawing the scores' colour
/// there took a coloured score 2.1× main's time (debug build), 256 1.4×. The L* spread
/// converges alike (6.11 to 6.43); the mean colour and windowing do not depend on the grid.
pub const COLOUR_GRID: usize = 256;

/// The colour of a coloured stone's picture (a body colour under a grey light), as faceters
/// judge it face-up: CIELAB relative to a white diffuser under D65.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ColourStats {
    /// L* of the mean colour over the stone's outline.
    pub l: f64,
    /// C*ab (chroma) of the mean colour.
    pub c: f64,
    /// Hue angle h°ab of the mean colour, degrees in [0, 360).
    pub h_deg: f64,
    /// Spread of the lightness: the standard deviation of the pixels' L* over the outline.
    pub l_spread: f64,
    /// Extinction: the share of the face-up outline under ISO light (the scores' view) where
    /// the light that comes through the stone (its surface reflection left out, as a faceter
    /// judges colour through the glare) is darker than [`EXTINCTION_L`], measured on the
    /// [`COLOUR_GRID`]. `None` for a picture at another light or pose, whose share is its
    /// [`ColourStats::dark_share`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extinction: Option<f64>,
    /// The same share of a picture at another light or pose than the scores' face-up ISO (a
    /// COS picture's, a tilted one's): not the extinction. `None` in the scores' view.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dark_share: Option<f64>,
    /// Windowing: the share of the light seen that comes from below the girdle plane (seen
    /// through the stone), weighted by luminance over the bands.
    pub windowing: f64,
}

impl ColourStats {
    /// From a picture's XYZ pixels (radiance times the covered share of each pixel) on the
    /// [`COLOUR_GRID`], the same of the light through the stone alone (`through`), the
    /// outline's `coverage` and the windowing share: the scores' view (its dark share is the
    /// [`ColourStats::extinction`]; see [`ColourStats::seen`]).
    pub(crate) fn of(
        xyz: &[DVec3],
        through: &[DVec3],
        coverage: &Raster,
        windowing: f64,
    ) -> ColourStats {
        let white = color::d65_white();
        let lab = |c: DVec3| color::xyz_to_lab(c, white);
        let (mut sum, mut area) = (DVec3::ZERO, 0.0);
        let (mut l1, mut l2, mut dark) = (0.0, 0.0, 0.0);
        for ((p, q), &a) in xyz.iter().zip(through).zip(&coverage.data) {
            if a <= 1e-9 {
                continue;
            }
            let a = a.min(1.0);
            sum += *p;
            area += a;
            let l = lab(*p / a).x;
            l1 += a * l;
            l2 += a * l * l;
            if lab(*q / a).x < EXTINCTION_L {
                dark += a;
            }
        }
        if area <= 0.0 {
            return ColourStats {
                extinction: Some(0.0),
                ..ColourStats::default()
            };
        }
        let mean = lab(sum / area);
        let spread = (l2 / area - (l1 / area).powi(2)).max(0.0).sqrt();
        ColourStats {
            l: mean.x,
            c: color::chroma(mean),
            h_deg: mean.z.atan2(mean.y).to_degrees().rem_euclid(360.0),
            l_spread: spread,
            extinction: Some(dark / area),
            dark_share: None,
            windowing,
        }
    }

    /// These statistics as a picture shows them: the extinction in the scores' view (`scores`:
    /// face-up under ISO light), else the same share named `dark_share`.
    pub(crate) fn seen(mut self, scores: bool) -> ColourStats {
        if !scores {
            self.dark_share = self.extinction.take().or(self.dark_share);
        }
        self
    }

    /// The share of the outline darker than [`EXTINCTION_L`], whichever name it has.
    pub fn dark(&self) -> f64 {
        self.extinction.or(self.dark_share).unwrap_or(f64::NAN)
    }
}

/// Statistics of a picture, computed from the exit beams that make its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Mean of the picture over the stone's outline, relative to a white diffuser (luminance
    /// Y for colour pictures): for `iso` and `cos`, that pose's brilliance value.
    pub mean: f64,
    /// ASET shares (ASET pictures only).
    pub aset: Option<AsetShares>,
    /// Fire of the picture ([`fire_of`] over its band images; fire pictures only): the fire
    /// of this one placement of the lights, named `placement_fire` in files (the score's
    /// `fire` averages the placements of [`crate::metrics::fire_placements`]).
    #[serde(rename = "placement_fire", alias = "fire")]
    pub fire: Option<f64>,
    /// The colour of a coloured stone's picture (a body colour under a grey light).
    pub colour: Option<ColourStats>,
    /// Pixels per side.
    pub size: usize,
    /// Share of the light cut off by the tracer's thresholds (largest over the bands).
    pub cut_off: f64,
    /// Exit beams drawn (all bands).
    pub exits: usize,
}

/// A rendered picture: linear channels relative to a white diffuser, black outside the stone.
#[derive(Clone, Debug)]
pub struct Image {
    /// The light it was drawn under.
    pub light: Light,
    /// Red, green and blue (linear sRGB); one channel for grey pictures.
    pub channels: Vec<Raster>,
    /// Share of each pixel covered by the stone's outline, [0, 1].
    pub coverage: Raster,
    /// Statistics of the picture.
    pub stats: Stats,
}

impl Image {
    /// Pixels per side.
    pub fn size(&self) -> usize {
        self.coverage.n
    }

    /// Channel values of pixel `(i, j)`, row `j` counted from the top (see
    /// [`Light::channels`]).
    pub fn pixel(&self, i: usize, j: usize) -> Vec<f64> {
        let n = self.size();
        let k = (n - 1 - j) * n + i;
        self.channels.iter().map(|c| c.data[k]).collect()
    }

    /// 8-bit sRGB, rows from the top, 3 bytes per pixel, over `background` (sRGB-encoded,
    /// 0–1) where the stone does not cover the pixel. Radiance pictures (grey, fire) are
    /// multiplied by `exposure`, clipped to [0, 1] and sRGB-encoded; false-colour pictures
    /// (ASET, IdealScope) mix their display colours ([`Light::false_colours`]) by the pixel's
    /// shares.
    pub fn to_srgb8(&self, exposure: f64, background: [f64; 3]) -> Vec<u8> {
        let n = self.size();
        let palette = self.light.false_colours();
        let byte = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        let mut out = vec![0u8; n * n * 3];
        // Rows in parallel (each pixel on its own: the same bytes on any number of threads).
        out.par_chunks_mut((n * 3).max(1))
            .enumerate()
            .for_each(|(j, row)| {
                for (i, px) in row.chunks_exact_mut(3).enumerate() {
                    let k = (n - 1 - j) * n + i;
                    let a = self.coverage.data[k].clamp(0.0, 1.0);
                    if a == 1.0 && palette.is_empty() {
                        // Inside the outline no background mixes in: the byte of the encoded
                        // value straight away (the same byte, without a power per channel).
                        match self.channels.as_slice() {
                            [g] => {
                                px.fill(color::srgb8(g.data[k] * exposure));
                                continue;
                            }
                            [r, g, b] => {
                                for (x, ch) in px.iter_mut().zip([r, g, b]) {
                                    *x = color::srgb8(ch.data[k] * exposure);
                                }
                                continue;
                            }
                            _ => {}
                        }
                    }
                    let bg = background.map(|b| (1.0 - a) * b);
                    let c: [f64; 3] = match self.channels.as_slice() {
                        _ if !palette.is_empty() => {
                            let mut c = bg;
                            for (ch, col) in self.channels.iter().zip(palette) {
                                for (x, y) in c.iter_mut().zip(col) {
                                    *x += ch.data[k] * y;
                                }
                            }
                            c
                        }
                        [g] => {
                            let v = color::srgb_encode(g.data[k] * exposure);
                            [0, 1, 2].map(|q| v + bg[q])
                        }
                        [r, g, b] => {
                            let v = [r, g, b].map(|ch| color::srgb_encode(ch.data[k] * exposure));
                            [0, 1, 2].map(|q| v[q] + bg[q])
                        }
                        _ => bg,
                    };
                    px.copy_from_slice(&c.map(byte));
                }
            });
        out
    }
}

/// Pixel `p`'s XYZ in a spectral picture: `Σ weights[b] · images[b]`, added in band order.
#[inline]
pub(super) fn pixel_xyz(images: &[&Raster], weights: &[DVec3], p: usize) -> DVec3 {
    images
        .iter()
        .zip(weights)
        .map(|(img, w)| *w * img.data[p])
        .sum()
}

/// Pixel `p`'s term of [`fire_of`]'s sum, `Y·s`, given its XYZ ([`pixel_xyz`]; asked for
/// only when needed) and the white: 0 for a grey pixel (the same value in every band), which
/// has no saturation at all.
#[inline]
pub(super) fn saturated_y(
    images: &[&Raster],
    p: usize,
    xyz: impl FnOnce() -> DVec3,
    white: DVec3,
) -> f64 {
    let v = images[0].data[p];
    if images.iter().all(|img| img.data[p] == v) {
        return 0.0;
    }
    let xyz = xyz();
    if xyz.y <= 0.0 {
        return 0.0;
    }
    let lab = color::xyz_to_lab(xyz, white);
    if lab.x > 0.0 {
        xyz.y * color::chroma(lab) / lab.x
    } else {
        0.0
    }
}

/// [`fire_of`] from the sum of its pixels' [`saturated_y`] terms.
pub(super) fn fire_from_sum(yc: f64, pixel: f64, area: f64) -> f64 {
    if area.is_nan() || area <= 0.0 {
        return 0.0;
    }
    100.0 * yc * pixel.powi(2) / area
}

/// Pictures at least this many pixels wide are summed row by row in parallel.
const PARALLEL_ROWS_FROM: usize = 256;

/// Saturated light of a spectral image in percent: `100 · Σ Y·s` over the pixels, times the
/// pixel area, divided by `area`, where `s = C*ab / L*` is the pixel's CIELAB saturation
/// (nearly independent of brightness, so the sum is linear in the light): `images[b]` is band `b`'s radiance image (relative to the
/// sources' radiance), `weights[b]` its XYZ weight (their sum is the white, Y = 1).
pub fn fire_of(images: &[&Raster], weights: &[DVec3], area: f64) -> f64 {
    let Some(first) = images.first() else {
        return 0.0;
    };
    if area.is_nan() || area <= 0.0 {
        return 0.0;
    }
    let white: DVec3 = weights.iter().copied().sum();
    let sum_over = |pixels: std::ops::Range<usize>| {
        pixels.fold(0.0, |yc, p| {
            yc + saturated_y(images, p, || pixel_xyz(images, weights, p), white)
        })
    };
    let (n, len) = (first.n, first.data.len());
    // A picture's rows in parallel, their sums added in row order (the same on any number of
    // threads); the scores' small images pixel by pixel, as they always were.
    let yc = if n >= PARALLEL_ROWS_FROM {
        let rows: Vec<f64> = (0..len.div_ceil(n))
            .into_par_iter()
            .map(|r| sum_over(r * n..((r + 1) * n).min(len)))
            .collect();
        rows.iter().sum()
    } else {
        sum_over(0..len)
    };
    fire_from_sum(yc, first.pixel(), area)
}
