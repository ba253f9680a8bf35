//! A picture's settings as a face gives them, each read once at the face's door into the
//! library's types, and turned into the library's options in one place
//! ([`PictureSettings::pictures`]): a laboratory picture ([`LabPictures`]) or a photograph
//! ([`PhotoPictures`]), by the light ([`LightChoice`], read once: a map file is read when its
//! `env:FILE` is). The command line's flags, Python's keyword arguments and the web page's
//! fields each fill [`PictureSettings`]; the web page adds only its own caps.
//!
//! Each value is read by the library's own parsers, the ones every face calls
//! ([`LightChoice::parse`], [`crate::render::pose::parse_tilt`],
//! [`crate::render::photo::parse_view`], [`GroundKind::parse`], [`Tone::parse`]) and those
//! here for the numbers, each with its range ([`parse_size`], [`parse_ground_gap`], …), and
//! every error names the setting ([`SETTINGS`]: `picture view`, `picture ground-gap`, …), a
//! setting inside a message too ([`crate::error::setting`]), for each face to spell as it
//! spells it: the command line's flag (`--view`), Python's keyword argument (`view`).

use crate::error::{setting, Error, Result, Setting};
use crate::io::text::{count, number};
use crate::optics::{Material, StoneSize};
use crate::render::photo::{turntable, Ground, GroundKind, PhotoLight, PhotoOptions, Tone, View};
use crate::render::pose::rocked;
use crate::render::{Light, RenderOptions, Tilt};
use std::path::PathBuf;

/// The light of a picture, read once from its name ([`LightChoice::parse`]): a laboratory
/// light, or a photograph's (a rig, the studio map, or an `env:FILE` map, read then).
#[derive(Clone, Debug)]
pub enum LightChoice {
    /// A laboratory light (iso, cos, aset, idealscope, hearts, arrows, fire).
    Lab(Light),
    /// A photographic light.
    Photo(PhotoLight),
}

impl Default for LightChoice {
    /// The ISO sky.
    fn default() -> LightChoice {
        LightChoice::Lab(Light::Iso)
    }
}

impl LightChoice {
    /// The light `text` names (`field` named in the error): a laboratory light's name (any
    /// case), a rig's, `studio`, or `env:FILE` (a Radiance `.hdr` or OpenEXR `.exr` map, read
    /// here; its errors name the file).
    pub fn parse(field: &str, text: &str) -> Result<LightChoice> {
        if let Some(photo) = PhotoLight::parse(text)? {
            return Ok(LightChoice::Photo(photo));
        }
        Light::parse(text.trim().to_ascii_lowercase().as_str())
            .map(LightChoice::Lab)
            .map_err(|_| {
                Error::invalid(
                    field,
                    format!(
                        "`{text}` is not allowed; use {}, {} or env:FILE",
                        Light::ALL.map(Light::name).join(", "),
                        PhotoLight::names().join(", ")
                    ),
                )
            })
    }

    /// The light's name as the pictures' records give it.
    pub fn name(&self) -> String {
        match self {
            LightChoice::Lab(l) => l.name().to_string(),
            LightChoice::Photo(p) => p.name(),
        }
    }

    /// The environment map's file, for an `env:FILE` light (an input: never overwritten).
    pub fn file(&self) -> Option<PathBuf> {
        match self {
            LightChoice::Photo(p) => PhotoLight::file_of(&p.name()),
            LightChoice::Lab(_) => None,
        }
    }

    /// Whether it is a photograph's light.
    pub fn is_photo(&self) -> bool {
        matches!(self, LightChoice::Photo(_))
    }
}

