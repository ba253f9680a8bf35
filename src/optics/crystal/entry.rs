//! Light arriving from outside at a facet: the external reflection and the two refracted
//! waves ([`Crystal::enter`]).

use super::boundary::{amplitudes, coherency, isotropic_modes, quad, Tangent};
use super::complex::C;
use super::uniaxial::Crystal;
use super::wave::{Wave, WaveMode};
use crate::optics::polarization::{rotate_stokes, Stokes};
use glam::{DVec3, DVec4};

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

impl Crystal {
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
}
