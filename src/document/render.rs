//! The render document, as `facetlab render --json` writes it (keys in docs/commands.md): per cut,
//! a picture's statistics ([`CutJson`], with [`FrameJson`] per frame of a rocking animation)
//! or a photograph's ([`PhotoRecord`], with [`PhotoFrame`] per frame of a turntable or rock).
//! One cut is written as its object, several as an array of them in the order given.

use crate::optics::Dispersion;
use crate::render::photo::{GroundStats, PhotoOptions, PhotoStats, View};
use crate::render::{RenderOptions, Stats, Tilt};
use serde::Serialize;

/// Statistics of one frame.
#[derive(Clone, Debug, Serialize)]
pub struct FrameJson {
    /// Frame number, from 0.
    pub frame: usize,
    /// Tilt of this frame, degrees.
    pub tilt_deg: f64,
    /// Azimuth the stone tips toward, degrees.
    pub azimuth_deg: f64,
    /// Mean of the picture over the outline (relative to a white diffuser).
    pub mean: f64,
    /// ASET shares (aset only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aset: Option<crate::render::AsetShares>,
    /// Fire of this one placement of the spot lights, in percent (fire only): `placement_fire`,
    /// not the score's `fire`, which averages the lights' placements.
    #[serde(rename = "placement_fire", skip_serializing_if = "Option::is_none")]
    pub fire: Option<f64>,
    /// Colour of a coloured stone's picture (L*, C*, h°, spread, extinction face-up under ISO
    /// light or else `dark_share`, windowing).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<crate::render::ColourStats>,
    /// Share of light below the tracer's thresholds.
    pub cut_off: f64,
    /// Exit beams drawn.
    pub exits: usize,
    /// Rendering time, seconds.
    pub elapsed_s: f64,
}

impl FrameJson {
    /// Frame `frame` drawn at `tilt` with statistics `s` in `elapsed_s` seconds.
    pub fn new(frame: usize, tilt: Tilt, s: &Stats, elapsed_s: f64) -> FrameJson {
        FrameJson {
            frame,
            tilt_deg: tilt.tilt_deg,
            azimuth_deg: tilt.azimuth_deg,
            mean: s.mean,
            aset: s.aset,
            fire: s.fire,
            colour: s.colour,
            cut_off: s.cut_off,
            exits: s.exits,
            elapsed_s,
        }
    }
}

/// Statistics of one cut (see the module documentation for the keys).
#[derive(Clone, Debug, Serialize)]
pub struct CutJson {
    /// The cut's name.
    pub name: String,
    /// CUT as given.
    pub input: String,
    /// Light name.
    pub light: &'static str,
    /// Pixels per side.
    pub size: usize,
    /// Mean of the picture over the outline (frame 0 with --rock).
    pub mean: f64,
    /// ASET shares (aset only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aset: Option<crate::render::AsetShares>,
    /// Fire of this one placement of the spot lights, in percent (fire only): `placement_fire`,
    /// not the score's `fire`, which averages the lights' placements.
    #[serde(rename = "placement_fire", skip_serializing_if = "Option::is_none")]
    pub fire: Option<f64>,
    /// Colour of a coloured stone's picture (a body colour under a grey light): `l`, `c`,
    /// `h_deg` (CIELAB L*, C*, h° of the mean colour), `l_spread` (standard deviation of the
    /// pixels' L*), `extinction` (share of the outline whose light through the stone is
    /// darker than L* 20: the score's, in a face-up ISO picture only) or else `dark_share`
    /// (the same share of this picture, under its own name), `windowing` (share of the light
    /// seen that comes from below the girdle plane); all on the colour grid
    /// ([`crate::render::COLOUR_GRID`]), whatever the picture's size.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<crate::render::ColourStats>,
    /// The stone's width in mm (with a body colour).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub width_mm: Option<f64>,
    /// Tilt, degrees.
    pub tilt_deg: f64,
    /// Azimuth of the tilt, degrees.
    pub azimuth_deg: f64,
    /// Head shadow / port / head half-angle in use, degrees.
    pub head_shadow_deg: f64,
    /// Material name.
    pub material: String,
    /// The fixed index of `--ri`, else null.
    pub ri: Option<f64>,
    /// Polarization tracked.
    pub polarization: bool,
    /// `--exposure`.
    pub exposure: f64,
    /// Share of light below the tracer's thresholds.
    pub cut_off: f64,
    /// Exit beams drawn.
    pub exits: usize,
    /// Rendering time of this cut, all frames, seconds.
    pub elapsed_s: f64,
    /// The PNG written.
    pub output: String,
    /// `--rock` amplitude, degrees.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rock_deg: Option<f64>,
    /// Per-frame statistics (with --rock).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frames: Option<Vec<FrameJson>>,
}

