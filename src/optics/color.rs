//! Colour: CIE 1931 2° colour matching functions, the D65 illuminant, XYZ → sRGB and CIELAB.
//!
//! The colour matching functions use the multi-lobe Gaussian fit of Wyman, Sloan & Shirley
//! (JCGT 2013), within about 1 % of the tabulated CIE 1931 functions; D65 is the CIE table at
//! 10 nm, linearly interpolated.

use glam::DVec3;

/// Shortest wavelength traced, nm.
pub const LAMBDA_MIN: f64 = 380.0;
/// Longest wavelength traced, nm.
pub const LAMBDA_MAX: f64 = 780.0;

fn lobe(l: f64, mu: f64, s1: f64, s2: f64) -> f64 {
    let s = if l < mu { s1 } else { s2 };
    let t = (l - mu) / s;
    (-0.5 * t * t).exp()
}

/// CIE 1931 2° colour matching functions (x̄, ȳ, z̄) at wavelength `l` nm.
pub fn cmf(l: f64) -> DVec3 {
    let x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7)
        - 0.065 * lobe(l, 501.1, 20.4, 26.2);
    let y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
    let z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
    DVec3::new(x, y, z)
}

/// CIE D65 relative spectral power, 380–780 nm in 10 nm steps.
const D65: [f64; 41] = [
    49.9755, 54.6482, 82.7549, 91.486, 93.4318, 86.6823, 104.865, 117.008, 117.812, 114.861,
    115.923, 108.811, 109.354, 107.802, 104.79, 107.689, 104.405, 104.046, 100.0, 96.3342, 95.788,
    88.6856, 90.0062, 89.5991, 87.6987, 83.2886, 83.6992, 80.0268, 80.2146, 82.2778, 78.2842,
    69.7213, 71.6091, 74.349, 61.604, 69.8856, 75.087, 63.5927, 46.4182, 66.8054, 63.3828,
];

/// D65 relative spectral power at `l` nm (100 at 560 nm); 0 outside 380–780 nm.
pub fn d65(l: f64) -> f64 {
    if !(LAMBDA_MIN..=LAMBDA_MAX).contains(&l) {
        return 0.0;
    }
    let x = (l - LAMBDA_MIN) / 10.0;
    let i = (x.floor() as usize).min(39);
    let f = x - i as f64;
    D65[i] * (1.0 - f) + D65[i + 1] * f
}

/// Largest value of [`d65`] (for rejection sampling).
pub const D65_MAX: f64 = 117.812;

/// `n` wavelengths at the centres of equal bands across 380–780 nm.
pub fn band_centres(n: usize) -> Vec<f64> {
    let w = (LAMBDA_MAX - LAMBDA_MIN) / n as f64;
    (0..n).map(|i| LAMBDA_MIN + (i as f64 + 0.5) * w).collect()
}

/// XYZ weight of each band of [`band_centres`]`(n)` under D65: the D65 × CMF integral over the
/// band (by 1 nm steps), scaled so the weights' Y sum to 1. A spectrum of band powers `p`
/// then has colour `Σ p_i · w_i`, and a perfect white reflector has Y = 1.
pub fn band_weights_d65(n: usize) -> Vec<DVec3> {
    let w = (LAMBDA_MAX - LAMBDA_MIN) / n as f64;
    let mut out: Vec<DVec3> = (0..n)
        .map(|i| {
            let a = LAMBDA_MIN + i as f64 * w;
            let steps = (w.ceil() as usize).max(1) * 4;
            let h = w / steps as f64;
            (0..steps)
                .map(|k| a + (k as f64 + 0.5) * h)
                .map(|l| d65(l) * cmf(l) * h)
                .sum()
        })
        .collect();
    let y: f64 = out.iter().map(|v| v.y).sum();
    for v in &mut out {
        *v /= y;
    }
    out
}

/// A band of [`band_weights_d65`] whose X, Y and Z weights are all below this share of the
/// white's is *faint* (with 8 bands, 730–780 nm: about 2e-5 of the white in X; with 6,
/// 713–780 nm: 1e-4).
pub const FAINT_BAND: f64 = 1e-3;

/// The bands of [`band_centres`]`(n)` worth tracing for a spectral image, each with its
/// weight: a faint band (every XYZ weight below `faint` of the white's) is not traced but
/// merged into the nearest band that is not faint (by index; the lower one on a tie), which
/// takes its weight, as if its image were that band's. The merged weights still sum to the
/// white, so a grey pixel (every band alike) stays grey. In band order; every band is kept
/// when `faint` is 0.
pub fn traced_bands(n: usize, faint: f64) -> Vec<(f64, DVec3)> {
    let centres = band_centres(n);
    let weights = band_weights_d65(n);
    let white: DVec3 = weights.iter().copied().sum();
    let bright: Vec<usize> = (0..weights.len())
        .filter(|&i| (weights[i] / white).max_element() >= faint)
        .collect();
    if bright.is_empty() {
        return centres.into_iter().zip(weights).collect();
    }
    let mut out: Vec<(f64, DVec3)> = bright.iter().map(|&i| (centres[i], DVec3::ZERO)).collect();
    for (i, w) in weights.iter().enumerate() {
        let k = (0..bright.len())
            .min_by_key(|&k| bright[k].abs_diff(i))
            .unwrap_or(0);
        out[k].1 += *w;
    }
    out
}

