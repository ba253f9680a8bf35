//! What a photograph shows and how ([`PhotoOptions`]), with the check of every field, and its
//! light ([`PhotoLight`]): a bundled rig, the bundled procedural studio map, or the user's
//! HDR environment map.

use super::camera::View;
use super::env::{Environment, MAX_EDGE_DEG};
use super::envmap::EnvMap;
use super::ground::{Ground, GroundKind};
use super::rigs::Rig;
use super::tone::Tone;
use crate::beam::TraceOptions;
use crate::error::{shown, Error, Result};
use crate::optics::Material;
use crate::render::lighting::EDGE_DEG;
use crate::render::options::{check_index, check_size, check_tilt};
use crate::render::Tilt;
use glam::DVec3;
use std::path::Path;
use std::sync::Arc;

/// The light of a photograph.
#[derive(Clone, Debug)]
pub enum PhotoLight {
    /// A bundled studio rig.
    Rig(Rig),
    /// An equirectangular environment map, with the name it was given by (`studio` for the
    /// bundled procedural map, `env:FILE` for a file).
    Map {
        /// The name shown.
        name: String,
        /// The map.
        map: Arc<EnvMap>,
    },
    /// Any environment built in code (tests, comparisons).
    Custom(Environment),
}

/// The name of the bundled procedural map.
pub const STUDIO: &str = "studio";

impl PhotoLight {
    /// The file the light named `s` reads, if any: FILE of `env:FILE`, an input that no
    /// output of the picture may replace.
    pub fn file_of(s: &str) -> Option<std::path::PathBuf> {
        s.trim().strip_prefix("env:").map(std::path::PathBuf::from)
    }

    /// The light a `--light` value names, if it is a photographic one: a rig's name,
    /// [`STUDIO`], or `env:FILE` (a Radiance `.hdr` or OpenEXR `.exr` map, read here; errors
    /// name the file). `Ok(None)` for any other name (the laboratory lights).
    pub fn parse(s: &str) -> Result<Option<PhotoLight>> {
        let t = s.trim();
        if let Some(file) = t.strip_prefix("env:") {
            let path = Path::new(file);
            let img = crate::io::hdr::read_hdr(path)?;
            let map = EnvMap::from_image(&img, &path.display().to_string())?;
            return Ok(Some(PhotoLight::Map {
                name: format!("env:{file}"),
                map: Arc::new(map),
            }));
        }
        let lower = t.to_ascii_lowercase();
        if lower == STUDIO {
            return Ok(Some(PhotoLight::studio()));
        }
        Ok(Rig::ALL
            .into_iter()
            .find(|r| r.name() == lower)
            .map(PhotoLight::Rig))
    }

    /// The bundled procedural studio map.
    pub fn studio() -> PhotoLight {
        static MAP: std::sync::OnceLock<Arc<EnvMap>> = std::sync::OnceLock::new();
        PhotoLight::Map {
            name: STUDIO.to_string(),
            map: MAP.get_or_init(|| Arc::new(EnvMap::studio())).clone(),
        }
    }

    /// The names `--light` takes for photographs (besides `env:FILE`).
    pub fn names() -> Vec<&'static str> {
        let mut v: Vec<&'static str> = Rig::ALL.iter().map(|r| r.name()).collect();
        v.push(STUDIO);
        v
    }

    /// Its name.
    pub fn name(&self) -> String {
        match self {
            PhotoLight::Rig(r) => r.name().to_string(),
            PhotoLight::Map { name, .. } => name.clone(),
            PhotoLight::Custom(e) => e.name.clone(),
        }
    }

    /// The environment for a camera looking along `view` (world) from azimuth
    /// `camera_az_deg`, turned by `rotation_deg`.
    pub fn environment(&self, view: DVec3, camera_az_deg: f64, rotation_deg: f64) -> Environment {
        let mut env = match self {
            PhotoLight::Rig(r) => r.environment(view, camera_az_deg),
            PhotoLight::Map { name, map } => {
                Environment::new(name, vec![super::env::Part::Map(map.clone())])
            }
            PhotoLight::Custom(e) => e.clone(),
        };
        env.rotation_deg += rotation_deg;
        env
    }
}

/// The entrance pupil a perspective camera has when none is given, mm: a human eye's in
/// room light (at the near point of 250 mm, ±0.46°).
pub const PUPIL_MM: f64 = 4.0;

/// The distance an aperture is read at when the camera is orthographic (no distance of its
/// own), mm: the near point, where a person holds a stone to look at it.
pub const NEAR_POINT_MM: f64 = 250.0;

