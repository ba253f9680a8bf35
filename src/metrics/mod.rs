//! Scores of a cut, computed from beam trees: overhead light return, brilliance, fire,
//! scintillation and ASET-style shares.
//!
//! All scores except `overhead_light_return` come from an orthographic viewer straight above
//! the stone, traced backwards: each exit beam of the backward trace is a bundle of the
//! viewer's sight lines that end up looking out of the stone in one direction `w`, and it
//! shows whatever the environment sends from `w`. By reciprocity (unpolarized light sources, a
//! polarization-blind eye) the backward trace's powers are the forward light's. The stone is
//! *tilted* for the off-face-up poses; the environment and the viewer stay put in the world
//! (z up), exactly as when a stone is rocked under a lamp. Lighting is described in
//! [`lighting`]; every edge there is soft, and the images of [`raster`] use exact area
//! coverage, so that every score is a continuous function of the cut's proportions (the beam
//! tree itself is: footprints and powers move continuously, beams appear and vanish with zero
//! area, and Fresnel's reflectance is continuous through the critical angle). The remaining
//! small jumps come from the tracer's approximations below its thresholds
//! ([`TraceOptions`]): each is at most a narrow beam's power (< 1e-4 of the light by default).
//!
//! # The scores
//!
//! * **`overhead_light_return`** ∈ [0, 1]: the share of a parallel beam from straight above,
//!   over the stone's projected area, that leaves into the upper hemisphere (exit direction
//!   z > 0), external reflection included, at [`ScoreConfig::wavelength_nm`]. The photon
//!   tracer with directed light at 0° and no absorption measures the same thing. (Not
//!   continuous: a beam crossing the horizon jumps; it is the figure for cross-checks.)
//! * **`brilliance_iso`**, **`brilliance_cos`** ∈ [0, 1]: the light the viewer sees returned,
//!   as a share of what a perfect white diffuser of the same outline would show, under
//!   GemRay-style ISO lighting (radiance 1 over the upper hemisphere) and COS lighting
//!   (radiance = cosine of the angle from the zenith), both times the optional head shadow
//!   (a dark cone of half-angle [`ScoreConfig::head_shadow_deg`] around the viewer), averaged
//!   with equal weights over the poses [`ScoreConfig::tilts`] (face-up and two rings of
//!   tilted poses by default) — GIA's weighted light return in spirit.
//!   **`brilliance`** = (ISO + COS) / 2.
//! * **`fire`** ≥ 0, in percent (0.7 for a Tolkowsky diamond, 1.2 for the same cut in cubic
//!   zirconia): saturated colour under small light sources. The face-up view is traced at
//!   [`ScoreConfig::bands`] wavelengths (band centres across 380–780 nm); each band's image of
//!   the spot lights ([`lighting::Spot::default_set`], seven 5° spots of radiance 1) is
//!   rasterised with exact footprint coverage; each pixel's spectrum becomes CIE XYZ with
//!   D65-weighted CIE 1931 bands ([`color::band_weights_d65`]) and then CIELAB relative to
//!   the D65 white of the spots' radiance (Y = 1). Fire is `100 · Σ Y·s` over the face-up
//!   outline per unit of its area, `s = C*ab / L*` the pixel's saturation: coloured light per
//!   unit of face-up area. `s` hardly depends on brightness, so fire is linear in the light
//!   and one concentrated flash cannot dominate (luminance × chroma grows like Y^4/3 and did).
//!   Fire is averaged over [`ScoreConfig::fire_placements`] placements of the spot set
//!   ([`fire_lightings`]: turned by golden angles, raised or lowered by up to 4.5°), as a
//!   viewer sees a stone under lights in many places: with one placement a coloured flash
//!   crossing one spot's rim made fire jump sevenfold within 0.1° of pavilion angle; averaged,
//!   the same neighbourhood varies by under 1.5×. A material without dispersion gives
//!   identical bands, hence grey pixels, hence 0 (to rounding). Fire's traces split down to
//!   [`ScoreConfig::fire_split_threshold`] (1e-5), ten times finer than the others.
//! * **`scintillation`** ∈ [0, 1]: how much the face-up pattern of bright and dark changes as
//!   the stone rocks. The image of the spot lights at [`ScoreConfig::wavelength_nm`] is taken
//!   at each tilt of [`ScoreConfig::scintillation_tilts`] (rocking about the x axis,
//!   −6°…6° in 2° steps by default); the score is `Σₖ Σₚ |Iₖ₊₁ − Iₖ| / Σₖ Σₚ (Iₖ₊₁ + Iₖ)`: 0 when
//!   nothing changes, 1 when consecutive patterns never overlap.
//! * **`aset`** `{blue, red, green, leak}`, each ∈ [0, 1], sum 1: the shares of the face-up
//!   view (by power, over the traced light; cut-off light excluded) whose sight lines leave
//!   the stone toward 75–90° elevation (blue), 45–75° (red), 0–45° (green) or below the
//!   horizon (leak), with ±1° soft boundaries. No head obstruction is applied: in a real ASET
//!   the viewing port at the top is dark; here that light counts as blue.