/// The light (a laboratory light, a photographic rig, `studio` or `env:FILE`).
pub const LIGHT: &str = Setting::PictureLight.name();
/// Pixels per side.
pub const SIZE: &str = Setting::PictureSize.name();
/// The stone's tilt, `DEG[@AZ]`.
pub const TILT: &str = Setting::PictureTilt.name();
/// A laboratory picture's head shadow, degrees.
pub const HEAD_SHADOW: &str = Setting::PictureHeadShadow.name();
/// Brightness factor.
pub const EXPOSURE: &str = Setting::PictureExposure.name();
/// A photograph's camera direction, `ELEV[@AZ]`.
pub const VIEW: &str = Setting::PictureView.name();
/// A photograph's camera distance, mm.
pub const DISTANCE: &str = Setting::PictureDistance.name();
/// A photograph's entrance pupil, mm (0: a pinhole).
pub const APERTURE: &str = Setting::PictureAperture.name();
/// A photograph's ground.
pub const GROUND: &str = Setting::PictureGround.name();
/// A photograph's gap under the stone, girdle diameters.
pub const GROUND_GAP: &str = Setting::PictureGroundGap.name();
/// A photograph's light turned about the vertical, degrees.
pub const LIGHT_ROTATION: &str = Setting::PictureLightRotation.name();
/// A photograph's tone curve.
pub const TONE: &str = Setting::PictureTone.name();
/// A photograph's wavelength bands.
pub const BANDS: &str = Setting::PictureBands.name();
/// The stone's width, mm (checked by a photograph against its camera distance).
pub const DIAMETER: &str = Setting::PictureDiameter.name();

/// Every setting a picture's errors name, for the faces' tables of their spellings.
pub const SETTINGS: [&str; 14] = [
    LIGHT,
    SIZE,
    TILT,
    HEAD_SHADOW,
    EXPOSURE,
    VIEW,
    DISTANCE,
    APERTURE,
    GROUND,
    GROUND_GAP,
    LIGHT_ROTATION,
    TONE,
    BANDS,
    DIAMETER,
];

/// The settings that only a photograph takes, in the order a face lists them.
const PHOTOGRAPHIC: [&str; 8] = [
    VIEW,
    DISTANCE,
    APERTURE,
    GROUND,
    GROUND_GAP,
    LIGHT_ROTATION,
    TONE,
    BANDS,
];

/// Pixels per side, 8 to 8192 (`field` named in the error, as in each of these parsers: the
/// setting, or a face's own name for it, a command line's flag).
pub fn parse_size(field: &str, s: &str) -> Result<usize> {
    count(field, s, 8, 8192).map(|n| n as usize)
}

/// A brightness factor, 0.01 to 100.
pub fn parse_exposure(field: &str, s: &str) -> Result<f64> {
    number(field, s, 0.01, 100.0, "a factor")
}

/// A laboratory picture's head shadow, a half-angle of 0 to 60 degrees.
pub fn parse_head_shadow(field: &str, s: &str) -> Result<f64> {
    number(field, s, 0.0, 60.0, "a half-angle in degrees (0 = none)")
}

/// A photograph's gap under the stone, 0 to 10 girdle diameters.
pub fn parse_ground_gap(field: &str, s: &str) -> Result<f64> {
    number(field, s, 0.0, 10.0, "girdle diameters")
}

/// A photograph's light turned about the vertical, −360 to 360 degrees.
pub fn parse_light_rotation(field: &str, s: &str) -> Result<f64> {
    number(field, s, -360.0, 360.0, "degrees")
}

/// A photograph's wavelength bands, 3 to 64.
pub fn parse_bands(field: &str, s: &str) -> Result<usize> {
    count(field, s, 3, 64).map(|n| n as usize)
}

/// A photograph's camera distance, 0 to 100000 mm (its least, three times the stone's width,
/// is [`PhotoOptions::validate`]'s).
pub fn parse_distance(field: &str, s: &str) -> Result<f64> {
    number(field, s, 0.0, 1e5, "millimetres")
}

/// A photograph's entrance pupil, 0 (a pinhole) to 100 mm (its most, the pupil seen within
/// ±10° from the camera's distance, is [`PhotoOptions::validate`]'s).
pub fn parse_aperture(field: &str, s: &str) -> Result<f64> {
    number(field, s, 0.0, 100.0, "millimetres (0 = a pinhole)")
}

