//! Light in a uniaxial crystal and at its facets, exactly: the two modes a plane wave has
//! inside (ordinary and extraordinary) for a given wave vector along a facet, their ray
//! (Poynting) directions, and the Fresnel coefficients of every mode on entry, on exit and
//! on internal reflection from the full boundary conditions.
//!
//! Units: wave vectors in units of the vacuum wave number k₀, so that `|k| = n` for a wave of
//! index `n`; fields with `H = k × E` (impedance of free space 1). The crystal has principal
//! dielectric constants `ε_o = n_o²` (for E ⊥ ĉ) and `ε_e = n_e²` (E ∥ ĉ), optic axis ĉ.
//!
//! **Modes.** At a plane facet with unit normal ν the tangential part `K` of the wave vector
//! is the same for every wave (phase matching), so each mode's wave vector is `k = K + q ν`
//! with one unknown `q`:
//!
//! * ordinary: `|k|² = ε_o`, so `q = ±√(ε_o − K²)`; E ∝ k × ĉ;
//! * extraordinary: `(|k|² − (k·ĉ)²)/ε_e + (k·ĉ)²/ε_o = 1`, a quadratic
//!   `A q² + 2B q + C = 0` with `A = ε_o + Δ b²`, `B = Δ a b`, `C = ε_o K² + Δ a² − ε_o ε_e`
//!   (`a = K·ĉ`, `b = ν·ĉ`, `Δ = ε_e − ε_o`). Its roots are not mirror images of each other:
//!   `q = (−B ± √(B² − A C))/A`. The field: D ∝ (k·ĉ) k − (k·k) ĉ, E = ε⁻¹ D.
//!
//! A negative discriminant makes the mode evanescent (a complex `q` decaying away from the
//! facet): total internal reflection is decided per mode, on its wave vector. Of the two
//! roots, the one whose energy flows away from the facet on the side in question is the one
//! that exists there: for the extraordinary wave the flux along ν is proportional to
//! `A q + B = ±√(B² − A C)`, so the sign in front of the root is the direction.
//!
//! **Rays.** Energy travels along the Poynting vector `S = Re(E × H*)`, which for the
//! extraordinary wave is `k/ε_e + (k·ĉ) ĉ (1/ε_o − 1/ε_e)` up to a factor, off the wave
//! vector by the walk-off angle. A parallel beam moves along S; its wave vector stays fixed
//! between facets.
//!
//! **Boundary conditions.** An incoming wave of either mode meets a facet and sends out two
//! reflected waves (the two modes on its own side) and two transmitted waves (the two modes,
//! or the s and p waves of an isotropic medium, on the other side). Continuity of the
//! tangential E and H (four complex equations) gives their four amplitudes
//! ([`Crystal::enter`], [`Crystal::meet`]); each propagating wave's power is its amplitude
//! squared times its Poynting flux through the facet, over the incoming wave's. What is
//! reflected plus what is transmitted is 1 (tested to 1e-12; Berreman's 4×4 transfer-matrix
//! method, written independently in the tests, gives the same powers to 1e-10).
//!
//! **Absorption (pleochroism).** A weakly absorbing uniaxial crystal has absorption
//! coefficients α_o (E ⊥ ĉ) and α_e (E ∥ ĉ) as measured along principal directions. A mode
//! with unit field E and wave vector k loses power along its ray at the rate
//! `(α_o n_o |E⊥|² + α_e n_e |E∥|²) / |E × (k × E)|` (absorbed power density `½ E·ε''·E`,
//! with `ε''_j = α_j n_j` from the principal measurements, over the energy flux): α_o for
//! every ordinary wave, α_e for an extraordinary wave travelling ⊥ ĉ, in between otherwise
//! ([`Crystal::absorption`]). It is constant along a beam, so Beer–Lambert over a beam's
//! footprint stays exact.
//!
//! References: J. Lekner, "Reflection and refraction by uniaxial crystals", J. Phys.:
//! Condens. Matter 3, 6121–6133 (1991); P. Yeh, "Electromagnetic propagation in birefringent
//! layered media", J. Opt. Soc. Am. 69, 742–756 (1979); D. W. Berreman, "Optics in
//! stratified and anisotropic media: 4×4-matrix formulation", J. Opt. Soc. Am. 62, 502–510
//! (1972).

