//! The pieces of a boundary problem at a facet: a wave's [`Field`], the facet's tangent
//! frame ([`Tangent`]), the isotropic side's s and p waves, Jones and Stokes vectors, and the
//! 4×4 solve of the four continuity equations ([`amplitudes`]).

use super::complex::{solve4, CVec3, C};
use crate::optics::polarization::Stokes;
use glam::{DVec3, DVec4};

/// One wave of a boundary problem: its normal component, complex wave vector, unit field,
/// `H = k × E`, and whether it propagates.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Field {
    pub(super) k: CVec3,
    pub(super) e: CVec3,
    pub(super) h: CVec3,
    pub(super) propagating: bool,
}

impl Field {
    /// A field with `E = e` as given (not normalised): powers are ratios of amplitude squared
    /// times flux, so they do not depend on the scale.
    #[inline]
    pub(super) fn raw(k: CVec3, e: CVec3, propagating: bool) -> Field {
        Field {
            k,
            e,
            h: k.cross(e),
            propagating,
        }
    }
    pub(super) fn new(k: CVec3, e: CVec3, propagating: bool) -> Field {
        let n = e.norm_sqr().sqrt();
        let e = e.scale(1.0 / n);
        Field {
            k,
            e,
            h: k.cross(e),
            propagating,
        }
    }
    /// Time-averaged energy flux through a plane of normal `nu`, per unit amplitude squared
    /// (`½ Re(E × H*) · ν`).
    pub(super) fn flux(&self, nu: DVec3) -> f64 {
        0.5 * self.e.cross_conj_re(self.h).dot(nu)
    }
}

/// A tangential frame on a facet: `t1` along the tangential wave vector (any direction in the
/// facet when there is none), `t2 = ν × t1` (the s direction of the isotropic side).
#[derive(Clone, Copy, Debug)]
pub(super) struct Tangent {
    pub(super) nu: DVec3,
    pub(super) kt: DVec3,
    pub(super) kt2: f64,
    pub(super) t1: DVec3,
    pub(super) t2: DVec3,
}

impl Tangent {
    pub(super) fn new(k: DVec3, nu: DVec3) -> Tangent {
        let kt = k - nu * k.dot(nu);
        let kt2 = kt.length_squared();
        let t1 = if kt2 > 1e-30 {
            kt / kt2.sqrt()
        } else {
            nu.any_orthonormal_vector()
        };
        Tangent {
            nu,
            kt,
            kt2,
            t1,
            t2: nu.cross(t1),
        }
    }
}

/// `σ √x` for `x ≥ 0`, `σ i √(−x)` otherwise (a wave decaying along σν), and whether it is
/// real.
#[inline]
pub(super) fn signed_root(x: f64, sigma: f64) -> (C, bool) {
    if x >= 0.0 {
        (C::real(sigma * x.sqrt()), true)
    } else {
        (C::new(0.0, sigma * (-x).sqrt()), false)
    }
}

/// The s and p waves of an isotropic medium of index `n` leaving the facet along `σ ν`
/// (`σ = ±1`): s along `t2`, p along `k × t2`.
pub(super) fn isotropic_modes(n: f64, tg: &Tangent, sigma: f64) -> [Field; 2] {
    let (q, real) = signed_root(n * n - tg.kt2, sigma);
    let k = CVec3::affine(tg.kt, tg.nu, q);
    let s = CVec3::real(tg.t2);
    [Field::new(k, s, real), Field::new(k, k.cross(s), real)]
}

/// Stokes vector `(I, Q, U, V)` of a Jones vector `(a_s, a_p)`: `Q = |a_s|² − |a_p|²`,
/// `U = 2 Re(a_s a_p*)`, `V = −2 Im(a_s a_p*)` (the convention of
/// [`Mueller`](crate::optics::Mueller)).
#[inline]
pub(super) fn jones_stokes(a_s: C, a_p: C) -> Stokes {
    let c = a_s * a_p.conj();
    let (ss, pp) = (a_s.norm_sqr(), a_p.norm_sqr());
    DVec4::new(ss + pp, ss - pp, 2.0 * c.re, -2.0 * c.im)
}

/// The coherency matrix `[[ρ_ss, ρ_sp], [ρ_ps, ρ_pp]]` of a Stokes vector (inverse of
/// [`jones_stokes`] summed over an ensemble).
#[inline]
pub(super) fn coherency(s: Stokes) -> [[C; 2]; 2] {
    [
        [C::real(0.5 * (s.x + s.y)), C::new(0.5 * s.z, -0.5 * s.w)],
        [C::new(0.5 * s.z, 0.5 * s.w), C::real(0.5 * (s.x - s.y))],
    ]
}

/// `⟨|Σ_b m_b J_b|²⟩ = Σ_ab m_a ρ_ab m_b*` for a row `m` and coherency `ρ`.
#[inline]
pub(super) fn quad(m: [C; 2], rho: &[[C; 2]; 2]) -> f64 {
    let mut s = C::default();
    for a in 0..2 {
        for b in 0..2 {
            s = s + m[a] * rho[a][b] * m[b].conj();
        }
    }
    s.re
}

/// Amplitudes of the two reflected and two transmitted waves for an incoming wave `inc`,
/// from continuity of tangential E and H on the facet (tangent frame `tg`); `None` when the
/// system is singular (grazing incidence).
pub(super) fn amplitudes(
    tg: &Tangent,
    inc: &Field,
    refl: &[Field; 2],
    trans: &[Field; 2],
) -> Option<([C; 2], [C; 2])> {
    let rows = |f: &Field| -> [C; 4] {
        [
            f.e.dot_real(tg.t1),
            f.e.dot_real(tg.t2),
            f.h.dot_real(tg.t1),
            f.h.dot_real(tg.t2),
        ]
    };
    let (r0, r1, t0, t1, i) = (
        rows(&refl[0]),
        rows(&refl[1]),
        rows(&trans[0]),
        rows(&trans[1]),
        rows(inc),
    );
    let mut a = [[C::default(); 4]; 4];
    let mut b = [C::default(); 4];
    for row in 0..4 {
        a[row] = [r0[row], r1[row], -t0[row], -t1[row]];
        b[row] = -i[row];
    }
    let x = solve4(a, b)?;
    Some(([x[0], x[1]], [x[2], x[3]]))
}