/// A picture's settings as the library's values (`None`: not given, the light's default),
/// turned into options by [`PictureSettings::pictures`]. The command line fills them from
/// its typed flags; Python from its keyword arguments; the web page from its fields.
#[derive(Clone, Debug)]
pub struct PictureSettings {
    /// A laboratory light or a photographic one, read once ([`LightChoice::parse`]).
    pub light: LightChoice,
    /// Pixels per side (8–8192; default 512).
    pub size: Option<usize>,
    /// The stone tilted toward an azimuth.
    pub tilt: Option<Tilt>,
    /// Half-angle of the viewer's head shadow, degrees (0–60; laboratory lights only).
    pub head_shadow: Option<f64>,
    /// Brightness factor (0.01–100; default 1).
    pub exposure: Option<f64>,
    /// Track polarization.
    pub polarization: bool,
    /// Where a photograph's camera looks from (default 30@0).
    pub view: Option<View>,
    /// A perspective camera this many mm from the stone's centre (default orthographic).
    pub distance: Option<f64>,
    /// The camera's entrance pupil, mm (0: a pinhole; default
    /// [`PhotoOptions::aperture_deg`]'s).
    pub aperture: Option<f64>,
    /// White, black or none (default).
    pub ground: Option<GroundKind>,
    /// Height of the stone's lowest point above the ground, girdle diameters (0–10).
    pub ground_gap: Option<f64>,
    /// The light turned about the vertical, degrees (−360 to 360).
    pub light_rotation: Option<f64>,
    /// The tone curve (default filmic).
    pub tone: Option<Tone>,
    /// Wavelength bands of a dispersive or coloured stone (3–64; default 8).
    pub bands: Option<usize>,
}

/// `text`, if given, read by `parse` as the setting `name` (a face that takes a picture's
/// settings as text reads each so).
pub fn read<T>(
    text: Option<&str>,
    name: &str,
    parse: fn(&str, &str) -> Result<T>,
) -> Result<Option<T>> {
    text.map(|t| parse(name, t)).transpose()
}

impl PictureSettings {
    /// The settings of a picture under `light`, every other setting its default.
    pub fn new(light: LightChoice) -> PictureSettings {
        PictureSettings {
            light,
            size: None,
            tilt: None,
            head_shadow: None,
            exposure: None,
            polarization: true,
            view: None,
            distance: None,
            aperture: None,
            ground: None,
            ground_gap: None,
            light_rotation: None,
            tone: None,
            bands: None,
            // (a new field is a new setting: name it in SETTINGS)
        }
    }

    /// The photographic settings given, by name ([`PHOTOGRAPHIC`]'s order).
    fn photographic(&self) -> impl Iterator<Item = &'static str> + '_ {
        let given = [
            self.view.is_some(),
            self.distance.is_some(),
            self.aperture.is_some(),
            self.ground.is_some(),
            self.ground_gap.is_some(),
            self.light_rotation.is_some(),
            self.tone.is_some(),
            self.bands.is_some(),
        ];
        PHOTOGRAPHIC
            .into_iter()
            .zip(given)
            .filter(|(_, g)| *g)
            .map(|(name, _)| name)
    }

    /// The single picture these settings describe of stones of `material` and `size` (the
    /// stone's width, when given, is the photograph's; each cut's own material and width come
    /// later, stone by stone): a laboratory picture or a photograph, by the light (no
    /// animation: a face adds its rock or turntable). An error names the setting; a
    /// photographic setting with a laboratory light, or a head shadow with a photographic one,
    /// is refused.
    pub fn pictures(&self, material: &Material, size: StoneSize) -> Result<Pictures> {
        match &self.light {
            LightChoice::Photo(light) => self
                .photo(light.clone(), material, size)
                .map(Pictures::Photo),
            LightChoice::Lab(light) => {
                if let Some(name) = self.photographic().next() {
                    return Err(Error::invalid(
                        name,
                        format!(
                            "is for photographs; give a photographic {} ({} or env:FILE)",
                            setting(LIGHT),
                            PhotoLight::names().join(", ")
                        ),
                    ));
                }
                self.lab(*light, material).map(Pictures::Lab)
            }
        }
    }