mod complex;
#[cfg(test)]
mod tests;

pub use complex::{CVec3, C};

use super::polarization::{rotate_stokes, Stokes};
use complex::solve4;
use glam::{DVec3, DVec4};

/// The two modes of a plane wave in a uniaxial crystal.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum WaveMode {
    /// The ordinary wave: E ⊥ ĉ, index n_o in every direction.
    Ordinary,
    /// The extraordinary wave: index between n_o and n_e, walking off its wave vector.
    Extraordinary,
}

impl WaveMode {
    /// Both modes, ordinary first (the order of every two-mode array here).
    pub const BOTH: [WaveMode; 2] = [WaveMode::Ordinary, WaveMode::Extraordinary];
    /// 0 for ordinary, 1 for extraordinary.
    #[inline]
    pub fn index(self) -> usize {
        self as usize
    }
    /// `o` or `e`.
    pub fn letter(self) -> &'static str {
        match self {
            WaveMode::Ordinary => "o",
            WaveMode::Extraordinary => "e",
        }
    }
}

/// A uniaxial crystal at one wavelength, in the stone's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crystal {
    /// Ordinary index n_o (ω).
    pub n_o: f64,
    /// Extraordinary index n_e (ε).
    pub n_e: f64,
    /// Optic axis ĉ (unit).
    pub axis: DVec3,
    eps_o: f64,
    eps_e: f64,
}

/// A propagating wave inside the crystal: what a beam carries between facets.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wave {
    /// Its mode.
    pub mode: WaveMode,
    /// Wave vector (units of k₀; `|k|` is the mode's index along it).
    pub k: DVec3,
    /// Ray direction: the unit Poynting vector, along which the beam moves.
    pub ray: DVec3,
    /// Unit electric field (real for a propagating wave in a lossless crystal).
    pub field: DVec3,
}

/// One wave of a boundary problem: its normal component, complex wave vector, unit field,
/// `H = k × E`, and whether it propagates.
#[derive(Clone, Copy, Debug, Default)]
struct Field {
    k: CVec3,
    e: CVec3,
    h: CVec3,
    propagating: bool,
}

