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

pub mod lighting;
pub mod pose;
pub mod raster;

#[cfg(test)]
mod tests;

use crate::beam::{BeamTree, Frame, Stone, TraceOptions};
use crate::error::{Error, Result};
use crate::geometry::{canonical::canonical, clip2d, Polyhedron};
use crate::optics::{color, Dispersion, Material};
use glam::{DMat3, DVec2, DVec3};
use lighting::{aset_bins, soft_above, Lighting, Spot};
use raster::{Accumulator, Raster};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// One pose of the stone: its table normal tipped by `tilt_deg` toward azimuth
/// `azimuth_deg` (a negative tilt tips it the other way).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Tilt {
    /// Tilt angle, degrees.
    pub tilt_deg: f64,
    /// Azimuth the table normal tips toward, degrees from +x toward +y.
    pub azimuth_deg: f64,
}

impl Tilt {
    /// Face-up.
    pub const FACE_UP: Tilt = Tilt {
        tilt_deg: 0.0,
        azimuth_deg: 0.0,
    };

    /// Rotation taking stone coordinates to world coordinates.
    pub fn rotation(&self) -> DMat3 {
        let a = self.azimuth_deg.to_radians();
        DMat3::from_axis_angle(
            DVec3::new(-a.sin(), a.cos(), 0.0),
            self.tilt_deg.to_radians(),
        )
    }

    /// The default brilliance poses: face-up, five at 10° (azimuths 0°, 72°, …) and five at
    /// 20° (azimuths 36°, 108°, …). Five-fold azimuths sample every orientation of a 4- or
    /// 8-fold symmetric cut differently.
    pub fn default_set() -> Vec<Tilt> {
        let mut v = vec![Tilt::FACE_UP];
        for k in 0..5 {
            v.push(Tilt {
                tilt_deg: 10.0,
                azimuth_deg: 72.0 * k as f64,
            });
        }
        for k in 0..5 {
            v.push(Tilt {
                tilt_deg: 20.0,
                azimuth_deg: 36.0 + 72.0 * k as f64,
            });
        }
        v
    }
}

/// The lighting environment of a picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Light {
    /// GemRay's ISO lighting: radiance 1 over the upper hemisphere (grey image).
    Iso,
    /// GemRay's COS lighting: radiance = cos(zenith angle) (grey image).
    Cos,
    /// ASET false colour: blue for light from 75–90° elevation, red 45–75°, green 0–45°,
    /// black for leakage (below the horizon) and for the viewer's dark port at the top.
    Aset,
    /// IdealScope: red for returned light, white for leakage, black for the viewer's head.
    #[serde(rename = "idealscope")]
    IdealScope,
    /// The hearts & arrows viewer face-down: the stone turned over, pavilion to the viewer.
    Hearts,
    /// The hearts & arrows viewer face-up.
    Arrows,
    /// Spectral tracing under the spot lights ([`Spot::default_set`]), shown in sRGB.
    Fire,
}

/// Half-angle of the dark tube around the line of sight in the hearts & arrows viewer,
/// degrees: sight lines that leave the stone within it see the viewer's dark top, the rest see
/// the bright white wall.
pub const SCOPE_TUBE_DEG: f64 = 20.0;

/// Default half-angle of the ASET's dark viewing port and of IdealScope's head obstruction,
/// degrees.
pub const PORT_DEG: f64 = 10.0;

/// ASET's display colours (sRGB-encoded): blue, red, green, leak (black), port (black).
pub const ASET_COLOURS: [[f64; 3]; 5] = [
    [0.10, 0.30, 1.0],
    [0.90, 0.08, 0.08],
    [0.10, 0.72, 0.16],
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 0.0],
];

/// IdealScope's display colours (sRGB-encoded): returned (red), leak (white), head (black).
pub const IDEALSCOPE_COLOURS: [[f64; 3]; 3] =
    [[0.86, 0.10, 0.12], [1.0, 1.0, 1.0], [0.0, 0.0, 0.0]];

