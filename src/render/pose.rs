//! Poses of the stone under the viewer: the tilt ([`Tilt`]), the rotation a picture uses
//! ([`view_rotation`]) and the square every pose of a stone shares ([`picture_half`]).

use super::light::Light;
use crate::geometry::Polyhedron;
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