/// XYZ of the D65 white with Y = 1, as integrated with [`cmf`].
pub fn d65_white() -> DVec3 {
    band_weights_d65(400).iter().copied().sum()
}

/// Chromaticity (x, y) of an XYZ colour.
pub fn chromaticity(xyz: DVec3) -> (f64, f64) {
    let s = xyz.x + xyz.y + xyz.z;
    (xyz.x / s, xyz.y / s)
}

/// Linear sRGB from XYZ (D65 white, IEC 61966-2-1).
pub fn xyz_to_linear_srgb(c: DVec3) -> DVec3 {
    DVec3::new(
        3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
        -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
        0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z,
    )
}

/// sRGB transfer function (linear → encoded), clamped to [0, 1].
pub fn srgb_encode(v: f64) -> f64 {
    let v = v.clamp(0.0, 1.0);
    if v <= 0.0031308 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// 8-bit sRGB from XYZ (clipped).
pub fn xyz_to_srgb8(c: DVec3) -> [u8; 3] {
    let l = xyz_to_linear_srgb(c);
    [l.x, l.y, l.z].map(|v| (srgb_encode(v) * 255.0).round() as u8)
}

/// CIELAB (L*, a*, b*) of `c` relative to the white `white`.
pub fn xyz_to_lab(c: DVec3, white: DVec3) -> DVec3 {
    fn f(t: f64) -> f64 {
        const D: f64 = 6.0 / 29.0;
        if t > D * D * D {
            t.cbrt()
        } else {
            t / (3.0 * D * D) + 4.0 / 29.0
        }
    }
    let (fx, fy, fz) = (f(c.x / white.x), f(c.y / white.y), f(c.z / white.z));
    DVec3::new(116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz))
}

/// CIELAB chroma C*ab = sqrt(a*² + b*²).
pub fn chroma(lab: DVec3) -> f64 {
    (lab.y * lab.y + lab.z * lab.z).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Faint bands are merged into their nearest traced neighbour: the weights still sum to
    /// the white, and only bands far out in the red (or violet) go.
    #[test]
    fn faint_bands_merge_into_their_neighbours() {
        for n in [1, 3, 6, 8, 16, 64] {
            let all = band_weights_d65(n);
            let white: DVec3 = all.iter().copied().sum();
            let kept = traced_bands(n, FAINT_BAND);
            let sum: DVec3 = kept.iter().map(|b| b.1).sum();
            assert!(
                (sum - white).abs().max_element() < 1e-12,
                "{n}: {sum} against {white}"
            );
            // Every band kept is bright; every band dropped is faint.
            let centres = band_centres(n);
            for (i, (c, w)) in centres.iter().zip(&all).enumerate() {
                let bright = (*w / white).max_element() >= FAINT_BAND;
                let traced = kept.iter().any(|k| k.0 == *c);
                assert_eq!(bright, traced, "{n} bands, band {i} at {c} nm: {w}");
            }
            // Nothing is dropped with a threshold of 0.
            assert_eq!(traced_bands(n, 0.0).len(), n);
        }
        // 8 bands: only 730–780 nm (≈2e-5 of the white) is faint, and 680–730 nm takes it.
        let kept = traced_bands(8, FAINT_BAND);
        let all = band_weights_d65(8);
        assert_eq!(kept.len(), 7);
        assert!((all[7] / all.iter().copied().sum::<DVec3>()).max_element() < 1e-4);
        assert_eq!(kept[6].1, all[6] + all[7]);
        assert_eq!(kept[..6].iter().map(|b| b.1).collect::<Vec<_>>(), all[..6]);
    }

    #[test]
    fn d65_white_point() {
        let (x, y) = chromaticity(d65_white());
        assert!(
            (x - 0.3127).abs() < 0.003 && (y - 0.3290).abs() < 0.003,
            "({x}, {y})"
        );
        let rgb = xyz_to_linear_srgb(d65_white());
        for v in rgb.to_array() {
            assert!((v - 1.0).abs() < 0.03, "{rgb:?}");
        }
        assert!(chroma(xyz_to_lab(d65_white(), d65_white())) < 1e-9);
    }

    #[test]
    fn cmf_peaks_where_cie_tables_do() {
        let argmax = |f: &dyn Fn(f64) -> f64| {
            (380i32..=780)
                .max_by(|a, b| f(*a as f64).total_cmp(&f(*b as f64)))
                .unwrap()
        };
        assert!((argmax(&|l| cmf(l).y) - 555).abs() <= 3);
        assert!((argmax(&|l| cmf(l).x) - 599).abs() <= 3);
        assert!((argmax(&|l| cmf(l).z) - 446).abs() <= 4);
        assert!((cmf(555.0).y - 1.0).abs() < 0.02);
    }

    #[test]
    fn monochromatic_light_is_saturated() {
        let w = d65_white();
        let red = cmf(650.0) / cmf(650.0).y * 0.2;
        assert!(chroma(xyz_to_lab(red, w)) > 60.0);
        let band = band_weights_d65(8);
        assert!((band.iter().map(|v| v.y).sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