pub mod lighting;
pub mod raster;

#[cfg(test)]
mod golden;
#[cfg(test)]
mod tests;

use crate::beam::{ExitBeam, ExitSink, Frame, Stone, TraceOptions};
use crate::error::{Error, Result};
use crate::geometry::{clip2d, Polyhedron};
use crate::optics::{color, Dispersion, Material};
use glam::{DMat3, DVec2, DVec3};
use lighting::{aset_bins, Lighting, Spot};
use raster::Raster;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Wavelength of the single-wavelength scores: the sodium D line, nm.
pub const REFERENCE_WAVELENGTH_NM: f64 = 589.3;

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

/// What to score and how.
#[derive(Clone, Debug, PartialEq)]
pub struct ScoreConfig {
    /// The stone's material (a constant index gives no dispersion and no fire).
    pub material: Material,
    /// Wavelength of the single-wavelength scores (light return, brilliance, ASET,
    /// scintillation), nm. Default 589.3.
    pub wavelength_nm: f64,
    /// Track polarization (default on).
    pub polarization: bool,
    /// Half-angle of the viewer's head shadow around the zenith, degrees; 0 = none (default).
    pub head_shadow_deg: f64,
    /// Poses averaged for brilliance. Default [`Tilt::default_set`].
    pub tilts: Vec<Tilt>,
    /// Spot lights for fire and scintillation. Default [`Spot::default_set`].
    pub spots: Vec<Spot>,
    /// Wavelength bands for fire (equal bands across 380–780 nm). Default 8.
    pub bands: usize,
    /// Rocking sequence for scintillation: tilts about the x axis, degrees, in order.
    /// Default −6°, −4°, …, 6°.
    pub scintillation_tilts: Vec<f64>,
    /// Pixels per side of the fire and scintillation images. Default 64.
    pub resolution: usize,
    /// Placements of the spot lights that fire is averaged over ([`fire_lightings`]).
    /// Default 8.
    pub fire_placements: usize,
    /// Tracer settings (footprints are switched on where needed).
    pub trace: TraceOptions,
    /// Split threshold of the face-up traces for fire, overhead light return and ASET (see
    /// [`TraceOptions::split_threshold`]): fire's spot images are the most sensitive to the
    /// narrow-beam approximation, overhead light return is the figure checked against the
    /// photon tracer, and face-up traces of symmetric stones are cheap. Default 1e-5.
    pub fire_split_threshold: f64,
}

impl Default for ScoreConfig {
    fn default() -> Self {
        ScoreConfig {
            material: Material::diamond(),
            wavelength_nm: REFERENCE_WAVELENGTH_NM,
            polarization: true,
            head_shadow_deg: 0.0,
            tilts: Tilt::default_set(),
            spots: Spot::default_set(),
            bands: 8,
            scintillation_tilts: (-3..=3).map(|k| 2.0 * k as f64).collect(),
            resolution: 64,
            fire_placements: 8,
            trace: TraceOptions::default(),
            fire_split_threshold: 1e-5,
        }
    }
}

