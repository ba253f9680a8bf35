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
//! Narrow beams followed as discs that fork at facet edges ([`TraceOptions::narrow_forks`],
//! `[score] narrow_forks` in a config) move their light from facet to facet continuously
//! too: with a split threshold of 3e-4 and a ray floor of 0.02, brilliance's total variation
//! over its range on the 0.002° pavilion profile of `cargo bench --bench profile` falls from
//! 2.30 to 1.02 and its median absolute second difference from 1.3e-4 to 1.6e-5, for 1.4
//! times the time (a full score 1.9 times); but brilliance moves by up to 4.1e-4 from the
//! exactly split value (on tolkowsky from +6e-5 to +4.1e-4, 4.5 standard errors of a
//! million-photon check), so they are off by default. (Most of that bias is their rays'
//! closure: with each fork stopped at the ray floor of its own share instead of the whole
//! narrow beam's, brilliance's mean offset over the profile's 501 cuts from the same cuts
//! split down to 2e-6 falls from +1.9e-4 to +6.6e-5 (the default: +3.9e-5), its total
//! variation is 1.01 of its range and its median |second difference| 1.4e-5, but a score
//! takes 15 times as long.)
//!
//! How smooth can brilliance be? Split finer, the profile converges (measured with
//! `cargo bench --bench profile`): with the tilted poses split down to 1e-5 its total
//! variation is 1.08 of its range and its median |second difference| 3.2e-5, at 2e-6 1.01
//! and 1.7e-5 (at 1e-4, the default, 2.30 and 1.3e-4). Much of that last figure is the
//! scores' own roughness on this scale, which splitting finer no longer removes: the face-up
//! pose alone, split down to 1e-6, 1e-7 and 1e-8 (nothing cut off above 1e-10), has median
//! |second differences| of 7.6e-5, 6.6e-5 and 6.0e-5 over the profile's first 0.1°, and its
//! second differences at 1e-6 and 1e-7 correlate by 0.81 over the whole degree. A beam
//! tree's powers are continuous in the cut but not smooth: Fresnel's reflectance has an
//! infinite slope at the critical angle (and a refracted exit's direction at grazing exit),
//! and as the cut changes, beams of the thousands of facet sequences cross it one after
//! another. Averaging over poses (and an optimizer's simplex, tenths of a degree wide)
//! smooths that; a median |second difference| of 1e-5 at 0.002° is out of reach by
//! splitting finer.
//!
//! How smooth are fire and scintillation? Both genuinely rise and fall over the profile's
//! degree (scintillation climbs from 0.47 to 0.65 at 40.65°, drops to 0.58 by 40.75° and
//! rises again; fire has two humps). Taken from every 25th cut only (0.05° apart), their
//! total variations are 1.90 and 1.55 of their ranges, so most of their 0.002° figures (2.51
//! and 1.66) is the functions' own shape, and a total variation near 1 would take a different
//! score, not a better trace. What the 0.002° figure adds is the fine-scale roughness: 0.61
//! for fire, 0.11 for scintillation, and 1.31 for brilliance, all of it below 0.01° (every
//! 5th cut: 1.08; split down to 1e-5, 0.08). Scintillation's shape stays with more rocking
//! azimuths (15 instead of 5: 1.61; for a round brilliant 10 are the 5's poses twice, exactly)
//! and with its images blurred before they are compared (1.79), and its rocked poses split
//! down to 1e-5 change it hardly at all (1.63).
//!
//! # Same solid, same scores; a turned stone too
//!
//! Scores are functions of the solid, not of its numbers: it is first put in the canonical
//! placement of [`canonical`] (centroid at the origin, unit size, turned about its axis to a
//! canonical azimuth, facets in a canonical order), so a translated, uniformly scaled,
//! reordered, symmetry-rotated or arbitrarily turned copy of a stone scores the same. The
//! canonical azimuth ([`canonical::azimuth_turn`]) is where the stone's k-th azimuthal harmonic
//! (k its rotation order) is real: it puts a mirror line on azimuth 0, and leaves the bundled
//! presets as drawn. Turned copies agree exactly when the turn is one of the stone's
//! symmetries, and otherwise to the ~1e-13 of the turn's arithmetic (so, at worst, to the
//! tracer's response to such a change; see [`TraceOptions`]).
//!
//! Turning a stone under the lights is still a real change of pose, and the scores average
//! over it from that canonical start: brilliance over the ring poses of [`Tilt::default_set`]
//! (five azimuths per ring), fire over [`fire_placements`] (turns of the lights in steps of
//! 360°/17), scintillation over [`scintillation_turns`] (five rocking azimuths).
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
//! * **`fire`** ≥ 0, in percent (about 0.7 for a Tolkowsky diamond, more for the same cut in cubic
//!   zirconia): saturated colour under small light sources, as an *expectation over the ways a
//!   face-up stone meets its lights*. The face-up view is traced at [`ScoreConfig::bands`]
//!   wavelengths (band centres across 380–780 nm; a band whose colour weight is below
//!   [`color::FAINT_BAND`] of the white's in X, Y and Z — with 8 bands, 730–780 nm at ~2e-5 — is
//!   not traced but takes its neighbour's image, [`color::traced_bands`]: fire moves by < 1e-6 for
//!   ~5 % fewer instructions); for one placement of the spot lights ([`Spot::default_set`], seven
//!   5° spots of radiance 1) each band's image is rasterised with exact footprint coverage; each
//!   pixel's spectrum becomes CIE XYZ with D65-weighted CIE 1931 bands
//!   ([`color::band_weights_d65`]) and then CIELAB relative to the D65 white of the spots' radiance
//!   (Y = 1). One placement's fire is `100 · Σ Y·s` over the face-up outline per unit of its area,
//!   `s = C*ab / L*` the pixel's saturation: coloured light per unit of face-up area (`s` hardly
//!   depends on brightness, so fire is linear in the light and one concentrated flash cannot
//!   dominate). Fire is the weighted mean over [`fire_placements`]: the lights turned about the
//!   zenith in equal steps (the stone turning under them: the face-up traces are shared, only the
//!   lights move) and raised or lowered by up to [`FIRE_LIFT_DEG`] with a smooth raised-cosine
//!   weight (the stone rocking a little under them). A single placement is a checkerboard of single
//!   flashes in the cut's parameters (a dispersed fan crossing one spot's rim); the expectation
//!   varies smoothly. A grey pixel (every band the same) contributes exactly 0, so a material
//!   without dispersion has fire exactly 0. Fire's traces split down to
//!   [`ScoreConfig::fire_split_threshold`] (3e-6), thirty times finer than the others: on the
//!   0.002° profile of `cargo bench --bench profile` fire's total variation over its range falls
//!   from 3.56 at 1e-5 to 2.51 (2.25 at 1e-6, 2.18 at 3e-7; sampled every 0.1° the profile itself
//!   rises and falls by 1.7 times its range), for a quarter more time.
//! * **`scintillation`** ∈ [0, 1]: how much the face-up pattern of bright and dark changes as
//!   the stone rocks, in every direction. For each of [`ScoreConfig::scintillation_turns`]
//!   evenly spaced azimuths ψ ([`scintillation_turns`]) the stone is rocked toward ψ through
//!   [`ScoreConfig::scintillation_tilts`] (0° then 3° by default) under the spot lights
//!   turned by ψ — a turn of the whole scene, i.e. the stone turned by −ψ — and its image of
//!   the spots at [`ScoreConfig::wavelength_nm`] taken at each tilt. The score is
//!   `Σ_ψ Σₖ Σₚ |Iₖ₊₁ − Iₖ| / Σ_ψ Σₖ Σₚ (Iₖ₊₁ + Iₖ)`: 0 when nothing changes, 1 when
//!   consecutive patterns never overlap. Rocking poses that a symmetry of the stone maps onto
//!   each other (for a round brilliant, the turns 72° and 288°, 144° and 216°) share one
//!   trace, each image seen through its symmetry (the same pixels to rounding). (Rocking
//!   about one axis only made the score depend on how the stone was turned: 0.466 → 0.509
//!   for a round brilliant turned by 22.5°.)
//! * **`aset`** `{blue, red, green, leak}`, each ∈ [0, 1], sum 1: the shares of the face-up
//!   view (by power, over the traced light; cut-off light excluded) whose sight lines leave
//!   the stone toward 75–90° elevation (blue), 45–75° (red), 0–45° (green) or below the
//!   horizon (leak), with ±1° soft boundaries. No head obstruction is applied: in a real ASET
//!   the viewing port at the top is dark; here that light counts as blue.