impl CutJson {
    /// Cut `name` (given as `input`) drawn with `opts` (its own material, the one it is traced
    /// in, and width; the pose of frame 0) in `frames` (frame 0 first, at least one), with
    /// exposure `exposure` and the rock's
    /// amplitude `rock_deg` (its frames are listed only with a rock). `output` is empty until
    /// the caller writes the picture.
    pub fn new(
        (name, input): (&str, &str),
        opts: &RenderOptions,
        exposure: f64,
        frames: Vec<FrameJson>,
        rock_deg: Option<f64>,
    ) -> CutJson {
        let f0 = &frames[0];
        CutJson {
            name: name.to_string(),
            input: input.to_string(),
            light: opts.light.name(),
            size: opts.size,
            mean: f0.mean,
            aset: f0.aset,
            fire: f0.fire,
            colour: f0.colour,
            width_mm: opts.material.colour.is_some().then_some(opts.width_mm),
            tilt_deg: f0.tilt_deg,
            azimuth_deg: f0.azimuth_deg,
            head_shadow_deg: opts.head_shadow(),
            material: opts.material.name.clone(),
            ri: match opts.material.dispersion {
                Dispersion::Constant(n) => Some(n),
                _ => None,
            },
            polarization: opts.trace.polarization,
            exposure,
            cut_off: f0.cut_off,
            exits: f0.exits,
            elapsed_s: frames.iter().map(|f| f.elapsed_s).sum(),
            output: String::new(),
            rock_deg,
            frames: rock_deg.is_some().then_some(frames),
        }
    }
}

/// Statistics of one frame of an animation.
#[derive(Clone, Debug, Serialize)]
pub struct PhotoFrame {
    /// Frame number, from 0.
    pub frame: usize,
    /// The turntable's angle, degrees.
    pub turn_deg: f64,
    /// The stone's tilt in this frame, degrees.
    pub tilt_deg: f64,
    /// Mean luminance of the stone's light over its outline.
    pub mean: f64,
    /// Share of the light cut off.
    pub cut_off: f64,
    /// Exit beams drawn.
    pub exits: usize,
    /// Seconds (0 for a frame that repeats another).
    pub elapsed_s: f64,
    /// The frame whose picture this one repeats (a turntable of a symmetric stone: the
    /// stone turned by one of its own symmetries, see
    /// [`turntable_period`](crate::render::photo::turntable_period)); absent when traced.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub same_as: Option<usize>,
}

impl PhotoFrame {
    /// Frame `frame` taken with `opts`, with its statistics and time.
    pub fn new(frame: usize, opts: &PhotoOptions, stats: &PhotoStats, elapsed_s: f64) -> Self {
        PhotoFrame {
            frame,
            turn_deg: opts.turn_deg,
            tilt_deg: opts.tilt.tilt_deg,
            mean: stats.mean,
            cut_off: stats.cut_off,
            exits: stats.exits,
            elapsed_s,
            same_as: None,
        }
    }
}

