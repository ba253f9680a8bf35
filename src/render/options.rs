//! What to draw and how ([`RenderOptions`]), with the check of every field.

use super::light::Light;
use super::lighting::Spot;
use super::pose::Tilt;
use crate::beam::TraceOptions;
use crate::error::{Error, Result};
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
    /// Track polarization (default on).
    pub polarization: bool,
    /// Wavelength bands of the fire picture (≥ 8 by default; faint ones share a neighbour's
    /// trace, [`color::traced_bands`](crate::optics::color::traced_bands)).
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