pub use crate::geometry::canonical;
pub use crate::render::{fire_of, lighting, raster, Tilt};

pub mod json;

#[cfg(test)]
mod golden;
#[cfg(test)]
mod invariance;
#[cfg(test)]
mod tests;

use crate::beam::{mirror_matrix, ExitBeam, ExitSink, Frame, Stone, TraceOptions, TraceStats};
use crate::error::{Error, Result};
use crate::geometry::{clip2d, Polyhedron};
use crate::optics::{color, Dispersion, Material};
use glam::{DMat3, DVec2, DVec3};
use lighting::{aset_bins, Lighting, Spot};
use raster::{Coverage, GridMap, Raster};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// Wavelength of the single-wavelength scores: the sodium D line, nm.
pub const REFERENCE_WAVELENGTH_NM: f64 = 589.3;

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
    /// Wavelength bands for fire (equal bands across 380–780 nm; faint ones share a
    /// neighbour's trace, [`color::traced_bands`]). Default 8.
    pub bands: usize,
    /// Rocking sequence for scintillation: tilts toward each of the
    /// [`ScoreConfig::scintillation_turns`] azimuths, degrees, in order (consecutive images
    /// are compared; a tilt of 0 is the face-up trace, shared). Default 0°, 3°.
    pub scintillation_tilts: Vec<f64>,
    /// Number of evenly spaced azimuths toward which scintillation rocks the stone
    /// ([`scintillation_turns`]), the spot lights turning with it. Default 5.
    pub scintillation_turns: usize,
    /// Pixels per side of the fire and scintillation images. Default 64.
    pub resolution: usize,
    /// Placements of the spot lights that fire is averaged over ([`fire_placements`]).
    /// Default 17.
    pub fire_placements: usize,
    /// Tracer settings (footprints are switched on where needed). The split threshold is the
    /// tilted poses'; the ray floor ([`ScoreConfig::RAY_FLOOR`] by default) applies to every
    /// trace but the face-up one at the reference wavelength, and the power it stops is handed
    /// back with the narrow exits' mean (brilliance, not the pictures).
    pub trace: TraceOptions,
    /// Split threshold of the face-up traces (fire's bands, and at most this for the face-up
    /// trace at the reference wavelength; see [`TraceOptions::split_threshold`]): fire's spot
    /// images are the most sensitive to the narrow-beam approximation, and face-up traces of
    /// symmetric stones are cheap. Default 3e-6 (see the module documentation on fire).
    pub fire_split_threshold: f64,
    /// Split threshold of the face-up trace at the reference wavelength: overhead light
    /// return, ASET, and the face-up pose of brilliance and of scintillation. Default 1e-6,
    /// which puts overhead light return within 0.01 percentage points of the exact reference
    /// (`cargo bench --bench exact`; at 1e-5 it is off by up to 0.035 points, at 1e-4 by up
    /// to 0.23). A face-up trace covers one symmetry wedge, so this fine trace is cheap.
    pub face_up_split_threshold: f64,
    /// Which of the costlier scores to compute (default: all). One left out is NaN in
    /// [`Scores`]. The optimizer leaves out what its objective does not weigh while it
    /// searches, and scores the cuts it reports in full.
    pub parts: Parts,
}

/// Which of fire and scintillation [`score`] computes (brilliance, overhead light return and
/// ASET always are: they share the traces brilliance needs). Fire takes about half of a
/// default score's time (its eight face-up traces: 62 of 127 ms on one thread for tolkowsky),
/// scintillation about a tenth (14 ms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Parts {
    /// Compute fire.
    pub fire: bool,
    /// Compute scintillation.
    pub scintillation: bool,
}

impl Default for Parts {
    fn default() -> Self {
        Parts {
            fire: true,
            scintillation: true,
        }
    }
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
            scintillation_tilts: vec![0.0, 3.0],
            scintillation_turns: 5,
            resolution: 64,
            fire_placements: 17,
            trace: TraceOptions {
                ray_floor: Self::RAY_FLOOR,
                ..TraceOptions::default()
            },
            fire_split_threshold: 3e-6,
            face_up_split_threshold: 1e-6,
            parts: Parts::default(),
        }
    }
}

impl ScoreConfig {
    /// Default [`TraceOptions::ray_floor`] of the scores' traces. Measured on 30 tilted poses
    /// of six presets against traces split down to 1e-6: the ISO light return errs by 4.71e-4
    /// on average (4.84e-4 without a floor) while the rays need 0.48 of their segments; the
    /// default brilliance of tolkowsky, princess and oval is within 7e-5 of the same scores
    /// split down to 2e-6 (within 1.3e-4 without a floor). A default score of tolkowsky takes
    /// 0.67 of its time (CPU time, one thread), brilliance alone 0.65.
    pub const RAY_FLOOR: f64 = 0.05;

