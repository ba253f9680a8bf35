//! Planes and facet planes (a cut's named, tiered half-spaces), facet angles and azimuths, and the
//! tolerances of "on the plane" and of welding.

use super::DVec3;
use serde::{Deserialize, Serialize};

/// Tolerance for "on the plane" tests, in girdle diameters.
pub const EPS: f64 = 1e-10;
/// Vertices closer than this are welded into one. Solids whose edges do not pair at this
/// tolerance (planes from rounded mesh coordinates) are re-welded at up to 1000× it
/// (1e-5 D is 65 nm on a 6.5 mm stone).
pub const WELD: f64 = 1e-8;

/// An oriented plane `normal · x = offset`; the solid is on the side `normal · x <= offset`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Plane {
    /// Outward unit normal.
    pub normal: DVec3,
    /// Signed distance of the plane from the origin along `normal`.
    pub offset: f64,
}

impl Plane {
    /// A plane from any non-zero normal (normalised here) and an offset along the given normal
    /// (scaled with it). Returns `None` for a zero or non-finite normal.
    pub fn new(normal: DVec3, offset: f64) -> Option<Plane> {
        let len = normal.length();
        if !(len.is_finite() && len > 0.0 && offset.is_finite()) {
            return None;
        }
        Some(Plane {
            normal: normal / len,
            offset: offset / len,
        })
    }

    /// The plane with outward normal `normal` (normalised) through the point `p`.
    pub fn through(normal: DVec3, p: DVec3) -> Option<Plane> {
        let n = normal.try_normalize()?;
        Some(Plane {
            normal: n,
            offset: n.dot(p),
        })
    }

    /// Signed distance: positive outside, negative inside.
    #[inline]
    pub fn distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}

/// Outward normal of a facet tilted `angle_deg` from the girdle plane, facing azimuth
/// `azimuth_deg` (measured from +x toward +y); `crown` selects the upper (+z) or lower side.
pub fn facet_normal(angle_deg: f64, azimuth_deg: f64, crown: bool) -> DVec3 {
    let (a, phi) = (angle_deg.to_radians(), azimuth_deg.to_radians());
    let z = if crown { a.cos() } else { -a.cos() };
    DVec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), z)
}

/// Angle of a facet with outward normal `n` against the girdle plane, in degrees
/// (table and culet 0°, girdle 90°).
pub fn facet_angle_deg(n: DVec3) -> f64 {
    n.z.abs().min(1.0).acos().to_degrees()
}

/// Azimuth of a facet normal in degrees in [0, 360).
pub fn facet_azimuth_deg(n: DVec3) -> f64 {
    let a = n.y.atan2(n.x).to_degrees();
    if a < 0.0 {
        a + 360.0
    } else {
        a
    }
}

/// One facet plane of a cut with its name and tier (the kind of facet: table, bezel, star,
/// upper-half, girdle, pavilion-main, lower-half, culet, or a file's own tier name).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FacetPlane {
    /// The facet's plane, outward normal.
    pub plane: Plane,
    /// Facet name, unique within a cut (e.g. `bezel-3`).
    pub name: String,
    /// Tier (kind) of the facet.
    pub tier: String,
}

impl FacetPlane {
    /// A facet plane from a normal and offset (normal need not be unit length).
    pub fn new(
        normal: DVec3,
        offset: f64,
        name: impl Into<String>,
        tier: impl Into<String>,
    ) -> FacetPlane {
        let plane = Plane::new(normal, offset).unwrap_or(Plane {
            normal: DVec3::Z,
            offset: f64::NAN,
        });
        FacetPlane {
            plane,
            name: name.into(),
            tier: tier.into(),
        }
    }
}
