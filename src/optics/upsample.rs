//! Light's colour as a spectrum: linear sRGB radiance (an environment map's texel, a studio
//! light's tint, the ground's albedo) turned into per-wavelength values for spectral pictures.
//!
//! The upsampling is the body colour's (Jakob & Hanika 2019, [`fit_sigmoid`]): each sRGB
//! primary's colour is fitted once by a smooth sigmoid-polynomial spectrum `T_c(λ)`, and the
//! three are normalised to add up to 1 at every wavelength, `B_c(λ) = T_c(λ) / Σ T(λ)`. An RGB
//! value is the spectrum `Σ_c rgb_c B_c(λ)`: linear in RGB (so radiance of any brightness,
//! an HDR map's sun included, upsamples by the same three curves, and a filtered or summed
//! radiance upsamples to the filtered or summed spectra), and grey stays exactly flat: equal
//! R, G and B give the same value at every wavelength, so a uniform white environment is 1 in
//! every band (the white furnace). The primaries' own colours are reproduced only as well as
//! smooth spectra can: [`primary_errors`] gives their ΔE₀₀.

use super::body_colour::sigmoid_poly;
use super::color::{linear_srgb_to_xyz, xyz_to_lab, LAMBDA_MAX, LAMBDA_MIN};
use super::fit_sigmoid;
use glam::DVec3;
use std::sync::OnceLock;

/// The sigmoid coefficients of the three primaries and their fits' ΔE₀₀.
fn fits() -> &'static [([f64; 3], f64); 3] {
    static FITS: OnceLock<[([f64; 3], f64); 3]> = OnceLock::new();
    FITS.get_or_init(|| {
        let white = super::color::d65_white();
        [DVec3::X, DVec3::Y, DVec3::Z].map(|p| {
            let xyz = linear_srgb_to_xyz(p) * (white.y / linear_srgb_to_xyz(DVec3::ONE).y);
            fit_sigmoid(xyz_to_lab(xyz, white))
        })
    })
}

/// The weights `[B_r, B_g, B_b]` of linear sRGB's red, green and blue at `nm` (they add up
/// to 1). Outside 380–780 nm the end values.
pub fn rgb_weights(nm: f64) -> [f64; 3] {
    let nm = nm.clamp(LAMBDA_MIN, LAMBDA_MAX);
    let t = fits().map(|(c, _)| sigmoid_poly(c, nm).max(1e-12));
    let s = t[0] + t[1] + t[2];
    t.map(|v| v / s)
}

/// The spectral value at `nm` of linear sRGB radiance `rgb`: `Σ rgb_c B_c(nm)`.
#[inline]
pub fn rgb_at(rgb: [f64; 3], w: [f64; 3]) -> f64 {
    rgb[0] * w[0] + rgb[1] * w[1] + rgb[2] * w[2]
}

/// ΔE₀₀ between each sRGB primary (red, green, blue) and its sigmoid fit (before the three
/// are normalised): how far a fully saturated primary is from a smooth spectrum.
pub fn primary_errors() -> [f64; 3] {
    fits().map(|(_, de)| de)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::color::{band_centres, band_weights_d65, xyz_to_linear_srgb};

    /// Grey is flat; the weights are a smooth partition of unity; the band colours of an RGB
    /// light come back near that RGB (8 bands, as pictures use).
    #[test]
    fn grey_is_flat_and_colours_come_back() {
        for k in 0..=400 {
            let w = rgb_weights(380.0 + k as f64);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            assert!(w.iter().all(|&x| (0.0..=1.0).contains(&x)));
            assert!((rgb_at([2.5, 2.5, 2.5], w) - 2.5).abs() < 1e-12);
        }
        // Blue weighs most at 450 nm, green at 540, red at 650.
        let argmax = |w: [f64; 3]| (0..3).max_by(|&a, &b| w[a].total_cmp(&w[b])).unwrap();
        assert_eq!(argmax(rgb_weights(450.0)), 2);
        assert_eq!(argmax(rgb_weights(540.0)), 1);
        assert_eq!(argmax(rgb_weights(650.0)), 0);
        // A pastel colour's spectrum, integrated over fine bands, comes back within a few
        // hundredths in linear sRGB.
        let n = 40;
        let (centres, weights) = (band_centres(n), band_weights_d65(n));
        for rgb in [[0.8, 0.5, 0.3], [0.3, 0.6, 0.9], [0.5, 0.8, 0.4]] {
            let xyz: DVec3 = centres
                .iter()
                .zip(&weights)
                .map(|(&l, &w)| w * rgb_at(rgb, rgb_weights(l)))
                .sum();
            let back = xyz_to_linear_srgb(xyz);
            for c in 0..3 {
                assert!((back[c] - rgb[c]).abs() < 0.08, "{rgb:?} → {back}");
            }
        }
    }
}