impl Light {
    /// Every light, in the order the command line lists them.
    pub const ALL: [Light; 7] = [
        Light::Iso,
        Light::Cos,
        Light::Aset,
        Light::IdealScope,
        Light::Hearts,
        Light::Arrows,
        Light::Fire,
    ];

    /// The name used on the command line and in files.
    pub fn name(self) -> &'static str {
        match self {
            Light::Iso => "iso",
            Light::Cos => "cos",
            Light::Aset => "aset",
            Light::IdealScope => "idealscope",
            Light::Hearts => "hearts",
            Light::Arrows => "arrows",
            Light::Fire => "fire",
        }
    }

    /// The light called `name` (as [`Light::name`] gives it).
    pub fn parse(name: &str) -> Result<Light> {
        Light::ALL
            .into_iter()
            .find(|l| l.name() == name)
            .ok_or_else(|| {
                Error::invalid(
                    "light",
                    format!(
                        "unknown light {name:?}; allowed {}",
                        Light::ALL.map(Light::name).join(", ")
                    ),
                )
            })
    }

    /// Default head shadow (ISO, COS, fire: none, as the scores; ASET's port and IdealScope's
    /// head: [`PORT_DEG`]; the hearts & arrows viewer has its own tube, [`SCOPE_TUBE_DEG`]).
    pub fn default_head_shadow_deg(self) -> f64 {
        match self {
            Light::Aset | Light::IdealScope => PORT_DEG,
            _ => 0.0,
        }
    }

    /// Number of channels of the picture: 1 (grey), 3 (fire: linear sRGB, IdealScope:
    /// returned, leak, head) or 5 (ASET: blue, red, green, leak, port).
    pub fn channels(self) -> usize {
        match self {
            Light::Iso | Light::Cos | Light::Hearts | Light::Arrows => 1,
            Light::Fire | Light::IdealScope => 3,
            Light::Aset => 5,
        }
    }

    /// The picture's channel values for light arriving from direction `w` (world coordinates,
    /// z up, the viewer straight above; `light` gives the head shadow), and the value that
    /// counts toward [`Stats::mean`]:
    ///
    /// * `iso`, `cos`: the radiance of [`Lighting::iso`] or [`Lighting::cos`];
    /// * `hearts`, `arrows`: radiance 1 from the viewer's bright wall, 0 within
    ///   [`SCOPE_TUBE_DEG`] of the line of sight (the dark tube) and below the horizon, soft
    ///   edges;
    /// * `aset`: the shares of the ASET bins (blue, red, green, leak, port; the port is the
    ///   head shadow's cone), which add up to 1; the mean counts blue, red and green;
    /// * `idealscope`: returned (above the horizon, outside the head), leak (below the
    ///   horizon) and head shares, adding up to 1; the mean counts the returned share.
    ///
    /// Not used for [`Light::Fire`], which is spectral (zeros).
    #[inline]
    pub fn shade(self, light: &Lighting, w: DVec3) -> ([f64; 5], f64) {
        match self {
            Light::Iso => {
                let v = light.iso(w);
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Cos => {
                let v = light.cos(w);
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Hearts | Light::Arrows => {
                let zen = 90.0 - lighting::elevation_deg(w);
                let v = soft_above(zen, SCOPE_TUBE_DEG) * (1.0 - soft_above(zen, 90.0));
                ([v, 0.0, 0.0, 0.0, 0.0], v)
            }
            Light::Aset => {
                let b = aset_bins(w);
                let head = light.head(w);
                let s = [
                    b[0] * head,
                    b[1] * head,
                    b[2] * head,
                    b[3],
                    (1.0 - head) * (1.0 - b[3]),
                ];
                (s, s[0] + s[1] + s[2])
            }
            Light::IdealScope => {
                let returned = light.iso(w);
                let sky = soft_above(lighting::elevation_deg(w), 0.0);
                let leak = 1.0 - sky;
                (
                    [returned, leak, (sky - returned).max(0.0), 0.0, 0.0],
                    returned,
                )
            }
            Light::Fire => ([0.0; 5], 0.0),
        }
    }

    /// Display colours (sRGB-encoded, 0–1) of the channels of a false-colour picture (ASET,
    /// IdealScope): a pixel shows the mix of these by its channels' shares.
    pub fn false_colours(self) -> &'static [[f64; 3]] {
        match self {
            Light::Aset => &ASET_COLOURS,
            Light::IdealScope => &IDEALSCOPE_COLOURS,
            _ => &[],
        }
    }
}