    fn lab(&self, light: Light, material: &Material) -> Result<LabPictures> {
        let mut opts = RenderOptions::new(light);
        opts.size = self.size.unwrap_or(opts.size);
        opts.tilt = self.tilt.unwrap_or(opts.tilt);
        opts.head_shadow_deg = self.head_shadow;
        opts.material = material.clone();
        opts.trace.polarization = self.polarization;
        opts.validate().map_err(named)?;
        Ok(LabPictures {
            opts,
            rock: None,
            exposure: self.exposure.unwrap_or(1.0),
        })
    }

    fn photo(
        &self,
        light: PhotoLight,
        material: &Material,
        size: StoneSize,
    ) -> Result<PhotoPictures> {
        let mut o = PhotoOptions::new(light);
        o.size = self.size.unwrap_or(o.size);
        o.view = self.view.unwrap_or(o.view);
        o.tilt = self.tilt.unwrap_or(o.tilt);
        if self.head_shadow.is_some() {
            return Err(Error::invalid(
                HEAD_SHADOW,
                "is for the laboratory lights; a photograph's camera casts no head shadow",
            ));
        }
        o.material = material.clone();
        o.polarization = self.polarization;
        if let Some(kind) = self.ground {
            o.ground = Ground { kind, gap: 0.0 };
        }
        o.ground.gap = self.ground_gap.unwrap_or(o.ground.gap);
        o.light_rotation_deg = self.light_rotation.unwrap_or(o.light_rotation_deg);
        o.tone = self.tone.unwrap_or(o.tone);
        o.bands = self.bands.unwrap_or(o.bands);
        o.distance_mm = self.distance.or(o.distance_mm);
        o.aperture_mm = self.aperture.or(o.aperture_mm);
        // The width the stone is seen at (for a perspective camera and absorption).
        if let StoneSize::Width(w) = size {
            o.width_mm = w;
        }
        o.validate().map_err(named)?;
        // A gap under no ground would be ignored: refused, as a photographic setting is with a
        // laboratory light.
        if self.ground_gap.is_some() && o.ground.kind == GroundKind::None {
            return Err(Error::invalid(
                GROUND_GAP,
                format!(
                    "is the stone's height above a ground; give {} white or black",
                    setting(GROUND)
                ),
            ));
        }
        Ok(PhotoPictures {
            opts: o,
            turn: None,
            rock: None,
            exposure: self.exposure.unwrap_or(1.0),
        })
    }
}

/// An error of a picture's `validate`, which names the field by the picture's own word
/// (`view`, `ground-gap`), named by its setting (`picture view`); a field no setting here
/// sets (the material, the tile) stays as it is.
fn named(e: Error) -> Error {
    match e {
        Error::Invalid { field, message } => {
            let name = format!("picture {field}");
            let field = if SETTINGS.contains(&name.as_str()) {
                name
            } else {
                field
            };
            Error::Invalid { field, message }
        }
        other => other,
    }
}

/// The laboratory pictures (iso, cos, aset, …): the options of the face-up (or tilted)
/// picture, a rock and the exposure.
#[derive(Clone, Debug)]
pub struct LabPictures {
    /// Options of the face-up (or tilted) picture; its material is the chosen one.
    pub opts: RenderOptions,
    /// A rock's amplitude in degrees and number of frames.
    pub rock: Option<(f64, usize)>,
    /// Brightness factor.
    pub exposure: f64,
}

impl LabPictures {
    /// The pose of frame `k`: the picture's pose rocked by `DEG·sin(2πk/FRAMES)` toward its
    /// azimuth.
    pub fn frame_tilt(&self, k: usize) -> Tilt {
        match self.rock {
            None => self.opts.tilt,
            Some(rock) => rocked(self.opts.tilt, rock, k),
        }
    }

