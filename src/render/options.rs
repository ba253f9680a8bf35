//! What to draw and how ([`RenderOptions`]), with the check of every field.

use super::light::Light;
use super::lighting::Spot;
use super::pose::Tilt;
use crate::beam::TraceOptions;
use crate::error::{shown, Error, Result};
use crate::optics::Material;

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
    /// Wavelength bands of the fire picture (≥ 8 by default; faint ones share a neighbour's
    /// trace, [`color::traced_bands`](crate::optics::color::traced_bands)).
    pub bands: usize,
    /// Spot lights of the fire picture.
    pub spots: Vec<Spot>,
    /// Tracer settings of a tilted picture, polarization among them (default on; footprints are
    /// switched on here, see [`RenderOptions::trace_options`]).
    /// The default splits beams down to [`RenderOptions::SPLIT_THRESHOLD`] of the light, with
    /// no ray floor and no forking narrow beams (pictures are not closed).
    pub trace: TraceOptions,
    /// Split threshold of an untilted picture (`tilt_deg` 0: face-up, or face-down for
    /// hearts): its trace splits down to at most this. Default
    /// [`RenderOptions::FACE_UP_SPLIT_THRESHOLD`], the scores' face-up one, so that a face-up
    /// picture's mean and the scores' face-up figures are the very same trace.
    pub face_up_split_threshold: f64,
    /// Split threshold and ray floor of a coloured stone's untilted picture (its bands,
    /// absorbed): the scores' fire bands are traced so, and the scores draw their face-up
    /// colour on those traces, so that `render --light iso` shows the scores' colour and
    /// extinction. Default [`RenderOptions::COLOUR_SPLIT_THRESHOLD`] and
    /// [`RenderOptions::COLOUR_RAY_FLOOR`].
    pub colour_split_threshold: f64,
    /// See [`RenderOptions::colour_split_threshold`].
    pub colour_ray_floor: f64,
    /// The stone's width in mm (a round's diameter), for its body colour's absorption
    /// (absorption depends on the physical size). Default
    /// [`StoneSize::DEFAULT_WIDTH_MM`](crate::optics::StoneSize::DEFAULT_WIDTH_MM).
    pub width_mm: f64,
}

impl RenderOptions {
    /// Default split threshold of a tilted picture. Finer than the scores' tilted poses
    /// (1e-4, with a ray floor whose stopped light the scores hand back but a picture cannot
    /// place): an 800² tilted picture of tolkowsky takes about twice as long at 1e-6 and its
    /// mean moves by 2e-5 or less.
    pub const SPLIT_THRESHOLD: f64 = 1e-5;

    /// Default split threshold of an untilted picture: the scores' face-up one
    /// (`ScoreConfig::default().face_up_split_threshold`), so that `render --light iso`
    /// face-up, under the scores' head shadow (15° by default), gives the scores' face-up ISO
    /// light return to the last bit. A face-up stone
    /// traces one symmetry wedge, so this fine trace is cheap.
    pub const FACE_UP_SPLIT_THRESHOLD: f64 = 1e-6;

    /// Default split threshold of a coloured stone's untilted picture: the scores' fire
    /// bands' (`ScoreConfig::default().fire_split_threshold`).
    pub const COLOUR_SPLIT_THRESHOLD: f64 = 3e-6;

    /// Default ray floor of a coloured stone's untilted picture: the scores'
    /// (`ScoreConfig::RAY_FLOOR`; the light it stops is not drawn, a few 1e-4 of it).
    pub const COLOUR_RAY_FLOOR: f64 = 0.05;

    /// Default options for `light`: 512 pixels, face-up, diamond at 589.3 nm, 8 bands.
    pub fn new(light: Light) -> RenderOptions {
        RenderOptions {
            light,
            size: 512,
            tilt: Tilt::FACE_UP,
            head_shadow_deg: None,
            material: Material::diamond(),
            wavelength_nm: 589.3,
            bands: 8,
            spots: Spot::default_set(),
            trace: TraceOptions {
                split_threshold: Self::SPLIT_THRESHOLD,
                ..TraceOptions::default()
            },
            face_up_split_threshold: Self::FACE_UP_SPLIT_THRESHOLD,
            colour_split_threshold: Self::COLOUR_SPLIT_THRESHOLD,
            colour_ray_floor: Self::COLOUR_RAY_FLOOR,
            width_mm: crate::optics::StoneSize::DEFAULT_WIDTH_MM,
        }
    }