/// What to photograph and how.
#[derive(Clone, Debug)]
pub struct PhotoOptions {
    /// The light.
    pub light: PhotoLight,
    /// Turn of the light about the vertical, degrees (counter-clockwise seen from above).
    pub light_rotation_deg: f64,
    /// Where the camera looks from.
    pub view: View,
    /// Camera distance from the stone's centre in mm (perspective); `None`: orthographic.
    pub distance_mm: Option<f64>,
    /// Diameter of the camera's (or eye's) entrance pupil, mm; 0: a pinhole. `None`: the
    /// default ([`PhotoOptions::aperture_deg`]).
    pub aperture_mm: Option<f64>,
    /// Tile side of a perspective picture, pixels.
    pub tile: usize,
    /// Pixels per side.
    pub size: usize,
    /// The stone's pose (tilted about its centre before it is set on the ground).
    pub tilt: Tilt,
    /// Turntable angle: the stone (with the ground under it) turned about the vertical by
    /// this many degrees under the fixed camera and lights.
    pub turn_deg: f64,
    /// The stone's material (and body colour).
    pub material: Material,
    /// The stone's width in mm (its body colour's absorption, a perspective camera's scale).
    pub width_mm: f64,
    /// Wavelength bands of the spectral picture (a dispersive or coloured stone).
    pub bands: usize,
    /// Track polarization.
    pub polarization: bool,
    /// The ground.
    pub ground: Ground,
    /// Cells of the hemisphere whose light the ground's shadows and caustics are summed over
    /// (round lights have their own directions besides).
    pub ground_cells: usize,
    /// Tracer settings of the picture (footprints and polarization are set from the fields
    /// here); face-up views split finer ([`PhotoOptions::face_up_split_threshold`]).
    pub trace: TraceOptions,
    /// Split threshold of a face-up orthographic view (the scores' and `render`'s).
    pub face_up_split_threshold: f64,
    /// Tracer settings of the lights' traces for the ground (default: split at 5e-4, its
    /// narrow beams landing over their own cross-sections, a birefringent stone's too).
    pub ground_trace: TraceOptions,
    /// How linear radiance becomes display values.
    pub tone: Tone,
    /// Margin: the picture's square is this many times the stone's own ([`picture_half`](crate::render::picture_half)).
    pub margin: f64,
}

impl PhotoOptions {
    /// Default options for `light`: 512 pixels, seen from 30° above the front, diamond,
    /// 8 bands, no ground, orthographic.
    pub fn new(light: PhotoLight) -> PhotoOptions {
        PhotoOptions {
            light,
            light_rotation_deg: 0.0,
            view: View {
                elevation_deg: 30.0,
                azimuth_deg: 0.0,
            },
            distance_mm: None,
            aperture_mm: None,
            tile: 32,
            size: 512,
            tilt: Tilt::FACE_UP,
            turn_deg: 0.0,
            material: Material::diamond(),
            width_mm: crate::optics::StoneSize::DEFAULT_WIDTH_MM,
            bands: 8,
            polarization: true,
            ground: Ground::default(),
            ground_cells: 32,
            trace: TraceOptions {
                split_threshold: crate::render::RenderOptions::SPLIT_THRESHOLD,
                ..TraceOptions::default()
            },
            face_up_split_threshold: crate::render::RenderOptions::FACE_UP_SPLIT_THRESHOLD,
            ground_trace: TraceOptions {
                split_threshold: 5e-4,
                threshold: 1e-7,
                ray_floor: 0.02,
                ..TraceOptions::default()
            },
            tone: Tone::Filmic,
            margin: 1.25,
        }
    }

    /// The quick settings of a picture taken while a slider moves (the workbench): the
    /// stone's index at 589.3 nm for a colourless stone (one trace: no fire; a coloured stone
    /// keeps three bands for its colour), beams split down to 1e-4 of the light (the
    /// tracer's default), the ground's light in 8 cells and round lights.
    pub fn quick(&self) -> PhotoOptions {
        let mut o = self.clone();
        if o.material.colour.is_none() {
            let n = o.material.ri(589.3);
            o.material = Material {
                dispersion: crate::optics::Dispersion::Constant(n),
                ..o.material.clone()
            };
        } else {
            o.bands = 3;
        }
        o.trace.split_threshold = TraceOptions::SPLIT_THRESHOLD;
        o.face_up_split_threshold = TraceOptions::SPLIT_THRESHOLD;
        o.ground_cells = 8;
        o
    }

    /// Whether the camera looks straight down at an untilted stone from an orthographic
    /// distance (the laboratory pictures' view: traced as finely as they are).
    pub fn face_up(&self) -> bool {
        self.view.elevation_deg == 90.0 && self.tilt.tilt_deg == 0.0 && self.distance_mm.is_none()
    }

