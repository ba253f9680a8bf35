//! Light inside meeting a facet: the two reflected waves and the light leaving
//! ([`Crystal::meet`]).

use super::boundary::{jones_stokes, signed_root, Field, Tangent};
use super::complex::C;
use super::uniaxial::Crystal;
use super::wave::{Wave, WaveMode};
use crate::optics::polarization::Stokes;
use glam::{DVec3, DVec4};

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

/// [`Meeting`] before its reflected waves are built: each reflected mode's real wave vector
/// and (not normalised) field, and its power (0, with zero vectors, for an evanescent one).
/// A trace that follows one of the two builds only that one ([`RawMeeting::wave`]); the
/// numbers are those of [`Crystal::meet`], bit for bit.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RawMeeting {
    /// Wave vector, field and power of the reflected waves (ordinary, extraordinary).
    pub(crate) reflected: [(DVec3, DVec3, f64); 2],
    /// As [`Meeting::exit_dir`].
    pub(crate) exit_dir: DVec3,
    /// As [`Meeting::exit_power`].
    pub(crate) exit_power: f64,
    /// As [`Meeting::exit`].
    pub(crate) exit: Stokes,
    /// As [`Meeting::axis`].
    pub(crate) axis: DVec3,
}

impl RawMeeting {
    /// The reflected wave of mode index `m` (0 ordinary, 1 extraordinary); meaningless when
    /// its power is 0.
    #[inline]
    pub(crate) fn wave(&self, m: usize) -> Wave {
        let (k, e, _) = self.reflected[m];
        Crystal::wave_of(k, e, WaveMode::BOTH[m])
    }

    /// The [`Meeting`] with both reflected waves built (an evanescent one, whose wave vector
    /// is left zero, as a zero wave).
    #[inline]
    fn built(&self) -> Meeting {
        let wave = |m: usize| {
            if self.reflected[m].0 == DVec3::ZERO {
                Wave {
                    mode: WaveMode::BOTH[m],
                    k: DVec3::ZERO,
                    ray: DVec3::ZERO,
                    field: DVec3::ZERO,
                }
            } else {
                self.wave(m)
            }
        };
        Meeting {
            reflected: [
                (wave(0), self.reflected[0].2),
                (wave(1), self.reflected[1].2),
            ],
            exit_dir: self.exit_dir,
            exit_power: self.exit_power,
            exit: self.exit,
            axis: self.axis,
        }
    }
}

impl Crystal {
    /// [`Crystal::meet`] when the incident and both reflected modes propagate (`inc`, `refl`:
    /// wave vectors and fields from [`Crystal::real_modes`]): the same equations with the
    /// crystal's side in real arithmetic.
    #[inline]
    fn meet_real(
        &self,
        tg: &Tangent,
        inc: (DVec3, DVec3),
        refl: [(DVec3, DVec3); 2],
    ) -> Option<RawMeeting> {
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
        let reflected = [
            (refl[0].0, refl[0].1, -r[0].norm_sqr() * f_o / f_in),
            (refl[1].0, refl[1].1, -r[1].norm_sqr() * f_e / f_in),
        ];
        let (exit_dir, exit_power, exit) = if out_real {
            let t_s = C::real(i[1]) + r[0].scale(o[1]) + r[1].scale(e[1]);
            let t_p = -(C::real(i[3]) + r[0].scale(o[3]) + r[1].scale(e[3]));
            let st = jones_stokes(t_s, t_p) * (0.5 * q.re / f_in);
            ((tg.kt + tg.nu * q.re).normalize(), st.x, st)
        } else {
            (DVec3::ZERO, 0.0, DVec4::ZERO)
        };
        Some(RawMeeting {
            reflected,
            exit_dir,
            exit_power,
            exit,
            axis: tg.t2,
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
        self.meet_raw(wave, n).map(|m| m.built())
    }

    /// [`Crystal::meet`] with the reflected waves not yet built.
    pub(crate) fn meet_raw(&self, wave: &Wave, n: DVec3) -> Option<RawMeeting> {
        let nu = n;
        let tg = Tangent::new(wave.k, nu);
        if let Some(roots) = self.real_roots(&tg) {
            let mi = self.real_modes(&tg, &roots, 1.0);
            let mr = self.real_modes(&tg, &roots, -1.0);
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
                (f.k.re, f.e.re, -r[m].norm_sqr() * f.flux(nu) / f_in)
            } else {
                (DVec3::ZERO, DVec3::ZERO, 0.0)
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
        Some(RawMeeting {
            reflected,
            exit_dir,
            exit_power,
            exit,
            axis: tg.t2,
        })
    }
}