    /// A quicker configuration for searches: narrow beams from 1e-3 of the light, 6 bands,
    /// face-up plus five poses at 15°, rocking toward three azimuths, seven placements of the
    /// spot lights for fire, 48 pixels. Brilliance stays within
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
            scintillation_tilts: vec![0.0, 3.0],
            scintillation_turns: 3,
            resolution: 48,
            fire_placements: 7,
            trace: TraceOptions {
                split_threshold: 1e-3,
                ray_floor: Self::RAY_FLOOR,
                ..TraceOptions::default()
            },
            fire_split_threshold: 1e-4,
            face_up_split_threshold: 1e-4,
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
        if !(1..=64).contains(&self.scintillation_turns) {
            return Err(Error::invalid(
                "scintillation-turns",
                format!(
                    "{} is out of range; allowed 1 to 64",
                    self.scintillation_turns
                ),
            ));
        }
        if !(1..=256).contains(&self.fire_placements) {
            return Err(Error::invalid(
                "fire-placements",
                format!("{} is out of range; allowed 1 to 256", self.fire_placements),
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
            && self.face_up_split_threshold >= 0.0
            && self.face_up_split_threshold < 1.0
            && t.split_threshold >= 0.0
            && t.split_threshold < 1.0
            && t.ray_floor >= 0.0
            && t.ray_floor < 1.0)
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

/// Light return of one pose of the brilliance average: the mean of the pose's ISO and COS
/// pictures ([`crate::render::Stats::mean`]). A pose that one of the stone's symmetries maps
/// onto another (10° toward 72° and toward 27° on a round brilliant) returns the same light,
/// and both are traced once, at the representative of [`symmetric_pose`]'s rule: the picture
/// drawn of that representative is the pose's exactly; the pose's own picture agrees to the
/// tracer's narrow-beam approximation (about 1e-4).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PoseScore {
    /// Tilt of the pose, degrees.
    pub tilt_deg: f64,
    /// Azimuth the table tips toward, degrees.
    pub azimuth_deg: f64,
    /// Light return under ISO lighting, [0, 1].
    pub iso: f64,
    /// Light return under COS lighting, [0, 1].
    pub cos: f64,
}

/// The scores of one cut (see the module documentation for definitions and ranges).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
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
    /// The poses of the brilliance average, in [`ScoreConfig::tilts`] order, each with its
    /// ISO and COS light return (brilliance_iso and brilliance_cos are their means).
    #[serde(default)]
    pub poses: Vec<PoseScore>,
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
        split_threshold: ScoreConfig::default().face_up_split_threshold,
        ..Default::default()
    };
    let solid = canonical::canonical(solid);
    overhead_light_return_with(&Stone::new(&solid), material.ri(wavelength_nm), &opts)
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
#[derive(Clone, Debug)]
struct Job {
    tilt: Tilt,
    ri: f64,
    /// Spot-light images: indices into the lightings of [`score`] (fire's placements, then
    /// scintillation's turns), in the order of [`PoseResult::images`].
    images: Vec<usize>,
    /// Per image, the world map `G` (a symmetry of the stone about the z axis) taking this
    /// job's traced pose to the pose the image shows, when they differ (see
    /// [`symmetric_pose_map`]): each exit is seen along `G w` with its footprint mapped by `G`.
    views: Vec<Option<DMat3>>,
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
    /// The same sums over the late exits of narrow beams' rays only ([`ExitBeam::late`];
    /// `traced` is their power), for the closure of the rays' stopped power.
    late: Sums,
    images: Vec<Raster>,
}

/// Power-weighted sums over exits.
#[derive(Clone, Copy, Debug, Default)]
struct Sums {
    traced: f64,
    up: f64,
    iso: f64,
    cos: f64,
    aset: [f64; 4],
}

impl PoseResult {
    /// Hand the power of rays stopped by the ray floor (`closed`) back with the mean of the
    /// late narrow exits (of rays that had already lost half their power): the light a ray
    /// still carries after losing most of it leaves like that, and dimmer than the narrow
    /// exits as a whole (measured on 8 tilted poses of four presets, brilliance's radiance of
    /// the stopped light when followed to the end: 0.386–0.449; the late exits' mean is within
    /// 0.04 of it, all narrow exits' 0.02–0.12 above it). Pictures are not closed (the
    /// closed light is a few tenths of a percent, spread thin).
    fn close(&mut self, closed: f64) {
        let n = self.late;
        if !(closed > 0.0 && n.traced > 0.0) {
            return;
        }
        let k = closed / n.traced;
        self.traced += closed;
        self.up += k * n.up;
        self.iso += k * n.iso;
        self.cos += k * n.cos;
        for (a, b) in self.aset.iter_mut().zip(n.aset) {
            *a += k * b;
        }
    }
}

struct PoseSink<'a> {
    rot: DMat3,
    light: &'a Lighting,
    /// Fire's placements, when this job's first images are theirs (all of them, in order).
    lattice: Option<&'a FireLattice<'a>>,
    spots: Vec<&'a Lighting>,
    /// Per image, its view's world map and that map's 2×2 part for footprints
    /// ([`Job::views`]).
    views: Vec<Option<(DMat3, [f64; 4])>>,
    /// A footprint mapped by a view, and its coverage.
    vfoot: Vec<DVec2>,
    vcov: Coverage,
    area: f64,
    face_up: bool,
    brilliance: bool,
    r: PoseResult,
    /// The current exit's footprint coverage (the same for every image).
    cov: Coverage,
    /// The copies of one traced exit (its orbit) under a symmetric trace's maps: per class
    /// of maps that differ by a symmetry of the pixel grid, the first copy's coverage; the
    /// other copies in its class move its pixels instead of clipping again.
    orbit: OrbitCoverage,
    /// Fire's placement lookup for the current orbit's elevation (shared by its copies).
    reach: Reach,
}

/// Coverages of the copies of one traced exit that a symmetric trace hands out
/// ([`ExitSink::symmetries`]). Their footprint maps fall into classes `G · R` (`R` the class's
/// first map, `G` a symmetry of the pixel grid, [`GridMap`]); within a class, coverages are
/// each other's with the pixels moved. A face-up round brilliant's 16 maps make two classes
/// (the quarter turns and the mirrors through the axes and diagonals, times 1 or a 45° turn),
/// so two clips serve all 16 copies.
#[derive(Debug, Default)]
struct OrbitCoverage {
    /// Per symmetry index: its class and its map's grid part `G`.
    class: Vec<Option<(usize, GridMap)>>,
    /// Per class: the first coverage computed for the current orbit, and that copy's `G`.
    first: Vec<(Option<GridMap>, Coverage)>,
    /// Per symmetry index: how it moves an azimuth, `a ↦ sign · a + turn` (degrees).
    turns: Vec<(f64, f64)>,
    /// The azimuth of the current orbit's identity copy, degrees.
    azimuth: f64,
}