/// One photographed cut as `render --json` writes it (keys in docs/commands.md).
#[derive(Clone, Debug, Serialize)]
pub struct PhotoRecord {
    /// The cut's name.
    pub name: String,
    /// CUT as given.
    pub input: String,
    /// The light's name (a rig, `studio` or `env:FILE`).
    pub light: String,
    /// Its turn about the vertical, degrees.
    pub light_rotation_deg: f64,
    /// Pixels per side.
    pub size: usize,
    /// Where the camera looks from.
    pub view: View,
    /// Camera distance (perspective), mm; null for orthographic.
    pub distance_mm: Option<f64>,
    /// Tile side of a perspective picture, pixels.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tile: Option<usize>,
    /// The entrance pupil given, mm (0: a pinhole).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aperture_mm: Option<f64>,
    /// The half-angle the light is seen through, degrees ([`PhotoOptions::aperture_deg`]),
    /// unless it is the scores' ±1°.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aperture_deg: Option<f64>,
    /// The ground: none, white or black.
    pub ground: &'static str,
    /// Height of the stone's lowest point above the ground, girdle diameters.
    pub ground_gap: f64,
    /// The stone's tilt, degrees, and its azimuth.
    pub tilt_deg: f64,
    /// Azimuth of the tilt, degrees.
    pub azimuth_deg: f64,
    /// Tone curve.
    pub tone: &'static str,
    /// Exposure factor.
    pub exposure: f64,
    /// Material name.
    pub material: String,
    /// A fixed index, else null.
    pub ri: Option<f64>,
    /// Polarization tracked.
    pub polarization: bool,
    /// Wavelength bands traced (0: a stone without dispersion or colour, traced once in
    /// red, green and blue).
    pub bands: usize,
    /// The stone's width, mm.
    pub width_mm: f64,
    /// Mean luminance of the stone's light over its outline, relative to a white diffuser
    /// under the ISO sky (frame 0 of an animation).
    pub mean: f64,
    /// Share of the light cut off by the tracer's thresholds.
    pub cut_off: f64,
    /// Exit beams drawn.
    pub exits: usize,
    /// Traces of the picture (bands × tiles).
    pub traces: usize,
    /// The light on the ground (with a ground): directions traced, power intercepted by the
    /// stone, landing as caustics inside and beyond the raster, escaping, absorbed, cut off,
    /// their balance, the shadow's area and the unshadowed irradiance (luminance).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ground_light: Option<GroundStats>,
    /// Seconds (all frames).
    pub elapsed_s: f64,
    /// The picture written.
    pub output: String,
    /// The linear picture written (`--hdr-out`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hdr_output: Option<String>,
    /// Frames of a turntable (`--turn`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turn_frames: Option<usize>,
    /// Per frame, with an animation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frames: Option<Vec<PhotoFrame>>,
}

impl PhotoRecord {
    /// The record of cut `name` (given as `input`) taken with `opts` (frame 0's), its
    /// statistics and exposure, and its `frames` (`turn_frames` of a turntable); the files it
    /// was written to are [`PhotoRecord::written`]'s.
    pub fn new(
        name: &str,
        input: &str,
        opts: &PhotoOptions,
        stats: &PhotoStats,
        exposure: f64,
        frames: Vec<PhotoFrame>,
        turn_frames: Option<usize>,
    ) -> PhotoRecord {
        PhotoRecord {
            name: name.to_string(),
            input: input.to_string(),
            light: opts.light.name(),
            light_rotation_deg: opts.light_rotation_deg,
            size: opts.size,
            view: opts.view,
            distance_mm: opts.distance_mm,
            tile: opts.distance_mm.map(|_| opts.tile),
            aperture_mm: opts.aperture_mm,
            aperture_deg: Some(opts.aperture_deg())
                .filter(|&d| d != crate::render::lighting::EDGE_DEG),
            ground: opts.ground.kind.name(),
            ground_gap: opts.ground.gap,
            tilt_deg: opts.tilt.tilt_deg,
            azimuth_deg: opts.tilt.azimuth_deg,
            tone: opts.tone.name(),
            exposure,
            material: opts.material.name.clone(),
            ri: match opts.material.dispersion {
                Dispersion::Constant(n) => Some(n),
                _ => None,
            },
            polarization: opts.polarization,
            bands: stats.bands,
            width_mm: opts.width_mm,
            mean: stats.mean,
            cut_off: stats.cut_off,
            exits: stats.exits,
            traces: stats.traces,
            ground_light: stats.ground,
            elapsed_s: frames.iter().map(|f| f.elapsed_s).sum(),
            output: String::new(),
            hdr_output: None,
            turn_frames,
            frames: (frames.len() > 1).then_some(frames),
        }
    }

    /// The record with the picture written to `output` (and the linear picture to
    /// `hdr_output`).
    pub fn written(self, output: &str, hdr_output: Option<&str>) -> PhotoRecord {
        PhotoRecord {
            output: output.to_string(),
            hdr_output: hdr_output.map(str::to_string),
            ..self
        }
    }
}
