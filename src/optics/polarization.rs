//! Stokes vectors and the Mueller matrices of a plane interface.

use glam::{DVec3, DVec4};

/// A Stokes vector `(I, Q, U, V)`.
pub type Stokes = DVec4;

/// A Mueller matrix of the block form an interface has in its s–p frame:
/// `[[a, b, 0, 0], [b, a, 0, 0], [0, 0, c, s], [0, 0, −s, c]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mueller {
    /// Intensity gain for unpolarized light.
    pub a: f64,
    /// Diattenuation term (s minus p).
    pub b: f64,
    /// Retardance cosine term.
    pub c: f64,
    /// Retardance sine term.
    pub s: f64,
}

impl Mueller {
    /// The block matrix with these entries.
    pub fn block(a: f64, b: f64, c: f64, s: f64) -> Mueller {
        Mueller { a, b, c, s }
    }
    /// Apply to a Stokes vector given in the interface's s–p frame.
    #[inline]
    pub fn apply(&self, v: Stokes) -> Stokes {
        DVec4::new(
            self.a * v.x + self.b * v.y,
            self.b * v.x + self.a * v.y,
            self.c * v.z + self.s * v.w,
            -self.s * v.z + self.c * v.w,
        )
    }
    /// The full 4×4 matrix, row-major (for tests and printing).
    pub fn rows(&self) -> [[f64; 4]; 4] {
        [
            [self.a, self.b, 0.0, 0.0],
            [self.b, self.a, 0.0, 0.0],
            [0.0, 0.0, self.c, self.s],
            [0.0, 0.0, -self.s, self.c],
        ]
    }
}

/// Unit vector perpendicular to the plane of incidence of direction `d` on a surface with
/// normal `n` (`d × n` normalised); `None` at normal incidence.
#[inline]
pub fn s_axis(d: DVec3, n: DVec3) -> Option<DVec3> {
    let s = d.cross(n);
    let l2 = s.length_squared();
    if l2 < 1e-24 {
        None
    } else {
        Some(s / l2.sqrt())
    }
}

/// Re-express Stokes vector `v`, given with reference axis `from` (⊥ `d`), with reference axis
/// `to` (⊥ `d`). Intensity and degree of polarization are unchanged.
#[inline]
pub fn rotate_stokes(v: Stokes, from: DVec3, to: DVec3, d: DVec3) -> Stokes {
    let cos = from.dot(to);
    let sin = from.cross(to).dot(d);
    // cos 2ψ, sin 2ψ from cos ψ, sin ψ (no trig).
    let (c2, s2) = (cos * cos - sin * sin, 2.0 * sin * cos);
    DVec4::new(v.x, v.y * c2 + v.z * s2, -v.y * s2 + v.z * c2, v.w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::fresnel;

    fn dop(v: Stokes) -> f64 {
        (v.y * v.y + v.z * v.z + v.w * v.w).sqrt() / v.x
    }

    #[test]
    fn mueller_matrices_are_physical() {
        for deg in [0.0f64, 10.0, 30.0, 50.0, 67.5, 85.0] {
            for (ni, nt) in [(1.0, 2.4173), (2.4173, 1.0)] {
                let f = fresnel(deg.to_radians().cos(), ni, nt);
                let (r, t) = (f.mueller_reflect(), f.mueller_transmit());
                // Unpolarized: R + T = 1.
                let u = DVec4::new(1.0, 0.0, 0.0, 0.0);
                assert!((r.apply(u).x + t.apply(u).x - 1.0).abs() < 1e-12);
                // Pure s and pure p light: R + T = 1 each, with Rs and Rp.
                let s = DVec4::new(1.0, 1.0, 0.0, 0.0);
                let p = DVec4::new(1.0, -1.0, 0.0, 0.0);
                assert!(
                    (r.apply(s).x - f.r_s).abs() < 1e-12 && (r.apply(p).x - f.r_p).abs() < 1e-12
                );
                assert!((r.apply(s).x + t.apply(s).x - 1.0).abs() < 1e-12);
                // A reflection of fully polarized light stays fully polarized (pure amplitudes).
                let v = DVec4::new(1.0, 0.3, 0.5, (1.0f64 - 0.09 - 0.25).sqrt());
                let out = r.apply(v);
                assert!((dop(out) - 1.0).abs() < 1e-9, "dop {}", dop(out));
            }
        }
    }

    #[test]
    fn tir_turns_linear_into_elliptical() {
        // 45° linear light totally reflected at 45° inside diamond picks up circular part.
        let f = fresnel(45f64.to_radians().cos(), 2.4173, 1.0);
        assert!(f.tir);
        let out = f.mueller_reflect().apply(DVec4::new(1.0, 0.0, 1.0, 0.0));
        assert!((out.x - 1.0).abs() < 1e-12);
        assert!((out.z - f.phase_difference().cos()).abs() < 1e-12);
        assert!((out.w.abs() - f.phase_difference().sin().abs()).abs() < 1e-12);
    }

    #[test]
    fn stokes_rotation() {
        let d = DVec3::Z;
        let v = DVec4::new(1.0, 1.0, 0.0, 0.0); // linear along x
                                                // Reference axis x → y (90°): the same light is now Q = −1.
        let w = rotate_stokes(v, DVec3::X, DVec3::Y, d);
        assert!((w - DVec4::new(1.0, -1.0, 0.0, 0.0)).length() < 1e-12);
        // 45°: Q → U sign convention, and a round trip is the identity.
        let a = DVec3::new(1.0, 1.0, 0.0).normalize();
        let w = rotate_stokes(v, DVec3::X, a, d);
        assert!((w - DVec4::new(1.0, 0.0, -1.0, 0.0)).length() < 1e-12);
        let back = rotate_stokes(w, a, DVec3::X, d);
        assert!((back - v).length() < 1e-12);
    }
}