    /// Number of frames (1 without a rock).
    pub fn frames(&self) -> usize {
        self.rock.map_or(1, |r| r.1)
    }
}

/// Photographs under a studio rig: frame 0's options, a turntable or a rock, the exposure.
#[derive(Clone, Debug)]
pub struct PhotoPictures {
    /// Options of frame 0; its material is the chosen one.
    pub opts: PhotoOptions,
    /// A turntable's number of frames.
    pub turn: Option<usize>,
    /// A rock's amplitude in degrees and number of frames.
    pub rock: Option<(f64, usize)>,
    /// Brightness factor.
    pub exposure: f64,
}

impl PhotoPictures {
    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.turn.or(self.rock.map(|r| r.1)).unwrap_or(1)
    }

    /// Options of frame `k`.
    pub fn frame(&self, k: usize) -> PhotoOptions {
        match (self.turn, self.rock) {
            (Some(n), _) => turntable(&self.opts, n, k),
            (None, Some(rock)) => PhotoOptions {
                tilt: rocked(self.opts.tilt, rock, k),
                ..self.opts.clone()
            },
            _ => self.opts.clone(),
        }
    }
}

/// The pictures `render` draws.
#[derive(Clone, Debug)]
pub enum Pictures {
    /// Under a laboratory light.
    Lab(LabPictures),
    /// Photographs.
    Photo(PhotoPictures),
}

