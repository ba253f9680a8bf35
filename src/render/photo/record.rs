//! A photograph's statistics as documents ([`PhotoRecord`], `render --json`) and captions
//! ([`caption`]), and the poses of its animations ([`turntable`]).

use super::options::PhotoOptions;
use super::{GroundStats, PhotoStats, View};
use crate::optics::Dispersion;
use serde::Serialize;

/// The options of frame `k` of a turntable of `frames` frames: the stone turned
/// `360° · k / frames` about the vertical under the camera and lights.
pub fn turntable(opts: &PhotoOptions, frames: usize, k: usize) -> PhotoOptions {
    PhotoOptions {
        turn_deg: opts.turn_deg + 360.0 * k as f64 / frames.max(1) as f64,
        ..opts.clone()
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
    /// Seconds.
    pub elapsed_s: f64,
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
        }
    }
}

/// One photographed cut as `render --json` writes it (keys in the README).
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
    /// statistics, exposure and outputs.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        name: &str,
        input: &str,
        opts: &PhotoOptions,
        stats: &PhotoStats,
        exposure: f64,
        output: &str,
        hdr_output: Option<&str>,
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
            output: output.to_string(),
            hdr_output: hdr_output.map(str::to_string),
            turn_frames,
            frames: (frames.len() > 1).then_some(frames),
        }
    }
}

/// Caption lines of a photograph (after the cut's name): the light, view and ground, and
/// the stone's mean luminance.
pub fn caption(opts: &PhotoOptions, stats: &PhotoStats) -> Vec<String> {
    let v = opts.view;
    let view = if v.elevation_deg == 90.0 {
        "from above".to_string()
    } else if v.elevation_deg == 0.0 {
        "side view".to_string()
    } else {
        format!("{:.0}° above", v.elevation_deg)
    };
    let cam = match opts.distance_mm {
        Some(d) => format!("{view}, {d:.0} mm away"),
        None => view,
    };
    let mut first = format!("{}, {cam}", opts.light.name());
    if opts.ground.kind != super::GroundKind::None {
        first.push_str(&format!(", {} ground", opts.ground.kind.name()));
    }
    vec![first, format!("mean {:.1} %", 100.0 * stats.mean)]
}