impl ScoreConfig {
    /// A quicker configuration for searches: narrow beams from 1e-3 of the light, 6 bands,
    /// face-up plus five poses at 15°, five rocking steps, 48 pixels. Brilliance stays within
    /// about 1e-3 of the default configuration; fire and scintillation are much coarser
    /// (tens of percent).
    pub fn fast() -> ScoreConfig {
        ScoreConfig {
            tilts: std::iter::once(Tilt::FACE_UP)
                .chain((0..5).map(|k| Tilt {
                    tilt_deg: 15.0,
                    azimuth_deg: 72.0 * k as f64,
                }))
                .collect(),
            bands: 6,
            scintillation_tilts: vec![-6.0, -3.0, 0.0, 3.0, 6.0],
            resolution: 48,
            fire_placements: 4,
            trace: TraceOptions {
                split_threshold: 1e-3,
                ..TraceOptions::default()
            },
            fire_split_threshold: 1e-4,
            ..ScoreConfig::default()
        }
    }

    /// Check every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        let w = self.wavelength_nm;
        if !(380.0..=780.0).contains(&w) {
            return Err(Error::invalid(
                "wavelength",
                format!("{w} nm is outside the visible range; allowed [380, 780] nm"),
            ));
        }
        for (what, l) in [("wavelength", w), ("bands", 380.0), ("bands", 780.0)] {
            let n = self.material.ri(l);
            if !(n.is_finite() && n > 1.0 && n <= 10.0) {
                return Err(Error::invalid(
                    what,
                    format!(
                        "material {} has refractive index {n} at {l} nm; allowed (1, 10]",
                        self.material.name
                    ),
                ));
            }
        }
        let h = self.head_shadow_deg;
        if !(0.0..=60.0).contains(&h) {
            return Err(Error::invalid(
                "head-shadow",
                format!("{h}° is out of range; allowed [0, 60] degrees (0 = no head shadow)"),
            ));
        }
        if self.tilts.is_empty() {
            return Err(Error::invalid("tilts", "at least one pose is needed"));
        }
        for t in &self.tilts {
            if !(t.tilt_deg.abs() <= 60.0 && t.azimuth_deg.is_finite()) {
                return Err(Error::invalid(
                    "tilts",
                    format!("{t:?}: tilts must be within ±60°"),
                ));
            }
        }
        for s in &self.spots {
            if !(s.elevation_deg.abs() <= 90.0
                && s.azimuth_deg.is_finite()
                && s.radius_deg > 0.0
                && s.radius_deg <= 45.0)
            {
                return Err(Error::invalid(
                    "spots",
                    format!("{s:?}: elevation within ±90°, radius in (0, 45]°"),
                ));
            }
        }
        if !(1..=64).contains(&self.bands) {
            return Err(Error::invalid(
                "bands",
                format!("{} is out of range; allowed 1 to 64", self.bands),
            ));
        }
        if self.scintillation_tilts.len() < 2
            || self
                .scintillation_tilts
                .iter()
                .any(|t| t.is_nan() || t.abs() > 60.0)
        {
            return Err(Error::invalid(
                "scintillation-tilts",
                "at least two tilts, each within ±60°",
            ));
        }
        if !(8..=1024).contains(&self.resolution) {
            return Err(Error::invalid(
                "resolution",
                format!(
                    "{} is out of range; allowed 8 to 1024 pixels",
                    self.resolution
                ),
            ));
        }
        let t = &self.trace;
        if !(t.threshold >= 0.0
            && t.threshold < 1.0
            && self.fire_split_threshold >= 0.0
            && self.fire_split_threshold < 1.0
            && t.split_threshold >= 0.0
            && t.split_threshold < 1.0)
        {
            return Err(Error::invalid(
                "threshold",
                "power thresholds must be in [0, 1)",
            ));
        }
        Ok(())
    }
}

/// ASET-style shares of the face-up view; they add up to 1.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Aset {
    /// Light from 75–90° elevation.
    pub blue: f64,
    /// Light from 45–75° elevation.
    pub red: f64,
    /// Light from 0–45° elevation.
    pub green: f64,
    /// Light from below the horizon (seen through the stone).
    pub leak: f64,
}