    /// These options with polarization tracked (`true`, the default) or not: the trace
    /// settings' own switch ([`TraceOptions::polarization`]), the one home of that setting.
    pub fn polarized(mut self, on: bool) -> RenderOptions {
        self.trace.polarization = on;
        self
    }

    /// The tracer settings of this picture: [`RenderOptions::trace`] with footprints on, and
    /// for an untilted picture a split threshold of at most
    /// [`RenderOptions::face_up_split_threshold`].
    pub fn trace_options(&self) -> TraceOptions {
        let split = if self.tilt.tilt_deg == 0.0 {
            self.trace.split_threshold.min(self.face_up_split_threshold)
        } else {
            self.trace.split_threshold
        };
        TraceOptions {
            footprints: true,
            split_threshold: split,
            ..self.trace
        }
    }

    /// The tracer settings of a coloured stone's band traces: for an untilted picture,
    /// [`RenderOptions::trace`] split down to [`RenderOptions::colour_split_threshold`] with
    /// the ray floor [`RenderOptions::colour_ray_floor`] (as the scores trace fire's bands);
    /// a tilted picture's are [`RenderOptions::trace_options`].
    pub fn colour_trace_options(&self) -> TraceOptions {
        if self.tilt.tilt_deg != 0.0 {
            return self.trace_options();
        }
        TraceOptions {
            footprints: true,
            split_threshold: self.colour_split_threshold,
            ray_floor: self.colour_ray_floor,
            ..self.trace
        }
    }

    /// The head shadow in use.
    pub fn head_shadow(&self) -> f64 {
        self.head_shadow_deg
            .unwrap_or_else(|| self.light.default_head_shadow_deg())
    }

    /// Check every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        check_size(self.size)?;
        check_tilt(self.tilt)?;
        let h = self.head_shadow();
        if !(0.0..=60.0).contains(&h) {
            return Err(Error::invalid(
                "head-shadow",
                format!(
                    "{}° is out of range; allowed 0 to 60 degrees (0 = none)",
                    shown(h)
                ),
            ));
        }
        if !(380.0..=780.0).contains(&self.wavelength_nm) {
            return Err(Error::invalid(
                "wavelength",
                format!(
                    "{} nm is outside the visible range; allowed 380 to 780 nm",
                    shown(self.wavelength_nm)
                ),
            ));
        }
        if self.light == Light::Fire && !(8..=64).contains(&self.bands) {
            return Err(Error::invalid(
                "bands",
                format!("{} is out of range; allowed 8 to 64", self.bands),
            ));
        }
        check_index(&self.material, &[self.wavelength_nm, 380.0, 780.0])
    }
}

/// Check a picture's size in pixels (8 to 8192 a side), both kinds of picture's.
pub(super) fn check_size(size: usize) -> Result<()> {
    if !(8..=8192).contains(&size) {
        return Err(Error::invalid(
            "size",
            format!("{size} pixels is out of range; allowed 8 to 8192"),
        ));
    }
    Ok(())
}

/// Check a stone's tilt (−90 to 90 degrees, a finite azimuth), both kinds of picture's.
pub(super) fn check_tilt(t: Tilt) -> Result<()> {
    if !(t.tilt_deg.abs() <= 90.0 && t.azimuth_deg.is_finite()) {
        return Err(Error::invalid(
            "tilt",
            format!(
                "{}° is out of range; allowed −90 to 90 degrees",
                shown(t.tilt_deg)
            ),
        ));
    }
    Ok(())
}

/// Check the material's refractive index at each of `wavelengths` (nm): in [1, 10] (1 to
/// rounding), both kinds of picture's.
pub(super) fn check_index(material: &Material, wavelengths: &[f64]) -> Result<()> {
    for &l in wavelengths {
        let n = material.ri(l);
        if !(n.is_finite() && n > 1.0 - 1e-12 && n <= 10.0) {
            return Err(Error::invalid(
                "material",
                format!(
                    "{} has refractive index {} at {l} nm; allowed [1, 10]",
                    material.name,
                    shown(n)
                ),
            ));
        }
    }
    Ok(())
}