    /// The half-angle the entrance pupil subtends from the stone, degrees: the half-width of
    /// the filter the light is seen through ([`Environment::with_aperture`]). An aperture of
    /// diameter A at distance d subtends atan(A / 2d); an orthographic camera reads its
    /// aperture at [`NEAR_POINT_MM`]; 0 is a pinhole. Not given: a perspective camera has a
    /// human pupil ([`PUPIL_MM`], at most ±10°), an orthographic one the scores' ±1°
    /// ([`EDGE_DEG`]).
    pub fn aperture_deg(&self) -> f64 {
        let half = |a: f64, d: f64| (a / (2.0 * d)).atan().to_degrees();
        match (self.aperture_mm, self.distance_mm) {
            (Some(a), d) => half(a, d.unwrap_or(NEAR_POINT_MM)),
            (None, Some(d)) => half(PUPIL_MM, d).min(MAX_EDGE_DEG),
            (None, None) => EDGE_DEG,
        }
    }

    /// The tracer settings of the picture's traces.
    pub fn trace_options(&self) -> TraceOptions {
        let split = if self.face_up() {
            self.trace.split_threshold.min(self.face_up_split_threshold)
        } else {
            self.trace.split_threshold
        };
        TraceOptions {
            polarization: self.polarization,
            footprints: true,
            split_threshold: split,
            ..self.trace
        }
    }

    /// Check every field; the error names the field and what is allowed.
    pub fn validate(&self) -> Result<()> {
        check_size(self.size)?;
        let v = self.view;
        if !(v.elevation_deg.abs() <= 90.0 && v.azimuth_deg.is_finite()) {
            return Err(Error::invalid(
                "view",
                format!(
                    "{}° is out of range; allowed −90 to 90 degrees of elevation",
                    shown(v.elevation_deg)
                ),
            ));
        }
        if self.ground.kind != GroundKind::None && v.elevation_deg < 0.0 {
            return Err(Error::invalid(
                "view",
                format!(
                    "{}° looks from under the ground; with a ground the camera's elevation is 0 to 90 degrees",
                    shown(v.elevation_deg)
                ),
            ));
        }
        if !(self.ground.gap.is_finite() && (0.0..=10.0).contains(&self.ground.gap)) {
            return Err(Error::invalid(
                "ground-gap",
                format!(
                    "{} is out of range; allowed 0 to 10 girdle diameters",
                    shown(self.ground.gap)
                ),
            ));
        }
        check_tilt(self.tilt)?;
        if !self.light_rotation_deg.is_finite() || !self.turn_deg.is_finite() {
            return Err(Error::invalid(
                "light-rotation",
                "must be a number of degrees",
            ));
        }
        if let Some(d) = self.distance_mm {
            let lo = 3.0 * self.width_mm;
            if !(d.is_finite() && d >= lo && d <= 1e5) {
                return Err(Error::invalid(
                    "distance",
                    format!(
                        "{} mm is out of range; allowed {} mm (three times the stone's width of {} mm) to 100000 mm",
                        shown(d),
                        shown(lo),
                        shown(self.width_mm)
                    ),
                ));
            }
        }
        if let Some(a) = self.aperture_mm {
            let d = self.distance_mm.unwrap_or(NEAR_POINT_MM);
            let deg = self.aperture_deg();
            if !(a.is_finite() && a >= 0.0 && deg <= MAX_EDGE_DEG) {
                return Err(Error::invalid(
                    "aperture",
                    format!(
                        "{a} mm is out of range; allowed 0 (a pinhole) to {:.1} mm, an entrance pupil seen within ±{MAX_EDGE_DEG}° from {d} mm",
                        2.0 * d * MAX_EDGE_DEG.to_radians().tan()
                    ),
                ));
            }
        }
        if !(4..=256).contains(&self.tile) {
            return Err(Error::invalid(
                "tile",
                format!("{} pixels is out of range; allowed 4 to 256", self.tile),
            ));
        }
        if !(3..=64).contains(&self.bands) {
            return Err(Error::invalid(
                "bands",
                format!("{} is out of range; allowed 3 to 64", self.bands),
            ));
        }
        if !(self.width_mm.is_finite() && self.width_mm > 0.0) {
            return Err(Error::invalid(
                "diameter-mm",
                format!("{} mm must be a positive number", self.width_mm),
            ));
        }
        if !(1..=4096).contains(&self.ground_cells) {
            return Err(Error::invalid(
                "ground-cells",
                format!("{} is out of range; allowed 1 to 4096", self.ground_cells),
            ));
        }
        if !(self.margin.is_finite() && (1.0..=10.0).contains(&self.margin)) {
            return Err(Error::invalid(
                "margin",
                format!("{} is out of range; allowed 1 to 10", self.margin),
            ));
        }
        check_index(&self.material, &[380.0, 780.0])
    }
}