/// The scores of one cut (see the module documentation for definitions and ranges).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Scores {
    /// Share of overhead parallel light leaving upward, [0, 1].
    pub overhead_light_return: f64,
    /// (ISO + COS) / 2, [0, 1].
    pub brilliance: f64,
    /// Light return under ISO lighting, averaged over poses, [0, 1].
    pub brilliance_iso: f64,
    /// Light return under COS lighting, averaged over poses, [0, 1].
    pub brilliance_cos: f64,
    /// Luminance-weighted CIELAB chroma per unit face-up area under spot lights, ≥ 0.
    pub fire: f64,
    /// Change of the spot-light pattern while rocking, [0, 1].
    pub scintillation: f64,
    /// ASET-style shares of the face-up view.
    pub aset: Aset,
}

/// Share of a parallel beam from straight above, over the stone's projected area, that leaves
/// into the upper hemisphere (external reflection included), for `material` at
/// `wavelength_nm`, with the default tracer settings.
pub fn overhead_light_return(
    solid: &Polyhedron,
    material: &Material,
    wavelength_nm: f64,
    polarization: bool,
) -> f64 {
    let opts = TraceOptions {
        polarization,
        split_threshold: ScoreConfig::default().fire_split_threshold,
        ..Default::default()
    };
    overhead_light_return_with(&Stone::new(solid), material.ri(wavelength_nm), &opts)
}

/// [`overhead_light_return`] on a prepared stone at index `ri` with explicit settings.
pub fn overhead_light_return_with(stone: &Stone, ri: f64, opts: &TraceOptions) -> f64 {
    struct Up(f64);
    impl ExitSink for Up {
        fn exit(&mut self, e: &ExitBeam, _: &[DVec2]) {
            if e.direction.z > 0.0 {
                self.0 += e.power;
            }
        }
    }
    let mut up = Up(0.0);
    let opts = TraceOptions {
        footprints: false,
        ..*opts
    };
    let (stats, _) = stone.trace_into(&Frame::overhead(), ri, &opts, &mut up, false);
    if stats.power_in > 0.0 {
        up.0 / stats.power_in
    } else {
        0.0
    }
}

/// One backward trace from the viewer at one pose and index, and what to measure on it.
#[derive(Clone, Copy, Debug)]
struct Job {
    tilt: Tilt,
    ri: f64,
    /// Spot-light images: one per lighting of [`fire_lightings`] used (0 = none; 1 for
    /// scintillation, all of them for fire).
    images: usize,
    /// ISO and COS sums (brilliance).
    brilliance: bool,
    /// Upward share and ASET bins (face-up).
    face_up: bool,
    /// Split threshold of this trace.
    split: f64,
}

/// What a [`Job`] measured.
#[derive(Clone, Debug, Default)]
struct PoseResult {
    power_in: f64,
    traced: f64,
    up: f64,
    iso: f64,
    cos: f64,
    aset: [f64; 4],
    images: Vec<Raster>,
}

struct PoseSink<'a> {
    rot: DMat3,
    light: &'a Lighting,
    spots: &'a [Lighting],
    area: f64,
    job: Job,
    r: PoseResult,
}

impl ExitSink for PoseSink<'_> {
    fn wants_footprints(&self) -> bool {
        !self.r.images.is_empty()
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        let w = self.rot * e.direction;
        let p = e.power;
        let r = &mut self.r;
        if self.job.face_up {
            r.traced += p;
            if w.z > 0.0 {
                r.up += p;
            }
            let b = aset_bins(w);
            for (acc, x) in r.aset.iter_mut().zip(b) {
                *acc += p * x;
            }
        }
        if self.job.brilliance {
            r.iso += p * self.light.iso(w);
            r.cos += p * self.light.cos(w);
        }
        for (img, light) in r.images.iter_mut().zip(self.spots) {
            if light.near_spot(w) {
                let l = light.spots(w);
                let a = clip2d::area(fp);
                if l > 0.0 && a > 0.0 {
                    // Radiance through this beam: its power per unit of footprint, relative to
                    // the incoming power per unit of cross-section.
                    img.add_polygon(fp, l * p * self.area / a);
                }
            }
        }
    }
}