impl Pictures {
    /// Number of frames.
    pub fn frames(&self) -> usize {
        match self {
            Pictures::Lab(p) => p.frames(),
            Pictures::Photo(p) => p.frames(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::photo::parse_view;
    use crate::render::pose::parse_tilt;

    /// A picture's settings as text, each read by its parser as a face does ([`read`]).
    #[derive(Default)]
    struct Text {
        light: String,
        size: Option<String>,
        tilt: Option<String>,
        head_shadow: Option<String>,
        exposure: Option<String>,
        view: Option<String>,
        distance: Option<String>,
        aperture: Option<String>,
        ground: Option<String>,
        ground_gap: Option<String>,
        tone: Option<String>,
        bands: Option<String>,
    }

    impl Text {
        fn new(light: &str) -> Text {
            Text {
                light: light.into(),
                ..Text::default()
            }
        }
        fn settings(&self) -> Result<PictureSettings> {
            Ok(PictureSettings {
                size: read(self.size.as_deref(), SIZE, parse_size)?,
                tilt: read(self.tilt.as_deref(), TILT, parse_tilt)?,
                head_shadow: read(self.head_shadow.as_deref(), HEAD_SHADOW, parse_head_shadow)?,
                exposure: read(self.exposure.as_deref(), EXPOSURE, parse_exposure)?,
                view: read(self.view.as_deref(), VIEW, parse_view)?,
                distance: read(self.distance.as_deref(), DISTANCE, parse_distance)?,
                aperture: read(self.aperture.as_deref(), APERTURE, parse_aperture)?,
                ground: read(self.ground.as_deref(), GROUND, GroundKind::parse)?,
                ground_gap: read(self.ground_gap.as_deref(), GROUND_GAP, parse_ground_gap)?,
                tone: read(self.tone.as_deref(), TONE, Tone::parse)?,
                bands: read(self.bands.as_deref(), BANDS, parse_bands)?,
                ..PictureSettings::new(LightChoice::parse(LIGHT, &self.light)?)
            })
        }
    }

    fn error(s: &Text) -> String {
        s.settings()
            .and_then(|v| v.pictures(&Material::diamond(), StoneSize::default()))
            .unwrap_err()
            .to_string()
    }

    fn pictures(s: &Text) -> Pictures {
        s.settings()
            .unwrap()
            .pictures(&Material::diamond(), StoneSize::default())
            .unwrap()
    }

    #[test]
    fn the_light_chooses_a_laboratory_picture_or_a_photograph() {
        let mut s = Text::new("aset");
        s.tilt = Some("10@45".into());
        s.size = Some("64".into());
        match pictures(&s) {
            Pictures::Lab(p) => {
                assert_eq!(p.opts.light, Light::Aset);
                assert_eq!((p.opts.size, p.opts.tilt.tilt_deg), (64, 10.0));
                assert_eq!(p.opts.tilt.azimuth_deg, 45.0);
                assert_eq!(p.exposure, 1.0);
            }
            other => panic!("{other:?}"),
        }
        let mut s = Text::new("Tent");
        s.view = Some("60@90".into());
        s.ground = Some("white".into());
        s.ground_gap = Some("0.5".into());
        s.tone = Some("clip".into());
        s.bands = Some("12".into());
        s.exposure = Some("2".into());
        s.distance = Some("100".into());
        match pictures(&s) {
            Pictures::Photo(p) => {
                let o = &p.opts;
                assert_eq!(o.light.name(), "tent");
                assert_eq!((o.view.elevation_deg, o.view.azimuth_deg), (60.0, 90.0));
                assert_eq!((o.ground.kind, o.ground.gap), (GroundKind::White, 0.5));
                assert_eq!(
                    (o.tone, o.bands, o.distance_mm),
                    (Tone::Clip, 12, Some(100.0))
                );
                assert_eq!(p.exposure, 2.0);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn every_error_names_its_setting() {
        type Change = fn(&mut Text);
        let cases: [(&str, Change); 15] = [
            ("picture light: `sunset` is not allowed; use iso, cos, aset, idealscope, hearts, arrows, fire, tent, darkfield, daylight, office, ring, studio or env:FILE", |s| s.light = "sunset".into()),
            ("picture size: `4` is not allowed; give a whole number from 8 to 8192", |s| s.size = Some("4".into())),
            ("picture view: ", |s| { s.light = "tent".into(); s.view = Some("95".into()) }),
            ("picture ground-gap: `11` is not allowed; give girdle diameters in [0, 10]", |s| { s.light = "ring".into(); s.ground_gap = Some("11".into()) }),
            ("picture ground: ", |s| { s.light = "ring".into(); s.ground = Some("grass".into()) }),
            ("picture tone: ", |s| { s.light = "ring".into(); s.tone = Some("sepia".into()) }),
            ("picture head-shadow: is for the laboratory lights; a photograph's camera casts no head shadow", |s| { s.light = "ring".into(); s.head_shadow = Some("5".into()) }),
            ("picture distance: 10 mm is out of range; allowed 19.5 mm", |s| { s.light = "ring".into(); s.distance = Some("10".into()) }),
            ("picture aperture: `-1` is not allowed; give millimetres (0 = a pinhole) in [0, 100]", |s| { s.light = "ring".into(); s.aperture = Some("-1".into()) }),
            ("picture aperture: `nan` is not allowed", |s| { s.light = "ring".into(); s.aperture = Some("nan".into()) }),
            ("picture aperture: 50 mm is out of range; allowed 0 (a pinhole) to 35.3 mm, an entrance pupil seen within ±10° from 100 mm", |s| { s.light = "ring".into(); s.distance = Some("100".into()); s.aperture = Some("50".into()) }),
            ("picture aperture: is for photographs", |s| s.aperture = Some("0".into())),
            ("picture bands: is for photographs; give a photographic picture light (tent, darkfield, daylight, office, ring, studio or env:FILE)", |s| s.bands = Some("8".into())),
            ("picture ground-gap: is the stone's height above a ground; give picture ground white or black", |s| { s.light = "tent".into(); s.ground_gap = Some("0.5".into()) }),
            ("picture ground-gap: is the stone's height above a ground", |s| { s.light = "tent".into(); s.ground = Some("none".into()); s.ground_gap = Some("0".into()) }),
        ];
        for (want, set) in cases {
            let mut s = Text::new("iso");
            set(&mut s);
            let got = error(&s);
            assert!(got.starts_with(want), "{got}\nwanted {want}");
        }
    }
}