impl OrbitCoverage {
    /// Sort the maps `(index, [a, b, c, d])` (orthogonal) into classes.
    fn new(maps: &[(u16, [f64; 4])]) -> OrbitCoverage {
        let mut o = OrbitCoverage::default();
        let mut reps: Vec<[f64; 4]> = Vec::new();
        for &(i, m) in maps {
            let i = usize::from(i);
            // m · rᵀ for each class's first map r.
            let found = reps.iter().enumerate().find_map(|(c, r)| {
                let mt = [
                    m[0] * r[0] + m[1] * r[1],
                    m[0] * r[2] + m[1] * r[3],
                    m[2] * r[0] + m[3] * r[1],
                    m[2] * r[2] + m[3] * r[3],
                ];
                GridMap::of(mt).map(|g| (c, g))
            });
            let entry = found.unwrap_or_else(|| {
                reps.push(m);
                o.first.push((None, Coverage::default()));
                (reps.len() - 1, GridMap::IDENTITY)
            });
            if o.class.len() <= i {
                o.class.resize(i + 1, None);
                o.turns.resize(i + 1, (f64::NAN, f64::NAN));
            }
            o.class[i] = Some(entry);
            // A turn by θ is [cos θ, −sin θ, sin θ, cos θ]; a mirror through the line at β is
            // [cos 2β, sin 2β, sin 2β, −cos 2β]: either way the angle is atan2(c, a).
            let sign = (m[0] * m[3] - m[1] * m[2]).signum();
            o.turns[i] = (sign, m[2].atan2(m[0]).to_degrees());
        }
        o
    }

    /// The azimuth (degrees, up to whole turns) of the copy with symmetry index `sym` and
    /// world direction `w`, from its orbit's identity copy's (one arc-tangent per orbit: ask
    /// for every copy, the identity first), when the trace is symmetric; `None` otherwise.
    /// The maps act on world directions as on footprints: the frames' symmetries keep the
    /// viewer's axis.
    fn azimuth(&mut self, sym: u16, w: DVec3) -> Option<f64> {
        let &(sign, turn) = self.turns.get(usize::from(sym))?;
        if sym == 0 {
            self.azimuth = w.y.atan2(w.x).to_degrees();
        }
        Some(sign * self.azimuth + turn)
    }

    /// A new orbit begins (its identity copy arrives).
    fn start(&mut self) {
        for f in &mut self.first {
            f.0 = None;
        }
    }

    /// The coverage of the copy with symmetry index `sym` and footprint `fp` on images like
    /// `img`, into `cov`: moved from its class's first coverage of this orbit, or clipped
    /// (and kept as the first).
    fn cover(&mut self, img: &Raster, sym: u16, fp: &[DVec2], cov: &mut Coverage) {
        let Some(&Some((c, g))) = self.class.get(usize::from(sym)) else {
            img.coverage_into(fp, cov);
            return;
        };
        let (g0, first) = &mut self.first[c];
        match *g0 {
            Some(g0) => img.map_coverage(first, g.after_inverse_of(g0), cov),
            None => {
                img.coverage_into(fp, first);
                *g0 = Some(g);
                cov.cells.clear();
                cov.cells.extend_from_slice(&first.cells);
            }
        }
    }
}

impl ExitSink for PoseSink<'_> {
    fn wants_footprints(&self) -> bool {
        !self.r.images.is_empty()
    }
    /// Fire's face-up traces measure nothing else: an exit (with its symmetric copies, which
    /// share its elevation) that no placement of the spots can reach is skipped whole.
    fn wants_orbit(&self, e: &ExitBeam) -> bool {
        let fire_only = self.lattice.map_or(0, |l| l.lightings.len());
        if self.face_up || self.brilliance || self.r.images.len() > fire_only {
            return true;
        }
        self.lattice
            .is_some_and(|l| l.reaches((self.rot * e.direction).z))
    }
    fn symmetries(&mut self, maps: &[(u16, [f64; 4])]) {
        self.orbit = OrbitCoverage::new(maps);
    }
    fn exit(&mut self, e: &ExitBeam, fp: &[DVec2]) {
        if e.sym == 0 {
            self.orbit.start();
        }
        let w = self.rot * e.direction;
        let p = e.power;
        let r = &mut self.r;
        if self.face_up {
            r.traced += p;
            let up = if w.z > 0.0 { p } else { 0.0 };
            r.up += up;
            let b = aset_bins(w);
            for (acc, x) in r.aset.iter_mut().zip(b) {
                *acc += p * x;
            }
            if e.late {
                r.late.up += up;
                for (acc, x) in r.late.aset.iter_mut().zip(b) {
                    *acc += p * x;
                }
            }
        }
        if self.brilliance {
            let (iso, cos) = (p * self.light.iso(w), p * self.light.cos(w));
            r.iso += iso;
            r.cos += cos;
            if e.late {
                r.late.iso += iso;
                r.late.cos += cos;
            }
        }
        if e.late {
            r.late.traced += p;
        }
        // The footprint's area and pixel coverage, computed on first use: every image has
        // the same size, so one coverage serves them all (a view's mapped footprint has its
        // own).
        let mut a = -1.0;
        let mut covered = false;
        let mut skip = 0;
        let cov = &mut self.cov;
        let orbit = &mut self.orbit;
        if let Some(lat) = self.lattice {
            skip = lat.lightings.len();
            let (images, scale) = (&mut r.images[..skip], p * self.area);
            if e.sym == 0 {
                lat.reach_into(w, &mut self.reach);
            }
            lat.for_each(w, orbit.azimuth(e.sym, w), &self.reach, |k, l| {
                if a < 0.0 {
                    a = clip2d::area(fp);
                }
                if l > 0.0 && a > 0.0 {
                    if !covered {
                        orbit.cover(&images[k], e.sym, fp, cov);
                        covered = true;
                    }
                    images[k].add_coverage(cov, l * scale / a);
                }
            });
        }
        // Skipping on each slice iterator is O(1), unlike skipping the zipped pairs.
        for ((img, light), view) in r
            .images
            .iter_mut()
            .skip(skip)
            .zip(self.spots.iter().skip(skip))
            .zip(self.views.iter().skip(skip))
        {
            // Another pose, the traced one under a symmetry: its own direction and footprint
            // (of the same area).
            let wv = view.as_ref().map_or(w, |(g, _)| *g * w);
            if !light.near_spot(wv) {
                continue;
            }
            let l = light.spots(wv);
            if a < 0.0 {
                a = clip2d::area(fp);
            }
            if !(l > 0.0 && a > 0.0) {
                continue;
            }
            // Radiance through this beam: its power per unit of footprint, relative to the
            // incoming power per unit of cross-section.
            let v = l * p * self.area / a;
            match view {
                Some((_, m)) => {
                    self.vfoot.clear();
                    self.vfoot.extend(
                        fp.iter()
                            .map(|q| DVec2::new(m[0] * q.x + m[1] * q.y, m[2] * q.x + m[3] * q.y)),
                    );
                    img.coverage_into(&self.vfoot, &mut self.vcov);
                    img.add_coverage(&self.vcov, v);
                }
                None => {
                    if !covered {
                        orbit.cover(img, e.sym, fp, cov);
                        covered = true;
                    }
                    img.add_coverage(cov, v);
                }
            }
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn run_job(
    stone: &Stone,
    solid: &Polyhedron,
    job: &Job,
    light: &Lighting,
    lightings: &[Lighting],
    lattice: &FireLattice,
    cfg: &ScoreConfig,
    half: f64,
) -> PoseResult {
    let (frame, opts, mut sink) = job_sink(solid, job, light, lightings, lattice, cfg, half);
    let (stats, _) = stone.trace_into(&frame, job.ri, &opts, &mut sink, false);
    sink.finish(stats)
}

/// A job's viewer frame, trace settings and sink (see [`run_job`]).
#[allow(clippy::too_many_arguments)]
fn job_sink<'a>(
    solid: &Polyhedron,
    job: &Job,
    light: &'a Lighting,
    lightings: &'a [Lighting],
    lattice: &'a FireLattice<'a>,
    cfg: &ScoreConfig,
    half: f64,
) -> (Frame, TraceOptions, PoseSink<'a>) {
    let rot = job.tilt.rotation();
    let frame = Frame::viewer(rot);
    let opts = TraceOptions {
        polarization: cfg.polarization,
        footprints: !job.images.is_empty(),
        split_threshold: job.split,
        // The face-up figures are the cross-checked exact ones: no closure there.
        ray_floor: if job.face_up {
            0.0
        } else {
            cfg.trace.ray_floor
        },
        narrow_forks: cfg.trace.narrow_forks && !job.face_up,
        ..cfg.trace
    };
    let spots: Vec<&Lighting> = job
        .images
        .iter()
        .filter_map(|&i| lightings.get(i))
        .collect();
    let views = job
        .views
        .iter()
        .map(|g| g.map(|g| (g, [g.x_axis.x, g.y_axis.x, g.x_axis.y, g.y_axis.y])))
        .collect();
    let n = lattice.lightings.len();
    let has_fire = job.images.len() >= n && job.images[..n].iter().copied().eq(0..n);
    let sink = PoseSink {
        rot,
        light,
        lattice: has_fire.then_some(lattice),
        area: solid.projected_area(-frame.dir),
        face_up: job.face_up,
        brilliance: job.brilliance,
        r: PoseResult {
            images: spots
                .iter()
                .map(|_| Raster::new(cfg.resolution, half))
                .collect(),
            ..Default::default()
        },
        spots,
        views,
        vfoot: Vec::new(),
        vcov: Coverage::default(),
        cov: Coverage::default(),
        orbit: OrbitCoverage::default(),
        reach: Reach::default(),
    };
    (frame, opts, sink)
}

impl PoseSink<'_> {
    /// What the job measured, once its trace (with `stats`) is done.
    fn finish(mut self, stats: TraceStats) -> PoseResult {
        self.r.power_in = stats.power_in;
        self.r.close(stats.ray_closed);
        self.r
    }
}