fn run_job(
    stone: &Stone,
    solid: &Polyhedron,
    job: &Job,
    light: &Lighting,
    spots: &[Lighting],
    cfg: &ScoreConfig,
    half: f64,
) -> PoseResult {
    let rot = job.tilt.rotation();
    let frame = Frame::viewer(rot);
    let opts = TraceOptions {
        polarization: cfg.polarization,
        footprints: job.images > 0,
        split_threshold: job.split,
        ..cfg.trace
    };
    let mut sink = PoseSink {
        rot,
        light,
        spots: &spots[..job.images.min(spots.len())],
        area: solid.projected_area(-frame.dir),
        job: *job,
        r: PoseResult {
            images: (0..job.images.min(spots.len()))
                .map(|_| Raster::new(cfg.resolution, half))
                .collect(),
            ..Default::default()
        },
    };
    let (stats, _) = stone.trace_into(&frame, job.ri, &opts, &mut sink, false);
    sink.r.power_in = stats.power_in;
    sink.r
}

/// Score `solid` (see the module documentation). The configuration should have passed
/// [`ScoreConfig::validate`]; out-of-range values are not checked here but never panic.
/// Poses and wavelengths are traced in parallel with rayon and combined in a fixed order, so
/// the result does not depend on the number of threads.
pub fn score(solid: &Polyhedron, cfg: &ScoreConfig) -> Scores {
    let stone = Stone::new(solid);
    let light = Lighting::new(cfg.head_shadow_deg, &cfg.spots);
    let spot_sets = fire_lightings(cfg);
    let half = solid
        .vertices()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f64::max)
        * 1.001;
    let ri0 = cfg.material.ri(cfg.wavelength_nm);
    let bands = cfg.bands.max(1);
    let centres = color::band_centres(bands);
    // Distinct traces, each shared by every score that needs it (same pose, same index).
    let mut jobs: Vec<Job> = Vec::new();
    #[derive(Clone, Copy)]
    enum Use {
        FaceUp,
        Brilliance,
        Image(usize),
    }
    let index = |tilt: Tilt, ri: f64, what: Use, split: f64, jobs: &mut Vec<Job>| -> usize {
        let same = |j: &Job| j.tilt == tilt && j.ri.to_bits() == ri.to_bits() && j.split == split;
        let k = match jobs.iter().position(same) {
            Some(k) => k,
            None => {
                jobs.push(Job {
                    tilt,
                    ri,
                    images: 0,
                    brilliance: false,
                    face_up: false,
                    split,
                });
                jobs.len() - 1
            }
        };
        match what {
            Use::FaceUp => jobs[k].face_up = true,
            Use::Brilliance => jobs[k].brilliance = true,
            Use::Image(n) => jobs[k].images = jobs[k].images.max(n),
        }
        k
    };
    let split = cfg.trace.split_threshold;
    // The face-up figures (overhead light return, ASET) are the cross-checked ones: trace them
    // as finely as fire's images (cheap: a face-up stone traces one symmetry wedge).
    let face_up = index(
        Tilt::FACE_UP,
        ri0,
        Use::FaceUp,
        cfg.fire_split_threshold,
        &mut jobs,
    );
    let brill: Vec<usize> = cfg
        .tilts
        .iter()
        .map(|t| index(*t, ri0, Use::Brilliance, split, &mut jobs))
        .collect();
    let constant = matches!(cfg.material.dispersion, Dispersion::Constant(_));
    let fire: Vec<usize> = centres
        .iter()
        .map(|&l| {
            index(
                Tilt::FACE_UP,
                if constant { ri0 } else { cfg.material.ri(l) },
                Use::Image(spot_sets.len()),
                cfg.fire_split_threshold,
                &mut jobs,
            )
        })
        .collect();
    let scint: Vec<usize> = cfg
        .scintillation_tilts
        .iter()
        .map(|&t| {
            index(
                Tilt {
                    tilt_deg: t,
                    azimuth_deg: 90.0,
                },
                ri0,
                Use::Image(1),
                split,
                &mut jobs,
            )
        })
        .collect();
    let results: Vec<PoseResult> = jobs
        .par_iter()
        .map(|j| run_job(&stone, solid, j, &light, &spot_sets, cfg, half))
        .collect();

    let norm = |r: &PoseResult, x: f64| {
        if r.power_in > 0.0 {
            x / r.power_in
        } else {
            0.0
        }
    };
    let fu = &results[face_up];
    let n = brill.len().max(1) as f64;
    let brilliance_iso = brill
        .iter()
        .map(|&k| norm(&results[k], results[k].iso))
        .sum::<f64>()
        / n;
    let brilliance_cos = brill
        .iter()
        .map(|&k| norm(&results[k], results[k].cos))
        .sum::<f64>()
        / n;
    let a = fu.aset;
    let at: f64 = a.iter().sum();
    let aset = if at > 0.0 {
        Aset {
            blue: a[0] / at,
            red: a[1] / at,
            green: a[2] / at,
            leak: a[3] / at,
        }
    } else {
        Aset::default()
    };
    let weights = color::band_weights_d65(bands);
    let outline = solid.projected_area(DVec3::Z);
    let fire_value = (0..spot_sets.len())
        .map(|s| {
            let images: Vec<&Raster> = fire
                .iter()
                .filter_map(|&k| results[k].images.get(s))
                .collect();
            fire_of(&images, &weights, outline)
        })
        .sum::<f64>()
        / spot_sets.len().max(1) as f64;
    let scint_images: Vec<&Raster> = scint
        .iter()
        .filter_map(|&k| results[k].images.first())
        .collect();
    Scores {
        overhead_light_return: norm(fu, fu.up),
        brilliance: 0.5 * (brilliance_iso + brilliance_cos),
        brilliance_iso,
        brilliance_cos,
        fire: fire_value,
        scintillation: scintillation_of(&scint_images),
        aset,
    }
}

