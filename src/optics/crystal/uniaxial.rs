//! [`Crystal`]: a uniaxial crystal at one wavelength, its extraordinary index along a
//! direction, a wave along a given normal and the absorption of a wave (pleochroism).

use super::boundary::Tangent;
use super::wave::{Wave, WaveMode};
use glam::DVec3;

/// A uniaxial crystal at one wavelength, in the stone's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crystal {
    /// Ordinary index n_o (ω).
    pub n_o: f64,
    /// Extraordinary index n_e (ε).
    pub n_e: f64,
    /// Optic axis ĉ (unit).
    pub axis: DVec3,
    pub(super) eps_o: f64,
    pub(super) eps_e: f64,
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
}