impl Field {
    /// A field with `E = e` as given (not normalised): powers are ratios of amplitude squared
    /// times flux, so they do not depend on the scale.
    #[inline]
    fn raw(k: CVec3, e: CVec3, propagating: bool) -> Field {
        Field {
            k,
            e,
            h: k.cross(e),
            propagating,
        }
    }
    fn new(k: CVec3, e: CVec3, propagating: bool) -> Field {
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
    fn flux(&self, nu: DVec3) -> f64 {
        0.5 * self.e.cross_conj_re(self.h).dot(nu)
    }
}

/// A tangential frame on a facet: `t1` along the tangential wave vector (any direction in the
/// facet when there is none), `t2 = ν × t1` (the s direction of the isotropic side).
#[derive(Clone, Copy, Debug)]
struct Tangent {
    nu: DVec3,
    kt: DVec3,
    kt2: f64,
    t1: DVec3,
    t2: DVec3,
}

impl Tangent {
    fn new(k: DVec3, nu: DVec3) -> Tangent {
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
fn signed_root(x: f64, sigma: f64) -> (C, bool) {
    if x >= 0.0 {
        (C::real(sigma * x.sqrt()), true)
    } else {
        (C::new(0.0, sigma * (-x).sqrt()), false)
    }
}

/// The s and p waves of an isotropic medium of index `n` leaving the facet along `σ ν`
/// (`σ = ±1`): s along `t2`, p along `k × t2`.
fn isotropic_modes(n: f64, tg: &Tangent, sigma: f64) -> [Field; 2] {
    let (q, real) = signed_root(n * n - tg.kt2, sigma);
    let k = CVec3::affine(tg.kt, tg.nu, q);
    let s = CVec3::real(tg.t2);
    [Field::new(k, s, real), Field::new(k, k.cross(s), real)]
}

/// Stokes vector `(I, Q, U, V)` of a Jones vector `(a_s, a_p)`: `Q = |a_s|² − |a_p|²`,
/// `U = 2 Re(a_s a_p*)`, `V = −2 Im(a_s a_p*)` (the convention of
/// [`Mueller`](super::Mueller)).
#[inline]
fn jones_stokes(a_s: C, a_p: C) -> Stokes {
    let c = a_s * a_p.conj();
    let (ss, pp) = (a_s.norm_sqr(), a_p.norm_sqr());
    DVec4::new(ss + pp, ss - pp, 2.0 * c.re, -2.0 * c.im)
}

/// The coherency matrix `[[ρ_ss, ρ_sp], [ρ_ps, ρ_pp]]` of a Stokes vector (inverse of
/// [`jones_stokes`] summed over an ensemble).
#[inline]
fn coherency(s: Stokes) -> [[C; 2]; 2] {
    [
        [C::real(0.5 * (s.x + s.y)), C::new(0.5 * s.z, -0.5 * s.w)],
        [C::new(0.5 * s.z, 0.5 * s.w), C::real(0.5 * (s.x - s.y))],
    ]
}

/// `⟨|Σ_b m_b J_b|²⟩ = Σ_ab m_a ρ_ab m_b*` for a row `m` and coherency `ρ`.
#[inline]
fn quad(m: [C; 2], rho: &[[C; 2]; 2]) -> f64 {
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
fn amplitudes(
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

/// Light arriving from outside: what is reflected and what enters in each mode.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// Direction of the externally reflected light.
    pub reflected_dir: DVec3,
    /// Its Stokes vector (intensity = its power), reference axis [`Entry::axis`].
    pub reflected: Stokes,
    /// Reference axis of both Stokes vectors (the s direction, ⊥ the plane of incidence).
    pub axis: DVec3,
    /// The two refracted waves (ordinary, extraordinary) with the power each carries.
    pub transmitted: [(Wave, f64); 2],
}

/// Light inside meeting a facet: what is reflected back in, in each mode, and what leaves.
#[derive(Clone, Copy, Debug)]
pub struct Meeting {
    /// The reflected waves (ordinary, extraordinary) with their powers; an evanescent one
    /// (total internal reflection of that mode) has power 0.
    pub reflected: [(Wave, f64); 2],
    /// Direction of the light leaving (meaningless when [`Meeting::exit_power`] is 0).
    pub exit_dir: DVec3,
    /// Power leaving (0 under total internal reflection).
    pub exit_power: f64,
    /// Stokes vector of the light leaving (intensity = `exit_power`), reference axis
    /// [`Meeting::axis`].
    pub exit: Stokes,
    /// Reference axis of [`Meeting::exit`].
    pub axis: DVec3,
}

impl Crystal {
    /// A crystal with ordinary index `n_o`, extraordinary index `n_e` and optic axis `axis`
    /// (normalised here).
    pub fn new(n_o: f64, n_e: f64, axis: DVec3) -> Crystal {
        Crystal {
            n_o,
            n_e,
            axis: axis.normalize(),
            eps_o: n_o * n_o,
            eps_e: n_e * n_e,
        }
    }

    /// The extraordinary index for wave normal `dir` (unit):
    /// `1/n² = cos²θ/n_o² + sin²θ/n_e²`, θ the angle between `dir` and ĉ.
    pub fn extraordinary_index(&self, dir: DVec3) -> f64 {
        let c = dir.dot(self.axis);
        let c2 = (c * c).min(1.0);
        1.0 / (c2 / self.eps_o + (1.0 - c2) / self.eps_e).sqrt()
    }

    /// The two modes (ordinary, extraordinary) with tangential wave vector `tg.kt` leaving
    /// the facet along `σ ν`.
    fn modes(&self, tg: &Tangent, sigma: f64) -> [Field; 2] {
        self.raw_modes(tg, sigma)
            .map(|f| Field::new(f.k, f.e, f.propagating))
    }

    /// [`Crystal::modes`] with fields not normalised.
    #[inline]
    fn raw_modes(&self, tg: &Tangent, sigma: f64) -> [Field; 2] {
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

    /// Both modes' real wave vectors and (not normalised) fields when both propagate, the
    /// common case: [`Crystal::raw_modes`] in real arithmetic.
    #[inline]
    fn real_modes(&self, tg: &Tangent, sigma: f64) -> Option<[(DVec3, DVec3); 2]> {
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
        let ko = tg.kt + tg.nu * (sigma * go.sqrt());
        let ke = tg.kt + tg.nu * ((sigma * disc.sqrt() - qb) / qa);
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
        Some([(ko, fo), (ke, fe)])
    }

    /// [`Crystal::meet`] when the incident and both reflected modes propagate (`inc`, `refl`:
    /// wave vectors and fields from [`Crystal::real_modes`]): the same equations with the
    /// crystal's side in real arithmetic.
    #[inline]
    fn meet_real(
        &self,
        tg: &Tangent,
        inc: (DVec3, DVec3),
        refl: [(DVec3, DVec3); 2],
    ) -> Option<Meeting> {
        let (q, out_real) = signed_root(1.0 - tg.kt2, 1.0);
        let nu = tg.nu;
        // Tangential E and H, and the flux along ν (½ (E × H) · ν), of a real field.
        let tan = |(k, e): (DVec3, DVec3)| {
            let h = k.cross(e);
            (
                [e.dot(tg.t1), e.dot(tg.t2), h.dot(tg.t1), h.dot(tg.t2)],
                0.5 * e.cross(h).dot(nu),
            )
        };
        let ((i, f_in), (o, f_o), (e, f_e)) = (tan(inc), tan(refl[0]), tan(refl[1]));
        if f_in.is_nan() || f_in <= 0.0 {
            return None;
        }
        let a11 = C::real(o[0]) - q.scale(o[3]);
        let a12 = C::real(e[0]) - q.scale(e[3]);
        let a21 = C::real(o[2]) + q.scale(o[1]);
        let a22 = C::real(e[2]) + q.scale(e[1]);
        let b1 = q.scale(i[3]) - C::real(i[0]);
        let b2 = -q.scale(i[1]) - C::real(i[2]);
        let det = a11 * a22 - a12 * a21;
        if !(det.norm_sqr() > 0.0 && det.norm_sqr().is_finite()) {
            return None;
        }
        let r = [(b1 * a22 - a12 * b2) / det, (a11 * b2 - b1 * a21) / det];
        let wave = |(k, e): (DVec3, DVec3), mode| {
            let s = k * e.length_squared() - e * e.dot(k);
            Wave {
                mode,
                k,
                ray: s.normalize(),
                field: e.normalize(),
            }
        };
        let reflected = [
            (
                wave(refl[0], WaveMode::Ordinary),
                -r[0].norm_sqr() * f_o / f_in,
            ),
            (
                wave(refl[1], WaveMode::Extraordinary),
                -r[1].norm_sqr() * f_e / f_in,
            ),
        ];
        let (exit_dir, exit_power, exit) = if out_real {
            let t_s = C::real(i[1]) + r[0].scale(o[1]) + r[1].scale(e[1]);
            let t_p = -(C::real(i[3]) + r[0].scale(o[3]) + r[1].scale(e[3]));
            let st = jones_stokes(t_s, t_p) * (0.5 * q.re / f_in);
            ((tg.kt + tg.nu * q.re).normalize(), st.x, st)
        } else {
            (DVec3::ZERO, 0.0, DVec4::ZERO)
        };
        Some(Meeting {
            reflected,
            exit_dir,
            exit_power,
            exit,
            axis: tg.t2,
        })
    }

    /// A propagating wave of mode `mode` from its boundary field (real for a propagating
    /// wave: `S = E × (k × E) = k |E|² − E (E · k)`).
    #[inline]
    fn wave(f: &Field, mode: WaveMode) -> Wave {
        let (k, e) = (f.k.re, f.e.re);
        let s = k * e.length_squared() - e * e.dot(k);
        Wave {
            mode,
            k,
            ray: s.normalize(),
            field: e.normalize(),
        }
    }

    /// The propagating wave of `mode` with unit wave normal `dir` (its wave vector is the
    /// mode's index along `dir` times `dir`).
    pub fn wave_along(&self, dir: DVec3, mode: WaveMode) -> Wave {
        let dir = dir.normalize();
        let n = match mode {
            WaveMode::Ordinary => self.n_o,
            WaveMode::Extraordinary => self.extraordinary_index(dir),
        };
        let tg = Tangent::new(dir * n, dir);
        let f = self.modes(&tg, 1.0)[mode.index()];
        Crystal::wave(&f, mode)
    }

    /// Absorption per unit of ray path of `wave`, for principal absorption coefficients
    /// `alpha_o` (E ⊥ ĉ) and `alpha_e` (E ∥ ĉ) per the same unit (see the module
    /// documentation).
    #[inline]
    pub fn absorption(&self, wave: &Wave, alpha_o: f64, alpha_e: f64) -> f64 {
        let e = wave.field;
        let ec = e.dot(self.axis);
        let par = ec * ec;
        let s = wave.k - e * e.dot(wave.k);
        (alpha_o * self.n_o * (1.0 - par) + alpha_e * self.n_e * par) / s.length()
    }

    /// Light arriving from outside (index 1) along unit direction `d` at a facet with outward
    /// unit normal `n` (`d · n < 0`), with Stokes vector `stokes` whose reference axis is
    /// `axis` (⊥ `d`): the externally reflected light and the two refracted waves. `None` at
    /// grazing incidence.
    pub fn enter(&self, d: DVec3, n: DVec3, stokes: Stokes, axis: DVec3) -> Option<Entry> {
        let nu = -n;
        let tg = Tangent::new(d, nu);
        let inc = isotropic_modes(1.0, &tg, 1.0);
        let refl = isotropic_modes(1.0, &tg, -1.0);
        let trans = self.modes(&tg, 1.0);
        let (rs, ts) = amplitudes(&tg, &inc[0], &refl, &trans)?;
        let (rp, tp) = amplitudes(&tg, &inc[1], &refl, &trans)?;
        let f_in = inc[0].flux(nu);
        if f_in.is_nan() || f_in <= 0.0 {
            return None;
        }
        let s_axis = tg.t2;
        let rho = coherency(rotate_stokes(stokes, axis, s_axis, d));
        let reflected_dir = d - 2.0 * d.dot(n) * n;
        // Reflected Jones matrix (rows: reflected s, p; columns: incident s, p).
        let r = [[rs[0], rp[0]], [rs[1], rp[1]]];
        let mut out = [[C::default(); 2]; 2];
        for a in 0..2 {
            for b in 0..2 {
                let mut v = C::default();
                for x in 0..2 {
                    for y in 0..2 {
                        v = v + r[a][x] * rho[x][y] * r[b][y].conj();
                    }
                }
                out[a][b] = v;
            }
        }
        let gain = -refl[0].flux(nu) / f_in;
        let reflected = DVec4::new(
            out[0][0].re + out[1][1].re,
            out[0][0].re - out[1][1].re,
            2.0 * out[0][1].re,
            -2.0 * out[0][1].im,
        ) * gain;
        let transmitted = [0, 1].map(|m| {
            let mode = WaveMode::BOTH[m];
            let f = &trans[m];
            let p = if f.propagating {
                quad([ts[m], tp[m]], &rho) * f.flux(nu) / f_in
            } else {
                0.0
            };
            (Crystal::wave(f, mode), p)
        });
        Some(Entry {
            reflected_dir,
            reflected,
            axis: s_axis,
            transmitted,
        })
    }

    /// Light inside in `wave` (of unit power) meeting a facet with outward unit normal `n`
    /// (`wave.ray · n > 0`), the outside of index 1: the two reflected waves and the light
    /// leaving. `None` at grazing incidence.
    ///
    /// The outside's s and p waves are simple enough to take out of the four boundary
    /// equations by hand (their tangential E and H are `(0, 1)`, `(−q, 0)` for s and
    /// `(−q, 0)`, `(0, −1)` for p, in the frame `t1, t2`), which leaves two equations for the
    /// reflected amplitudes: the same solution as the 4×4 system of [`Crystal::enter`]
    /// (both are held to Berreman's in the tests) for a fifth of the time.
    pub fn meet(&self, wave: &Wave, n: DVec3) -> Option<Meeting> {
        let nu = n;
        let tg = Tangent::new(wave.k, nu);
        if let (Some(mi), Some(mr)) = (self.real_modes(&tg, 1.0), self.real_modes(&tg, -1.0)) {
            return self.meet_real(&tg, mi[wave.mode.index()], mr);
        }
        let inc = self.raw_modes(&tg, 1.0)[wave.mode.index()];
        let refl = self.raw_modes(&tg, -1.0);
        let (q, out_real) = signed_root(1.0 - tg.kt2, 1.0);
        let tan = |f: &Field| {
            [
                f.e.dot_real(tg.t1),
                f.e.dot_real(tg.t2),
                f.h.dot_real(tg.t1),
                f.h.dot_real(tg.t2),
            ]
        };
        let (i, o, e) = (tan(&inc), tan(&refl[0]), tan(&refl[1]));
        // (E1 − q H2) · r = q H2ᵢ − E1ᵢ and (H1 + q E2) · r = −q E2ᵢ − H1ᵢ.
        let a11 = o[0] - q * o[3];
        let a12 = e[0] - q * e[3];
        let a21 = o[2] + q * o[1];
        let a22 = e[2] + q * e[1];
        let b1 = q * i[3] - i[0];
        let b2 = -(q * i[1]) - i[2];
        let det = a11 * a22 - a12 * a21;
        if !(det.norm_sqr() > 0.0 && det.norm_sqr().is_finite()) {
            return None;
        }
        let r = [(b1 * a22 - a12 * b2) / det, (a11 * b2 - b1 * a21) / det];
        let f_in = inc.flux(nu);
        if f_in.is_nan() || f_in <= 0.0 {
            return None;
        }
        let reflected = [0, 1].map(|m| {
            let f = &refl[m];
            if f.propagating {
                let p = -r[m].norm_sqr() * f.flux(nu) / f_in;
                (Crystal::wave(f, WaveMode::BOTH[m]), p)
            } else {
                (
                    Wave {
                        mode: WaveMode::BOTH[m],
                        k: DVec3::ZERO,
                        ray: DVec3::ZERO,
                        field: DVec3::ZERO,
                    },
                    0.0,
                )
            }
        });
        let (exit_dir, exit_power, exit) = if out_real {
            let t_s = i[1] + r[0] * o[1] + r[1] * e[1];
            let t_p = -(i[3] + r[0] * o[3] + r[1] * e[3]);
            // The s and p waves carry ½ q of flux per amplitude squared.
            let st = jones_stokes(t_s, t_p) * (0.5 * q.re / f_in);
            ((tg.kt + tg.nu * q.re).normalize(), st.x, st)
        } else {
            (DVec3::ZERO, 0.0, DVec4::ZERO)
        };
        Some(Meeting {
            reflected,
            exit_dir,
            exit_power,
            exit,
            axis: tg.t2,
        })
    }
}