/// What to draw and how.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderOptions {
    /// The lighting environment.
    pub light: Light,
    /// Pixels per side (square image).
    pub size: usize,
    /// Pose of the stone (the viewer stays straight above).
    pub tilt: Tilt,
    /// Head shadow, ASET port or IdealScope head half-angle, degrees; `None` for the light's
    /// default ([`Light::default_head_shadow_deg`]).
    pub head_shadow_deg: Option<f64>,
    /// The stone's material.
    pub material: Material,
    /// Wavelength of the single-wavelength lights, nm.
    pub wavelength_nm: f64,
    /// Track polarization (default on).
    pub polarization: bool,
    /// Wavelength bands of the fire picture (≥ 8 by default; faint ones share a neighbour's
    /// trace, [`color::traced_bands`]).
    pub bands: usize,
    /// Spot lights of the fire picture.
    pub spots: Vec<Spot>,
    /// Tracer settings (footprints are switched on here). The default splits beams down to
    /// [`RenderOptions::SPLIT_THRESHOLD`] of the light, as the scores' face-up traces do.
    pub trace: TraceOptions,
}

impl RenderOptions {
    /// Default split threshold: the scores' face-up one, so that a face-up picture and the
    /// scores are the very same trace.
    pub const SPLIT_THRESHOLD: f64 = 1e-5;

    /// Default options for `light`: 512 pixels, face-up, diamond at 589.3 nm, 8 bands.
    pub fn new(light: Light) -> RenderOptions {
        RenderOptions {
            light,
            size: 512,
            tilt: Tilt::FACE_UP,
            head_shadow_deg: None,
            material: Material::diamond(),
            wavelength_nm: 589.3,
            polarization: true,
            bands: 8,
            spots: Spot::default_set(),
            trace: TraceOptions {
                split_threshold: Self::SPLIT_THRESHOLD,
                ..TraceOptions::default()
            },
        }
    }

    /// The head shadow in use.
    pub fn head_shadow(&self) -> f64 {
        self.head_shadow_deg
            .unwrap_or_else(|| self.light.default_head_shadow_deg())
    }

