//! Poses of the stone under the viewer: the tilt ([`Tilt`]), the rotation a picture uses
//! ([`view_rotation`]) and the square every pose of a stone shares ([`picture_half`]); and
//! poses written as text: a tilt `DEG[@AZ]` ([`parse_tilt`]) and a rock `DEG:FRAMES` (the stone
//! rocked about its tilt, one picture per frame: [`parse_rock`], [`rocked`]), as
//! `facetlab render --tilt` and `--rock` take them.

use super::light::Light;
use crate::error::{Error, Result};
use crate::geometry::Polyhedron;
use crate::io::text::{count, number};
use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

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

/// Rotation taking the stone's coordinates to the world's for a picture: the pose, after
/// turning the stone over for the hearts view (a half-turn about the x axis).
pub fn view_rotation(light: Light, tilt: Tilt) -> DMat3 {
    let r = tilt.rotation();
    if light == Light::Hearts {
        r * DMat3::from_rotation_x(std::f64::consts::PI)
    } else {
        r
    }
}

/// A pose as a picture's caption says it: `face-up`, or `face-down` under the hearts viewer
/// (which turns the stone over, [`view_rotation`]); a tilted pose `tilt 10.0° toward 45°`,
/// with `, face-down` for the hearts.
///
/// ```
/// use facetlab::render::{pose::describe, Light, Tilt};
/// assert_eq!(describe(Light::Iso, Tilt::FACE_UP), "face-up");
/// assert_eq!(describe(Light::Hearts, Tilt::FACE_UP), "face-down");
/// let t = Tilt { tilt_deg: 10.0, azimuth_deg: 45.0 };
/// assert_eq!(describe(Light::Hearts, t), "tilt 10.0° toward 45°, face-down");
/// ```
pub fn describe(light: Light, tilt: Tilt) -> String {
    let down = light == Light::Hearts;
    if tilt.tilt_deg == 0.0 {
        if down { "face-down" } else { "face-up" }.to_string()
    } else {
        format!(
            "tilt {:.1}° toward {}°{}",
            tilt.tilt_deg,
            tilt.azimuth_deg,
            if down { ", face-down" } else { "" }
        )
    }
}

/// Half the side of the square a picture of `solid` (in its canonical placement) spans: its
/// largest distance from the centroid, plus 0.1 %. The same for every pose, so that the
/// frames of a rocking stone share one pixel grid (scintillation compares them pixel by
/// pixel), and the same for the scores' images and the pictures.
pub fn picture_half(solid: &Polyhedron) -> f64 {
    solid
        .vertices()
        .iter()
        .map(|v| v.length())
        .fold(0.0, f64::max)
        * 1.001
}

/// `DEG` or `DEG@AZ`: a tilt in [−90, 90] degrees toward azimuth AZ in [−360, 360] degrees
/// (default 0); the error names `field`.
///
/// ```
/// use facetlab::render::pose::parse_tilt;
/// let t = parse_tilt("tilt", "10@45").unwrap();
/// assert_eq!((t.tilt_deg, t.azimuth_deg), (10.0, 45.0));
/// assert!(parse_tilt("tilt", "91").is_err());
/// ```
pub fn parse_tilt(field: &str, s: &str) -> Result<Tilt> {
    let bad = || {
        Error::invalid(
            field,
            format!("`{s}` is not allowed; give DEG or DEG@AZ: a tilt in [-90, 90] degrees toward azimuth AZ in [-360, 360] degrees (10@45)"),
        )
    };
    let (t, az) = match s.split_once('@') {
        Some((t, az)) => (t, az),
        None => (s, "0"),
    };
    let tilt_deg = number(field, t, -90.0, 90.0, "degrees").map_err(|_| bad())?;
    let azimuth_deg = number(field, az, -360.0, 360.0, "degrees").map_err(|_| bad())?;
    Ok(Tilt {
        tilt_deg,
        azimuth_deg,
    })
}

/// `DEG:FRAMES`: a rock of DEG in (0, 60] degrees over FRAMES in 2..=240 frames, as
/// `(DEG, FRAMES)`; the error names `field`.
///
/// ```
/// use facetlab::render::pose::parse_rock;
/// assert_eq!(parse_rock("rock", "15:24").unwrap(), (15.0, 24));
/// assert!(parse_rock("rock", "0:24").is_err());
/// ```
pub fn parse_rock(field: &str, s: &str) -> Result<(f64, usize)> {
    let bad = || {
        Error::invalid(
            field,
            format!("`{s}` is not allowed; give DEG:FRAMES with DEG in (0, 60] degrees and FRAMES in 2..=240 (15:24)"),
        )
    };
    let (d, n) = s.split_once(':').ok_or_else(bad)?;
    let deg = number(field, d, 0.0, 60.0, "degrees").map_err(|_| bad())?;
    if deg <= 0.0 {
        return Err(bad());
    }
    let n = count(field, n, 2, 240).map_err(|_| bad())? as usize;
    Ok((deg, n))
}

/// The pose of frame `k` of a rock `(deg, frames)` about `base`: tilted
/// `deg·sin(2πk/frames)` more toward the same azimuth.
pub fn rocked(base: Tilt, (deg, frames): (f64, usize), k: usize) -> Tilt {
    Tilt {
        tilt_deg: base.tilt_deg + deg * (std::f64::consts::TAU * k as f64 / frames as f64).sin(),
        azimuth_deg: base.azimuth_deg,
    }
}

/// A birefringent stone's optic axis carried into the canonical placement of `solid` (see
/// [`crate::geometry::canonical::canonical_axis`]); `+z` for any other stone (unused).
pub(crate) fn canonical_optic_axis(
    solid: &Polyhedron,
    material: &crate::optics::Material,
) -> glam::DVec3 {
    material.uniaxial.as_ref().map_or(glam::DVec3::Z, |u| {
        crate::geometry::canonical::canonical_axis(solid, u.axis.vector())
    })
}
