//! A photograph's captions ([`caption`]) and the poses of its animations ([`turntable`]).

use super::options::PhotoOptions;
use super::PhotoStats;

/// The options of frame `k` of a turntable of `frames` frames: the stone turned
/// `360° · k / frames` about the vertical under the camera and lights.
pub fn turntable(opts: &PhotoOptions, frames: usize, k: usize) -> PhotoOptions {
    PhotoOptions {
        turn_deg: opts.turn_deg + 360.0 * k as f64 / frames.max(1) as f64,
        ..opts.clone()
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