    /// Check every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        if !(8..=8192).contains(&self.size) {
            return Err(Error::invalid(
                "size",
                format!("{} pixels is out of range; allowed 8 to 8192", self.size),
            ));
        }
        let t = self.tilt;
        if !(t.tilt_deg.abs() <= 90.0 && t.azimuth_deg.is_finite()) {
            return Err(Error::invalid(
                "tilt",
                format!("{}° is out of range; allowed −90 to 90 degrees", t.tilt_deg),
            ));
        }
        let h = self.head_shadow();
        if !(0.0..=60.0).contains(&h) {
            return Err(Error::invalid(
                "head-shadow",
                format!("{h}° is out of range; allowed 0 to 60 degrees (0 = none)"),
            ));
        }
        if !(380.0..=780.0).contains(&self.wavelength_nm) {
            return Err(Error::invalid(
                "wavelength",
                format!(
                    "{} nm is outside the visible range; allowed 380 to 780 nm",
                    self.wavelength_nm
                ),
            ));
        }
        if self.light == Light::Fire && !(8..=64).contains(&self.bands) {
            return Err(Error::invalid(
                "bands",
                format!("{} is out of range; allowed 8 to 64", self.bands),
            ));
        }
        for l in [self.wavelength_nm, 380.0, 780.0] {
            let n = self.material.ri(l);
            if !(n.is_finite() && n > 1.0 - 1e-12 && n <= 10.0) {
                return Err(Error::invalid(
                    "material",
                    format!(
                        "{} has refractive index {n} at {l} nm; allowed [1, 10]",
                        self.material.name
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// ASET shares of a picture: the share of the stone's outline (by light, each sight line
/// weighted by its Fresnel power) in each colour. They add up to 1 with the light cut off by
/// the tracer's thresholds (a few 1e-6).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct AsetShares {
    /// Light from 75–90° elevation, outside the port.
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

/// Statistics of a picture, computed from the exit beams that make its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Stats {
    /// Mean of the picture over the stone's outline, relative to a white diffuser (luminance
    /// Y for colour pictures): for `iso` and `cos`, that pose's brilliance value.
    pub mean: f64,
    /// ASET shares (ASET pictures only).
    pub aset: Option<AsetShares>,
    /// Fire of the picture ([`fire_of`] over its band images; fire pictures only).
    pub fire: Option<f64>,
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
        let mut out = Vec::with_capacity(n * n * 3);
        let byte = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        for j in 0..n {
            for i in 0..n {
                let k = (n - 1 - j) * n + i;
                let a = self.coverage.data[k].clamp(0.0, 1.0);
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
                    [r, g, b] => [r, g, b]
                        .map(|ch| color::srgb_encode(ch.data[k] * exposure))
                        .iter()
                        .zip(bg)
                        .map(|(v, b)| v + b)
                        .collect::<Vec<f64>>()
                        .try_into()
                        .unwrap_or([0.0; 3]),
                    _ => bg,
                };
                out.extend(c.map(byte));
            }
        }
        out
    }
}

/// Rotation taking the stone's coordinates to the world's for a picture: the pose, after
/// turning the stone over for the hearts view (a half-turn about the x axis).
pub fn view_rotation(light: Light, tilt: Tilt) -> DMat3 {
    let r = tilt.rotation();
    if light == Light::Hearts {
        r * DMat3::from_rotation_x(std::f64::consts::PI)
    } else {
        r
    }
}

/// Half the side of the square a picture of `solid` (in its canonical placement) spans: its
/// largest distance from the centroid, plus 0.1 %. The same for every pose, so that the
/// frames of a rocking stone share one pixel grid (scintillation compares them pixel by
/// pixel), and the same for the scores' images and the pictures.
pub fn picture_half(solid: &Polyhedron) -> f64 {
    solid
        .vertices()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f64::max)
        * 1.001
}

/// One traced picture layer: its exits with footprints and each exit's values per unit of
/// footprint (one per channel).
struct Layer {
    tree: BeamTree,
    /// Per exit: values per unit area, one per channel.
    values: Vec<[f64; 5]>,
    /// Per exit: smallest and largest y of its footprint.
    ys: Vec<(f64, f64)>,
}

impl Layer {
    fn new(tree: BeamTree, channels: usize, value: impl Fn(usize) -> [f64; 5]) -> Layer {
        let area = tree.stats.area;
        let mut values = Vec::with_capacity(tree.exits.len());
        let mut ys = Vec::with_capacity(tree.exits.len());
        for (i, e) in tree.exits.iter().enumerate() {
            let fp = tree.footprint(i);
            let a = clip2d::area(fp);
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in fp {
                lo = lo.min(p.y);
                hi = hi.max(p.y);
            }
            ys.push((lo, hi));
            let mut v = [0.0; 5];
            if a > 0.0 && e.power > 0.0 {
                // Radiance through this beam: its power per unit of footprint, relative to
                // the incoming power per unit of cross-section.
                let c = value(i);
                let k = e.power * area / a;
                for ch in 0..channels {
                    v[ch] = c[ch] * k;
                }
            }
            values.push(v);
        }
        Layer { tree, values, ys }
    }
}

/// Rows per band of the parallel fill.
const BAND_ROWS: usize = 64;

/// Fill `channels` images of `size` pixels over `[−half, half]²` from the layers (each
/// layer's channel values added to the same images), in bands of rows in parallel; each
/// pixel receives its footprints in the layers' order, so the result does not depend on the
/// number of threads.
fn fill(layers: &[Layer], channels: usize, size: usize, half: f64) -> Vec<Raster> {
    let proto = Raster::new(size, half);
    let h = proto.pixel();
    let bands: Vec<(usize, usize)> = (0..size)
        .step_by(BAND_ROWS)
        .map(|j| (j, (j + BAND_ROWS).min(size)))
        .collect();
    let parts: Vec<Vec<Vec<f64>>> = bands
        .par_iter()
        .map(|&(j0, j1)| {
            let (ylo, yhi) = (-half + j0 as f64 * h, -half + j1 as f64 * h);
            let mut acc = Accumulator::new(size, half, (j0, j1), channels);
            for layer in layers {
                for (i, v) in layer.values.iter().enumerate() {
                    let (lo, hi) = layer.ys[i];
                    if hi < ylo || lo > yhi || v[..channels].iter().all(|&x| x == 0.0) {
                        continue;
                    }
                    acc.add_polygon(layer.tree.footprint(i), &v[..channels]);
                }
            }
            acc.finish()
        })
        .collect();
    (0..channels)
        .map(|ch| {
            let mut r = Raster::new(size, half);
            for (part, &(j0, _)) in parts.iter().zip(&bands) {
                let p = &part[ch];
                r.data[j0 * size..j0 * size + p.len()].copy_from_slice(p);
            }
            r
        })
        .collect()
}

/// Draw `solid` as `opts` says. The solid is first put in its canonical placement
/// ([`canonical`]: centred, unit size; not turned), so a moved or rescaled copy gives the
/// same picture; the picture spans [`picture_half`] around the centroid. Options should
/// have passed [`RenderOptions::validate`]; out-of-range values never panic.
pub fn render(solid: &Polyhedron, opts: &RenderOptions) -> Image {
    let solid = canonical(solid);
    let stone = Stone::new(&solid);
    let rot = view_rotation(opts.light, opts.tilt);
    let frame = Frame::viewer(rot);
    let size = opts.size.max(1);
    let half = picture_half(&solid);
    let trace_opts = TraceOptions {
        polarization: opts.polarization,
        footprints: true,
        ..opts.trace
    };
    let lighting = Lighting::new(opts.head_shadow(), &opts.spots);
    let mut stats = Stats {
        size,
        ..Stats::default()
    };
    let (channels, layers) = if opts.light == Light::Fire {
        // Faint bands (far out in the red) take a neighbour's trace, as in the scores.
        let bands = color::traced_bands(opts.bands.max(1), color::FAINT_BAND);
        let centres: Vec<f64> = bands.iter().map(|b| b.0).collect();
        let weights: Vec<DVec3> = bands.iter().map(|b| b.1).collect();
        let constant = matches!(opts.material.dispersion, Dispersion::Constant(_));
        let ri0 = opts.material.ri(opts.wavelength_nm);
        // One trace per band (one for all when the index does not change with wavelength).
        let traced: Vec<BeamTree> = if constant {
            vec![stone.trace(&frame, ri0, opts.wavelength_nm, &trace_opts)]
        } else {
            centres
                .par_iter()
                .map(|&l| stone.trace(&frame, opts.material.ri(l), l, &trace_opts))
                .collect()
        };
        // Each band's radiance image (one channel), then XYZ → linear sRGB per pixel.
        let band_layers: Vec<Layer> = traced
            .into_iter()
            .map(|t| {
                let v: Vec<f64> = t
                    .exits
                    .iter()
                    .map(|e| lighting.spots(rot * e.direction))
                    .collect();
                Layer::new(t, 1, |i| [v[i], 0.0, 0.0, 0.0, 0.0])
            })
            .collect();
        let band_images: Vec<Raster> = band_layers
            .par_iter()
            .map(|l| fill(std::slice::from_ref(l), 1, size, half).remove(0))
            .collect();
        let images: Vec<&Raster> = (0..bands.len())
            .map(|b| &band_images[if constant { 0 } else { b }])
            .collect();
        for l in &band_layers {
            stats.cut_off = stats.cut_off.max(l.tree.stats.cut_off);
            stats.exits += l.tree.exits.len();
        }
        let outline = band_layers[0].tree.stats.area;
        stats.fire = Some(fire_of(&images, &weights, outline));
        let mut rgb = vec![Raster::new(size, half); 3];
        let mut y_sum = 0.0;
        for p in 0..size * size {
            let xyz: DVec3 = images
                .iter()
                .zip(&weights)
                .map(|(img, w)| *w * img.data[p])
                .sum();
            y_sum += xyz.y;
            let c = color::xyz_to_linear_srgb(xyz).max(DVec3::ZERO);
            rgb[0].data[p] = c.x;
            rgb[1].data[p] = c.y;
            rgb[2].data[p] = c.z;
        }
        let h = rgb[0].pixel();
        stats.mean = if outline > 0.0 {
            y_sum * h * h / outline
        } else {
            0.0
        };
        (rgb, band_layers)
    } else {
        let tree = stone.trace(
            &frame,
            opts.material.ri(opts.wavelength_nm),
            opts.wavelength_nm,
            &trace_opts,
        );
        let n = opts.light.channels();
        let shades: Vec<([f64; 5], f64)> = tree
            .exits
            .iter()
            .map(|e| opts.light.shade(&lighting, rot * e.direction))
            .collect();
        let (mut mean, mut bins) = (0.0, [0.0; 5]);
        for (e, (c, y)) in tree.exits.iter().zip(&shades) {
            mean += e.power * y;
            for (b, x) in bins.iter_mut().zip(c) {
                *b += e.power * x;
            }
        }
        let power_in = tree.stats.power_in;
        stats.mean = if power_in > 0.0 { mean / power_in } else { 0.0 };
        if opts.light == Light::Aset {
            let t: f64 = bins.iter().sum();
            let t = if t > 0.0 { t } else { 1.0 };
            stats.aset = Some(AsetShares {
                blue: bins[0] / t,
                red: bins[1] / t,
                green: bins[2] / t,
                leak: bins[3] / t,
                port: bins[4] / t,
            });
        }
        stats.cut_off = tree.stats.cut_off;
        stats.exits = tree.exits.len();
        let layer = Layer::new(tree, n, |i| shades[i].0);
        let layers = vec![layer];
        (fill(&layers, n, size, half), layers)
    };
    // The outline: the facets facing the viewer tile it.
    let entry = &layers[0].tree.frame;
    let mut outline = Accumulator::new(size, half, (0, size), 1);
    for (f, facet) in solid.facets().iter().enumerate() {
        if facet.plane.normal.dot(entry.dir) < 0.0 {
            let poly: Vec<DVec2> = solid
                .facet_polygon(f)
                .iter()
                .map(|p| DVec2::new(p.dot(entry.u), p.dot(entry.v)))
                .collect();
            outline.add_polygon(&poly, &[1.0]);
        }
    }
    let mut coverage = Raster::new(size, half);
    if let Some(c) = outline.finish().pop() {
        coverage.data = c;
    }
    Image {
        light: opts.light,
        channels,
        coverage,
        stats,
    }
}

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
    let mut yc = 0.0;
    for p in 0..first.data.len() {
        // A grey pixel (the same value in every band) has no saturation at all.
        let v = first.data[p];
        if images.iter().all(|img| img.data[p] == v) {
            continue;
        }
        let xyz: DVec3 = images
            .iter()
            .zip(weights)
            .map(|(img, w)| *w * img.data[p])
            .sum();
        if xyz.y > 0.0 {
            let lab = color::xyz_to_lab(xyz, white);
            if lab.x > 0.0 {
                yc += xyz.y * color::chroma(lab) / lab.x;
            }
        }
    }
    100.0 * yc * first.pixel().powi(2) / area
}
