//! The plain values a photograph's light is made of: linear sRGB radiance, its luminance, and a
//! direction on the sky given by elevation and azimuth (shared by the environments of `env.rs`
//! and the maps of `envmap.rs`).

use glam::DVec3;

/// Linear sRGB.
pub type Rgb = [f64; 3];

/// Luminance Y of linear sRGB (white = 1).
pub fn luminance(c: Rgb) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// Unit vector at `elevation_deg` above the horizon toward `azimuth_deg` (from +x toward +y).
pub fn direction(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}