/// The placements of the spot lights over which fire is averaged: the first is
/// [`ScoreConfig::spots`] as given (scintillation uses it); placement k > 0 turns the set about
/// the zenith by k golden angles (137.5°, so every rotational symmetry of a cut is sampled at
/// spread-out phases) and raises or lowers it by up to 4.5°. A viewer sees a stone under lights
/// in many places; one fixed placement makes fire jump when a single coloured flash crosses a
/// single spot's rim.
pub fn fire_lightings(cfg: &ScoreConfig) -> Vec<Lighting> {
    const LIFT: [f64; 8] = [0.0, 3.0, -3.0, 1.5, -1.5, 4.5, -4.5, 0.75];
    (0..cfg.fire_placements.max(1))
        .map(|k| {
            let turn = 137.507_764_050_037_85 * k as f64;
            let lift = LIFT[k % LIFT.len()];
            let spots: Vec<Spot> = cfg
                .spots
                .iter()
                .map(|s| Spot {
                    elevation_deg: (s.elevation_deg + lift).clamp(1.0, 89.0),
                    azimuth_deg: (s.azimuth_deg + turn) % 360.0,
                    radius_deg: s.radius_deg,
                })
                .collect();
            Lighting::new(cfg.head_shadow_deg, &spots)
        })
        .collect()
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

/// `Σₖ Σₚ |Iₖ₊₁ − Iₖ| / Σₖ Σₚ (Iₖ₊₁ + Iₖ)` over a sequence of images; 0 without light.
pub fn scintillation_of(images: &[&Raster]) -> f64 {
    let (mut diff, mut sum) = (0.0, 0.0);
    for pair in images.windows(2) {
        for (a, b) in pair[0].data.iter().zip(&pair[1].data) {
            diff += (a - b).abs();
            sum += a + b;
        }
    }
    if sum > 0.0 {
        (diff / sum).min(1.0)
    } else {
        0.0
    }
}