/// Score `solid` (see the module documentation). The configuration should have passed
/// [`ScoreConfig::validate`]; out-of-range values are not checked here but never panic.
/// Poses and wavelengths are traced in parallel with rayon and combined in a fixed order, so
/// the result does not depend on the number of threads.
pub fn score(solid: &Polyhedron, cfg: &ScoreConfig) -> Scores {
    score_with_faint(solid, cfg, color::FAINT_BAND)
}

/// [`score`], with fire's bands whose colour weight is below `faint` of the white's merged
/// into a neighbour ([`color::traced_bands`]; 0 traces every band).
fn score_with_faint(solid: &Polyhedron, cfg: &ScoreConfig, faint: f64) -> Scores {
    let solid = &canonical::canonical(solid);
    let stone = Stone::new(solid);
    let light = Lighting::new(cfg.head_shadow_deg, &cfg.spots);
    let placements = fire_placements(cfg);
    let turns = scintillation_turns(cfg);
    let mut lightings: Vec<Lighting> = placements
        .iter()
        .map(|p| Lighting::new(cfg.head_shadow_deg, &p.spots))
        .collect();
    let first_turn = lightings.len();
    lightings.extend(
        turns
            .iter()
            .map(|&t| Lighting::new(cfg.head_shadow_deg, &turned(&cfg.spots, t, 0.0))),
    );
    let half = crate::render::picture_half(solid);
    let ri0 = cfg.material.ri(cfg.wavelength_nm);
    // Fire's bands: the faint ones (far out in the red) take a neighbour's trace.
    let bands = color::traced_bands(cfg.bands.max(1), faint);
    // Distinct traces, each shared by every score that needs it (same pose, same index).
    let mut jobs: Vec<Job> = Vec::new();
    #[derive(Clone, Copy)]
    enum Use {
        FaceUp,
        Brilliance,
        /// An image under lighting `l`, of the pose the job traces or, mapped by a symmetry
        /// of the stone, of another ([`Job::views`]).
        Image(usize, Option<DMat3>),
    }
    let index = |tilt: Tilt, ri: f64, what: Use, split: f64, jobs: &mut Vec<Job>| -> usize {
        // Every face-up pose is the same trace, whatever azimuth it names.
        let tilt = if tilt.tilt_deg == 0.0 {
            Tilt::FACE_UP
        } else {
            tilt
        };
        let split = if tilt != Tilt::FACE_UP {
            split
        } else if ri.to_bits() == ri0.to_bits() {
            split
                .min(cfg.fire_split_threshold)
                .min(cfg.face_up_split_threshold)
        } else {
            split.min(cfg.fire_split_threshold)
        };
        let same = |j: &Job| j.tilt == tilt && j.ri.to_bits() == ri.to_bits() && j.split == split;
        let k = match jobs.iter().position(same) {
            Some(k) => k,
            None => {
                jobs.push(Job {
                    tilt,
                    ri,
                    images: Vec::new(),
                    views: Vec::new(),
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
            Use::Image(l, view) => {
                if !jobs[k].images.contains(&l) {
                    jobs[k].images.push(l);
                    jobs[k].views.push(view);
                }
            }
        }
        k
    };
    let split = cfg.trace.split_threshold;
    // The face-up figures (overhead light return, ASET) are the cross-checked ones: the
    // face-up trace at the reference wavelength splits down to `face_up_split_threshold`
    // (cheap: a face-up stone traces one symmetry wedge), the other face-up traces (fire's
    // bands) to `fire_split_threshold`.
    let face_up = index(
        Tilt::FACE_UP,
        ri0,
        Use::FaceUp,
        cfg.fire_split_threshold,
        &mut jobs,
    );
    // Brilliance sees no spot light: a pose and its image under one of the stone's
    // symmetries return the same light, so they share one trace.
    let symmetry = stone.symmetry();
    let brill: Vec<usize> = cfg
        .tilts
        .iter()
        .map(|t| {
            let t = symmetric_pose(*t, symmetry);
            index(t, ri0, Use::Brilliance, split, &mut jobs)
        })
        .collect();
    let constant = matches!(cfg.material.dispersion, Dispersion::Constant(_));
    let fire: Vec<usize> = bands
        .iter()
        .filter(|_| cfg.parts.fire)
        .map(|&(l, _)| {
            let ri = if constant { ri0 } else { cfg.material.ri(l) };
            let mut k = 0;
            for p in 0..placements.len() {
                k = index(
                    Tilt::FACE_UP,
                    ri,
                    Use::Image(p, None),
                    cfg.fire_split_threshold,
                    &mut jobs,
                );
            }
            k
        })
        .collect();
    // Scintillation: per turn, the rocking sequence toward the turn's azimuth, under the spot
    // lights turned with it. A pose that a symmetry of the stone maps onto another is that
    // pose's trace seen through the symmetry (one trace for both).
    let scint: Vec<Vec<(usize, usize)>> = turns
        .iter()
        .enumerate()
        .filter(|_| cfg.parts.scintillation)
        .map(|(j, &turn)| {
            cfg.scintillation_tilts
                .iter()
                .map(|&t| {
                    let tilt = Tilt {
                        tilt_deg: t,
                        azimuth_deg: turn,
                    };
                    let l = first_turn + j;
                    let (rep, view) = symmetric_pose_map(tilt, symmetry);
                    (index(rep, ri0, Use::Image(l, view), split, &mut jobs), l)
                })
                .collect()
        })
        .collect();
    let lattice = FireLattice::new(&placements, &lightings[..first_turn]);
    // The costliest traces first, so that the short ones fill in at the end: face-up ones
    // (the finest splits), then the poses whose trace uses the fewest symmetries.
    let copies: Vec<usize> = jobs
        .iter()
        .map(|j| stone.frame_symmetries(&Frame::viewer(j.tilt.rotation())))
        .collect();
    let mut order: Vec<usize> = (0..jobs.len()).collect();
    order.sort_by(|&a, &b| {
        let (x, y) = (&jobs[a], &jobs[b]);
        (x.tilt != Tilt::FACE_UP)
            .cmp(&(y.tilt != Tilt::FACE_UP))
            .then(x.split.total_cmp(&y.split))
            .then(copies[a].cmp(&copies[b]))
            .then(y.images.len().cmp(&x.images.len()))
    });
    let results: Vec<PoseResult> = par_in_order(&order, |k| {
        run_job(
            &stone, solid, &jobs[k], &light, &lightings, &lattice, cfg, half,
        )
    });
    let image = |k: usize, l: usize| -> Option<&Raster> {
        let pos = jobs[k].images.iter().position(|&x| x == l)?;
        results[k].images.get(pos)
    };

    let norm = |r: &PoseResult, x: f64| {
        if r.power_in > 0.0 {
            x / r.power_in
        } else {
            0.0
        }
    };
    let fu = &results[face_up];
    let n = brill.len().max(1) as f64;
    let poses: Vec<PoseScore> = brill
        .iter()
        .zip(&cfg.tilts)
        .map(|(&k, t)| PoseScore {
            tilt_deg: t.tilt_deg,
            azimuth_deg: t.azimuth_deg,
            iso: norm(&results[k], results[k].iso),
            cos: norm(&results[k], results[k].cos),
        })
        .collect();
    let brilliance_iso = poses.iter().map(|p| p.iso).sum::<f64>() / n;
    let brilliance_cos = poses.iter().map(|p| p.cos).sum::<f64>() / n;
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
    let weights: Vec<DVec3> = bands.iter().map(|b| b.1).collect();
    let outline = solid.projected_area(DVec3::Z);
    // Each placement's fire in parallel, summed in placement order.
    let per_placement: Vec<f64> = placements
        .par_iter()
        .enumerate()
        .map(|(p, placement)| {
            let images: Vec<&Raster> = fire.iter().filter_map(|&k| image(k, p)).collect();
            placement.weight * fire_of(&images, &weights, outline)
        })
        .collect();
    let fire_sum: f64 = per_placement.iter().sum();
    let fire_w: f64 = placements.iter().map(|p| p.weight).sum();
    let fire_value = if !cfg.parts.fire {
        f64::NAN
    } else if fire_w > 0.0 {
        fire_sum / fire_w
    } else {
        0.0
    };
    let sequences: Vec<Vec<&Raster>> = scint
        .iter()
        .map(|seq| seq.iter().filter_map(|&(k, l)| image(k, l)).collect())
        .collect();
    let sequences: Vec<&[&Raster]> = sequences.iter().map(|s| s.as_slice()).collect();
    Scores {
        overhead_light_return: norm(fu, fu.up),
        brilliance: 0.5 * (brilliance_iso + brilliance_cos),
        brilliance_iso,
        brilliance_cos,
        fire: fire_value,
        scintillation: if cfg.parts.scintillation {
            scintillation_of(&sequences)
        } else {
            f64::NAN
        },
        aset,
        poses,
    }
}

/// `f(k)` for every `k` of `order` (a permutation of `0..n`), started in that order on the
/// rayon pool: each worker takes the next one when it is free (greedy list scheduling, so
/// that long jobs given first finish together). The results come back by index,
/// `[f(0), f(1), …]`, whatever the number of threads.
fn par_in_order<T: Send + Sync>(order: &[usize], f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::OnceLock;
    let next = AtomicUsize::new(0);
    let slots: Vec<OnceLock<T>> = order.iter().map(|_| OnceLock::new()).collect();
    let workers = rayon::current_num_threads().clamp(1, order.len().max(1));
    (0..workers).into_par_iter().for_each(|_| loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        let Some(&k) = order.get(i) else { break };
        if let Some(slot) = slots.get(k) {
            let _ = slot.set(f(k));
        }
    });
    slots
        .into_iter()
        .map(|s| s.into_inner().expect("every index of `order` was run"))
        .collect()
}

/// The representative of `tilt` under a stone's symmetry `(order, mirror azimuth)` (see
/// [`Stone::symmetry`]): the stone turned by 360°/order, or mirrored through a mirror line at
/// azimuth β, meets the viewer tilted toward azimuth `a` as the unturned stone meets one tilted
/// toward `a − 360°/order`, or toward `2β − a`. Light returned under an azimuthally symmetric
/// lighting (ISO, COS, the head shadow) is the same for all of them, so brilliance traces
/// one. The representative's azimuth is the smallest in `[0°, 360°/order)` over the group,
/// rounded to 1e-9° so that equal poses are found equal.
pub fn symmetric_pose(tilt: Tilt, (order, mirror): (usize, Option<f64>)) -> Tilt {
    if tilt.tilt_deg == 0.0 || order == 0 {
        return tilt;
    }
    let period = 360.0 / order as f64;
    let snap = |a: f64| {
        let a = (a.rem_euclid(period) * 1e9).round() / 1e9;
        if a >= period {
            0.0
        } else {
            a
        }
    };
    let mut a = snap(tilt.azimuth_deg);
    if let Some(beta) = mirror {
        a = a.min(snap(2.0 * beta.to_degrees() - a));
    }
    Tilt {
        tilt_deg: tilt.tilt_deg,
        azimuth_deg: a,
    }
}

/// [`symmetric_pose`] with the symmetry taking it to `tilt`: the representative pose and,
/// unless it is `tilt` itself, the world map `G` (a rotation about the z axis or a mirror
/// through it, a symmetry of the stone) with `tilt.rotation() = G · rep.rotation() · Gᵀ`. The
/// stone at `tilt` is then the stone at the representative moved by `G` (the viewer on the z
/// axis stays put): its exits leave along `G w` with footprints mapped by `G`.
fn symmetric_pose_map(tilt: Tilt, symmetry: (usize, Option<f64>)) -> (Tilt, Option<DMat3>) {
    let rep = symmetric_pose(tilt, symmetry);
    let (order, mirror) = symmetry;
    if tilt.tilt_deg == 0.0 || order == 0 {
        return (rep, None);
    }
    let period = 360.0 / order as f64;
    // Azimuths equal modulo 360° (the representative is rounded to 1e-9°).
    let same = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(360.0);
        d.min(360.0 - d) < 1e-6
    };
    if same(rep.azimuth_deg, tilt.azimuth_deg) {
        return (rep, None);
    }
    for k in 0..order {
        let turn = k as f64 * period;
        if same(rep.azimuth_deg + turn, tilt.azimuth_deg) {
            return (rep, Some(DMat3::from_rotation_z(turn.to_radians())));
        }
        if let Some(beta) = mirror {
            // The mirror through azimuth γ takes a tilt toward a to one toward 2γ − a.
            let gamma = beta.to_degrees() + 0.5 * turn;
            if same(2.0 * gamma - rep.azimuth_deg, tilt.azimuth_deg) {
                return (rep, Some(mirror_matrix(gamma.to_radians())));
            }
        }
    }
    // Not reached for a representative of `tilt`; tracing `tilt` itself is always right.
    (tilt, None)
}

/// One placement of the spot lights for fire, and its weight in the average.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The spots, turned about the zenith and raised or lowered.
    pub spots: Vec<Spot>,
    /// How far they were turned, degrees.
    pub turn_deg: f64,
    /// How far they were raised (negative: lowered), degrees.
    pub lift_deg: f64,
    /// Weight in fire's average (the weights need not add up to 1).
    pub weight: f64,
}

