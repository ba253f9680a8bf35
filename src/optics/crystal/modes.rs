//! The two modes a wave has in the crystal for a given tangential wave vector on a facet, in
//! complex arithmetic (evanescent modes included) and in real arithmetic (the common case).

use super::boundary::{signed_root, Field, Tangent};
use super::complex::{CVec3, C};
use super::uniaxial::Crystal;
use super::wave::{Wave, WaveMode};
use glam::DVec3;

impl Crystal {
    /// The two modes (ordinary, extraordinary) with tangential wave vector `tg.kt` leaving
    /// the facet along `σ ν`.
    pub(super) fn modes(&self, tg: &Tangent, sigma: f64) -> [Field; 2] {
        self.raw_modes(tg, sigma)
            .map(|f| Field::new(f.k, f.e, f.propagating))
    }

    /// [`Crystal::modes`] with fields not normalised.
    #[inline]
    pub(super) fn raw_modes(&self, tg: &Tangent, sigma: f64) -> [Field; 2] {
        let c = self.axis;
        let (eo, ee) = (self.eps_o, self.eps_e);
        // Ordinary.
        let (qo, real_o) = signed_root(eo - tg.kt2, sigma);
        let ko = CVec3::affine(tg.kt, tg.nu, qo);
        let mut eo_field = ko.cross(CVec3::real(c));
        // Extraordinary.
        let d = ee - eo;
        let (a, b) = (tg.kt.dot(c), tg.nu.dot(c));
        let qa = eo + d * b * b;
        let qb = d * a * b;
        let qc = eo * tg.kt2 + d * a * a - eo * ee;
        let (root, real_e) = signed_root(qb * qb - qa * qc, sigma);
        let qe = (root - C::real(qb)).scale(1.0 / qa);
        let ke = CVec3::affine(tg.kt, tg.nu, qe);
        let kc = ke.dot_real(c);
        let dfield = ke.times(kc) - CVec3::real(c).times(ke.dot(ke));
        let dc = dfield.dot_real(c);
        let mut ee_field =
            dfield.scale(1.0 / eo) + CVec3::real(c).times(dc.scale(1.0 / ee - 1.0 / eo));
        // Along the optic axis the two modes are one (any polarization ⊥ ĉ): take the s
        // direction for the ordinary wave and ĉ × s for the extraordinary one.
        if eo_field.norm_sqr() <= 1e-24 * ko.norm_sqr() {
            let s = tg.t2 - c * tg.t2.dot(c);
            let s = if s.length_squared() > 1e-12 {
                s.normalize()
            } else {
                (tg.t1 - c * tg.t1.dot(c)).normalize()
            };
            eo_field = CVec3::real(s);
            ee_field = CVec3::real(c.cross(s));
        } else if ee_field.norm_sqr() <= 1e-24 * ke.norm_sqr() * ke.norm_sqr() {
            ee_field = CVec3::real(c).cross(eo_field);
        }
        [
            Field::raw(ko, eo_field, real_o),
            Field::raw(ke, ee_field, real_e),
        ]
    }

    /// What both sides' real modes share for tangential wave vector `tg.kt`: the square
    /// roots of the ordinary and extraordinary normal components' equations and the
    /// latter's coefficients; `None` unless both modes propagate. [`Crystal::real_modes`]
    /// of either side follows from them, so a facet's incident and reflected sides take
    /// their square roots once.
    #[inline]
    pub(super) fn real_roots(&self, tg: &Tangent) -> Option<RealRoots> {
        let c = self.axis;
        let (eo, ee) = (self.eps_o, self.eps_e);
        let go = eo - tg.kt2;
        let d = ee - eo;
        let (a, b) = (tg.kt.dot(c), tg.nu.dot(c));
        let qa = eo + d * b * b;
        let qb = d * a * b;
        let qc = eo * tg.kt2 + d * a * a - eo * ee;
        let disc = qb * qb - qa * qc;
        if go < 0.0 || disc < 0.0 {
            return None;
        }
        Some(RealRoots {
            ordinary: go.sqrt(),
            extraordinary: disc.sqrt(),
            qa,
            qb,
        })
    }

    /// Both modes' real wave vectors and (not normalised) fields leaving the facet along
    /// `σ ν` when both propagate (`roots` from [`Crystal::real_roots`]), the common case:
    /// [`Crystal::raw_modes`] in real arithmetic.
    #[inline]
    pub(super) fn real_modes(
        &self,
        tg: &Tangent,
        roots: &RealRoots,
        sigma: f64,
    ) -> [(DVec3, DVec3); 2] {
        let c = self.axis;
        let (eo, ee) = (self.eps_o, self.eps_e);
        let ko = tg.kt + tg.nu * (sigma * roots.ordinary);
        let ke = tg.kt + tg.nu * ((sigma * roots.extraordinary - roots.qb) / roots.qa);
        let mut fo = ko.cross(c);
        let dfield = ke * ke.dot(c) - c * ke.length_squared();
        let mut fe = dfield / eo + c * (dfield.dot(c) * (1.0 / ee - 1.0 / eo));
        if fo.length_squared() <= 1e-24 * ko.length_squared() {
            let s = tg.t2 - c * tg.t2.dot(c);
            let s = if s.length_squared() > 1e-12 {
                s.normalize()
            } else {
                (tg.t1 - c * tg.t1.dot(c)).normalize()
            };
            fo = s;
            fe = c.cross(s);
        } else if fe.length_squared() <= 1e-24 * ke.length_squared() * ke.length_squared() {
            fe = c.cross(fo);
        }
        [(ko, fo), (ke, fe)]
    }

    /// A propagating wave of mode `mode` from its boundary field (real for a propagating
    /// wave: `S = E × (k × E) = k |E|² − E (E · k)`).
    #[inline]
    pub(super) fn wave(f: &Field, mode: WaveMode) -> Wave {
        Crystal::wave_of(f.k.re, f.e.re, mode)
    }

    /// The propagating wave of `mode` with real wave vector `k` and field `e` (not
    /// normalised).
    #[inline]
    pub(super) fn wave_of(k: DVec3, e: DVec3, mode: WaveMode) -> Wave {
        let s = k * e.length_squared() - e * e.dot(k);
        Wave {
            mode,
            k,
            ray: s.normalize(),
            field: e.normalize(),
        }
    }
}

/// The square roots and coefficients both sides' real modes share ([`Crystal::real_roots`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct RealRoots {
    /// `√(ε_o − |k_t|²)`: the ordinary wave's normal component (up to its side's sign).
    ordinary: f64,
    /// The square root of the extraordinary wave's quadratic's discriminant.
    extraordinary: f64,
    /// The extraordinary wave's quadratic's leading and half-middle coefficients.
    qa: f64,
    qb: f64,
}