/// Fire's placements arranged for a quick lookup: for a direction, only the placements whose
/// turned and lifted spots can reach it are visited (equal turn steps make them a short
/// range of indices per spot), so the cost hardly grows with the number of placements.
struct FireLattice<'a> {
    lightings: &'a [Lighting],
    /// Per spot of the base set, what [`FireLattice::for_each`] needs of it.
    spots: Vec<SpotReach>,
    /// Per spot `i` and placement `k` (at `i · P + k`): the sines of the lowest and highest
    /// elevations that spot reaches there (so that no arcsine is needed per exit).
    zband: Vec<(f64, f64)>,
    /// The lowest `z_lo` and highest `z_hi` of all spots (see [`FireLattice::reaches`]).
    z_range: (f64, f64),
    step: f64,
}

/// One spot of fire's base set, hoisted out of [`FireLattice::for_each`].
#[derive(Clone, Copy, Debug)]
struct SpotReach {
    /// Azimuth of its centre at the first placement, degrees.
    azimuth: f64,
    /// Smallest cosine of its elevation over the lifts.
    cos_top: f64,
    /// Sines of the elevations below and above which no placement's spot reaches.
    z_lo: f64,
    z_hi: f64,
    /// `1 − cos(reach)`, the reach being the angular radius with the soft rim.
    one_minus_cos_reach: f64,
}

/// The sine of an elevation in degrees, clamped to the sphere.
fn sin_deg(e: f64) -> f64 {
    e.clamp(-90.0, 90.0).to_radians().sin()
}

/// An upper bound of `acos(1 − x)` for `x` in [0, 2], in radians, without the arc-cosine:
/// `√(2x) · (1 + 0.3x)` (the series is `√(2x) · (1 + x/12 + …)`; the bound is tight at 0 and
/// 2% above π at 2).
#[inline]
fn acos_one_minus_upper(x: f64) -> f64 {
    (2.0 * x).sqrt() * (1.0 + 0.3 * x)
}

impl<'a> FireLattice<'a> {
    fn new(placements: &[Placement], lightings: &'a [Lighting]) -> FireLattice<'a> {
        let lifts: Vec<f64> = placements.iter().map(|p| p.lift_deg).collect();
        let (lo, hi) = lifts
            .iter()
            .fold((0.0f64, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
        // Per spot: elevation at lift 0, azimuth, reach (degrees) and its SpotReach.
        let base: Vec<(f64, f64, SpotReach)> = placements.first().map_or_else(Vec::new, |p0| {
            p0.spots
                .iter()
                .map(|s| {
                    let base = s.elevation_deg - p0.lift_deg;
                    let reach = s.radius_deg + lighting::EDGE_DEG + 1e-6;
                    let top = (base + hi)
                        .clamp(1.0, 89.0)
                        .max((base + lo).clamp(1.0, 89.0));
                    let spot = SpotReach {
                        azimuth: s.azimuth_deg - p0.turn_deg,
                        cos_top: top.to_radians().cos(),
                        z_lo: sin_deg((base + lo).clamp(1.0, 89.0) - reach),
                        z_hi: sin_deg((base + hi).clamp(1.0, 89.0) + reach),
                        one_minus_cos_reach: 1.0 - reach.to_radians().cos(),
                    };
                    (base, reach, spot)
                })
                .collect()
        });
        let zband = base
            .iter()
            .flat_map(|&(base, reach, _)| {
                lifts.iter().map(move |&lift| {
                    let ek = (base + lift).clamp(1.0, 89.0);
                    (sin_deg(ek - reach), sin_deg(ek + reach))
                })
            })
            .collect();
        let z_range = base
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
                (lo.min(b.2.z_lo), hi.max(b.2.z_hi))
            });
        FireLattice {
            lightings,
            spots: base.iter().map(|b| b.2).collect(),
            zband,
            z_range,
            step: 360.0 / placements.len().max(1) as f64,
        }
    }

    /// Whether some placement's spots can light a direction whose z component is `z` (the
    /// same test [`FireLattice::for_each`] makes per spot: `false` means it visits nothing).
    #[inline]
    fn reaches(&self, z: f64) -> bool {
        let z = z.clamp(-1.0, 1.0);
        !self.lightings.is_empty() && z >= self.z_range.0 && z <= self.z_range.1
    }

    /// What [`FireLattice::for_each`] needs of a direction's elevation alone, into `out`:
    /// the head shadow and the spots within reach, each with the half-width of the azimuths
    /// it reaches there. The copies of a face-up exit share their elevation, so one `Reach`
    /// serves the whole orbit.
    fn reach_into(&self, w: DVec3, out: &mut Reach) {
        out.spots.clear();
        // Elevations are compared through their sines (sin e = w.z), with the reach's margin
        // of 1e-6° far above rounding: the same placements are visited as with the angles.
        let z = w.z.clamp(-1.0, 1.0);
        out.head = self.lightings.first().map_or(0.0, |l| l.head(w));
        if out.head == 0.0 {
            return;
        }
        let mut cos_e: Option<f64> = None;
        for (i, sp) in self.spots.iter().enumerate() {
            if z < sp.z_lo || z > sp.z_hi {
                continue;
            }
            let cos_e = *cos_e.get_or_insert_with(|| (1.0 - z * z).sqrt());
            // 1 − cos Δa ≤ (1 − cos ρ) / (cos e · cos ε): the azimuths within reach (an upper
            // bound of the arc-cosine visits a few more placements, whose light is 0).
            let x = sp.one_minus_cos_reach / (cos_e * sp.cos_top).max(1e-300);
            let half = if x >= 2.0 {
                180.0
            } else {
                acos_one_minus_upper(x).to_degrees().min(180.0)
            };
            out.spots.push((i, half));
        }
    }

    /// Calls `f(k, radiance)` for every placement `k` whose spots light direction `w`
    /// (each spot separately, head shadow applied), `reach` being [`FireLattice::reach_into`]
    /// of `w` or of any direction with the same elevation. `az`, when given, is `w`'s azimuth
    /// in degrees (any turn of it; it only picks the placements to look at, each of which is
    /// then evaluated at `w` itself).
    #[inline]
    fn for_each(&self, w: DVec3, az: Option<f64>, reach: &Reach, mut f: impl FnMut(usize, f64)) {
        let n = self.lightings.len();
        if n == 0 || reach.spots.is_empty() {
            return;
        }
        let z = w.z.clamp(-1.0, 1.0);
        let az = az.unwrap_or_else(|| w.y.atan2(w.x).to_degrees());
        let ni = n as i64;
        for &(i, half) in &reach.spots {
            let sp = &self.spots[i];
            let t0 = az - sp.azimuth;
            let (k0, k1) = if half >= 180.0 {
                (0, ni - 1)
            } else {
                (
                    raster::ceil_i64((t0 - half) / self.step),
                    raster::floor_i64((t0 + half) / self.step),
                )
            };
            // Placements k0, k0 + 1, … (at most all n once), taken modulo n.
            let mut k = k0.rem_euclid(ni) as usize;
            for _ in k0..=k1.min(k0 + ni - 1) {
                let (lo, hi) = self.zband[i * n + k];
                if z >= lo && z <= hi {
                    let l = self.lightings[k].spot(i, w);
                    if l > 0.0 {
                        f(k, l * reach.head);
                    }
                }
                k += 1;
                if k == n {
                    k = 0;
                }
            }
        }
    }
}

/// The part of fire's placement lookup that depends on a direction's elevation only
/// ([`FireLattice::reach_into`]).
#[derive(Debug, Default)]
struct Reach {
    /// The head shadow's share at that elevation.
    head: f64,
    /// The spots within reach, with the half-width (degrees) of the azimuths each reaches.
    spots: Vec<(usize, f64)>,
}

/// Largest raising or lowering of the spot lights in fire's average, degrees.
pub const FIRE_LIFT_DEG: f64 = 8.0;

/// The placements of the spot lights over which fire is averaged: the expectation over the
/// ways a face-up stone meets the lights, as a rank-1 lattice of `P =`
/// [`ScoreConfig::fire_placements`] points in (turn, lift). Placement k turns the set
/// about the zenith by `360° · k / P` (turning the stone under fixed lights is turning the
/// lights the other way: the face-up trace does not change) and raises it by
/// `lift = FIRE_LIFT_DEG · (2 (m + ½) / P − 1)`, m = 7k mod P (a stone rocked by a few degrees
/// sees each light higher or lower by about as much), with the smooth weight
/// `(1 + cos(π · lift / FIRE_LIFT_DEG)) / 2`. Equal turn steps make fire exactly the same for a
/// stone turned by a multiple of `360° / P`; an odd `P` shares no factor with the usual 4-, 8-
/// or 16-fold symmetries, so the turns sample every phase of the stone's symmetry evenly.
pub fn fire_placements(cfg: &ScoreConfig) -> Vec<Placement> {
    let p = cfg.fire_placements.max(1);
    (0..p)
        .map(|k| {
            let turn = 360.0 * k as f64 / p as f64;
            let m = (7 * k) % p;
            let lift = if p == 1 {
                0.0
            } else {
                FIRE_LIFT_DEG * (2.0 * (m as f64 + 0.5) / p as f64 - 1.0)
            };
            let weight = if p == 1 {
                1.0
            } else {
                0.5 * (1.0 + (std::f64::consts::PI * lift / FIRE_LIFT_DEG).cos())
            };
            Placement {
                spots: turned(&cfg.spots, turn, lift),
                turn_deg: turn,
                lift_deg: lift,
                weight,
            }
        })
        .collect()
}

/// The azimuths toward which scintillation rocks the stone, degrees:
/// `360° · j / `[`ScoreConfig::scintillation_turns`]; the spot lights turn with them.
pub fn scintillation_turns(cfg: &ScoreConfig) -> Vec<f64> {
    let k = cfg.scintillation_turns.max(1);
    (0..k).map(|j| 360.0 * j as f64 / k as f64).collect()
}

/// `spots` turned about the zenith by `turn_deg` and raised by `lift_deg` (elevations kept
/// within 1°–89°).
fn turned(spots: &[Spot], turn_deg: f64, lift_deg: f64) -> Vec<Spot> {
    spots
        .iter()
        .map(|s| Spot {
            elevation_deg: (s.elevation_deg + lift_deg).clamp(1.0, 89.0),
            azimuth_deg: (s.azimuth_deg + turn_deg).rem_euclid(360.0),
            radius_deg: s.radius_deg,
        })
        .collect()
}

/// `Σⱼ Σₖ Σₚ |Iⱼ,ₖ₊₁ − Iⱼ,ₖ| / Σⱼ Σₖ Σₚ (Iⱼ,ₖ₊₁ + Iⱼ,ₖ)` over sequences `j` of images
/// (consecutive images of each sequence are compared); 0 without light.
pub fn scintillation_of(sequences: &[&[&Raster]]) -> f64 {
    let (mut diff, mut sum) = (0.0, 0.0);
    for images in sequences {
        for pair in images.windows(2) {
            for (a, b) in pair[0].data.iter().zip(&pair[1].data) {
                diff += (a - b).abs();
                sum += a + b;
            }
        }
    }
    if sum > 0.0 {
        (diff / sum).min(1.0)
    } else {
        0.0
    }
}
