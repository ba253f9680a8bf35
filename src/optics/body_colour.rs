//! Body colour: a stone's absorption coefficient α(λ) per millimetre of path over 380–780 nm,
//! the light it lets through a path of L mm (Beer–Lambert, T = exp(−α·L)), and the colour of
//! white D65 light seen through that path (CIE XYZ, CIELAB, sRGB).
//!
//! A [`BodyColour`] is sampled every [`STEP_NM`] nm and linearly interpolated; its `density`
//! multiplies α (`--colour-density`: 0.5 is paler, 2 is darker). The colour seen through L mm
//! is the D65-weighted transmittance Σ w(λ)·T(λ) over 1 nm bands, so a path with no
//! absorption is the D65 white (Y = 1, CIELAB 100, 0, 0); surface reflections are not part
//! of it (it is the internal transmittance of the body only).
//!
//! Named coloured varieties with published spectra are in `varieties.rs`; a user's colour
//! becomes a spectrum by [`BodyColour::from_colour`] (the sigmoid-polynomial spectral
//! upsampling of W. Jakob and J. Hanika, "A low-dimensional function space for efficient
//! spectral upsampling", Computer Graphics Forum 38(2), 147–155 (2019)).

use super::color::{
    band_weights_d65, d65_white, delta_e2000, lab_to_xyz, linear_srgb_to_xyz, srgb_decode,
    xyz_to_lab, xyz_to_srgb8, LAMBDA_MAX, LAMBDA_MIN,
};
use crate::error::{shown, Error, Result};
use glam::DVec3;
use std::sync::OnceLock;

/// Spacing of a body colour's samples, nm.
pub const STEP_NM: f64 = 10.0;
/// Number of samples, 380–780 nm.
pub const SAMPLES: usize = 41;

/// The path length a user's colour is seen through when `@…mm` is not given.
pub const DEFAULT_PATH_MM: f64 = 10.0;

/// A stone's body colour: absorption per millimetre of path, 380–780 nm.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyColour {
    /// What it is: a variety's name (`ruby`) or the user's colour as given.
    pub name: String,
    /// α at 380, 390, …, 780 nm, per mm, before `density`.
    pub alpha_per_mm: Vec<f64>,
    /// Multiplies α (1 = as published or as fitted).
    pub density: f64,
    /// Where the spectrum comes from (sample, thickness, publication) or how it was made.
    pub source: String,
}

/// The 1 nm bands the colour integrals use: (centre, D65 × CMF weight with Σ Y = 1).
fn fine_bands() -> &'static [(f64, DVec3)] {
    static BANDS: OnceLock<Vec<(f64, DVec3)>> = OnceLock::new();
    BANDS.get_or_init(|| {
        let n = (LAMBDA_MAX - LAMBDA_MIN) as usize;
        band_weights_d65(n)
            .into_iter()
            .enumerate()
            .map(|(i, w)| (LAMBDA_MIN + i as f64 + 0.5, w))
            .collect()
    })
}

/// The D65 white the colours are relative to (as integrated by [`fine_bands`]).
fn white() -> DVec3 {
    static WHITE: OnceLock<DVec3> = OnceLock::new();
    *WHITE.get_or_init(d65_white)
}

impl BodyColour {
    /// A body colour from α sampled at 380, 390, …, 780 nm (per mm). Errors name `what` when
    /// there are not [`SAMPLES`] values or one is negative or not finite.
    pub fn new(name: &str, alpha_per_mm: Vec<f64>, source: &str) -> Result<BodyColour> {
        if alpha_per_mm.len() != SAMPLES {
            return Err(Error::invalid(
                name,
                format!(
                    "an absorption spectrum needs {SAMPLES} values (380–780 nm every {STEP_NM} nm), not {}",
                    alpha_per_mm.len()
                ),
            ));
        }
        if let Some(bad) = alpha_per_mm.iter().find(|a| !(a.is_finite() && **a >= 0.0)) {
            return Err(Error::invalid(
                name,
                format!("absorption {bad} per mm is not allowed; give finite values ≥ 0"),
            ));
        }
        Ok(BodyColour {
            name: name.into(),
            alpha_per_mm,
            density: 1.0,
            source: source.into(),
        })
    }

    /// The same spectrum with `density` times the absorption (a darker or paler stone of the
    /// same hue family).
    pub fn with_density(mut self, density: f64) -> BodyColour {
        self.density *= density;
        self
    }

    /// Absorption coefficient at `nm`, per mm (density applied); the end values outside
    /// 380–780 nm.
    pub fn alpha(&self, nm: f64) -> f64 {
        let x = ((nm - LAMBDA_MIN) / STEP_NM).clamp(0.0, (SAMPLES - 1) as f64);
        let i = (x.floor() as usize).min(SAMPLES - 2);
        let f = x - i as f64;
        self.density * (self.alpha_per_mm[i] * (1.0 - f) + self.alpha_per_mm[i + 1] * f)
    }

    /// Internal transmittance exp(−α·L) through `path_mm` at `nm`.
    pub fn transmittance(&self, nm: f64, path_mm: f64) -> f64 {
        (-self.alpha(nm) * path_mm).exp()
    }

    /// CIE XYZ of D65 light after `path_mm` (the white has Y = 1).
    pub fn xyz_through(&self, path_mm: f64) -> DVec3 {
        fine_bands()
            .iter()
            .map(|(l, w)| *w * self.transmittance(*l, path_mm))
            .sum()
    }

    /// CIELAB (relative to D65) of the light after `path_mm`.
    pub fn lab_through(&self, path_mm: f64) -> DVec3 {
        xyz_to_lab(self.xyz_through(path_mm), white())
    }

    /// 8-bit sRGB of the light after `path_mm` (clipped).
    pub fn srgb8_through(&self, path_mm: f64) -> [u8; 3] {
        xyz_to_srgb8(self.xyz_through(path_mm))
    }

    /// `#rrggbb` of the light after `path_mm`.
    pub fn hex_through(&self, path_mm: f64) -> String {
        let [r, g, b] = self.srgb8_through(path_mm);
        format!("#{r:02x}{g:02x}{b:02x}")
    }

    /// The smooth spectrum whose colour through `colour.path_mm` is `colour` (the
    /// sigmoid-polynomial upsampling of Jakob & Hanika 2019, see [`fit_sigmoid`]), as α per
    /// mm = −ln T(λ) / path. Errors (naming `field`) when no transmission spectrum of that
    /// form comes within ΔE₀₀ [`FIT_TOLERANCE`] of the colour (too bright for its
    /// saturation: a filter cannot be brighter than white).
    pub fn from_colour(colour: &UserColour, field: &str) -> Result<BodyColour> {
        let (c, de) = fit_sigmoid(colour.lab);
        let alpha: Vec<f64> = sigmoid_alpha(c)
            .into_iter()
            .map(|a| a / colour.path_mm)
            .collect();
        let out = BodyColour {
            name: colour.text.clone(),
            alpha_per_mm: alpha,
            density: 1.0,
            source: format!(
                "the user's colour {} seen through {} mm under D65, upsampled to a smooth spectrum (W. Jakob, J. Hanika, Comput. Graph. Forum 38(2), 147–155 (2019): T(λ) = S(c0 t² + c1 t + c2)); ΔE2000 of the fit {de:.2}",
                colour.text, colour.path_mm
            ),
        };
        let got = delta_e2000(out.lab_through(colour.path_mm), colour.lab);
        if got > FIT_TOLERANCE {
            return Err(Error::invalid(
                field,
                format!(
                    "`{}` cannot be the colour of a stone seen through {} mm: the nearest smooth transmission spectrum is ΔE2000 {got:.1} away (too light for its saturation); give a darker or less saturated colour",
                    colour.text, colour.path_mm
                ),
            ));
        }
        Ok(out)
    }
}

/// The names under which a colour choice reaches [`BodyColour::choose`] (a flag pair
/// `--colour`/`--colour-density` or a config's `score.colour`/`score.colour_density`), for
/// its error messages.
#[derive(Clone, Copy, Debug)]
pub struct ColourFields<'a> {
    /// Where the colour was given.
    pub colour: &'a str,
    /// Where the density was given.
    pub density: &'a str,
}

/// The largest `--colour-density` accepted.
pub const DENSITY_MAX: f64 = 100.0;

impl BodyColour {
    /// The one chooser of a body colour, for the command line and the config: the user's
    /// colour (`user`, parsed by [`UserColour::parse`] and upsampled) if given, else the
    /// material's own (`own`: a variety's published spectrum), times `density` if given.
    /// Errors name `fields.colour` or `fields.density`: a malformed or impossible colour, a
    /// density outside (0, [`DENSITY_MAX`]], or a density with no colour to scale.
    pub fn choose(
        own: Option<&BodyColour>,
        user: Option<&str>,
        density: Option<f64>,
        fields: ColourFields<'_>,
    ) -> Result<Option<BodyColour>> {
        let base = match user {
            Some(text) => Some(BodyColour::from_colour(
                &UserColour::parse(text, fields.colour)?,
                fields.colour,
            )?),
            None => own.cloned(),
        };
        match density {
            None => Ok(base),
            Some(d) if !(d > 0.0 && d <= DENSITY_MAX) => Err(Error::invalid(
                fields.density,
                format!("{} is out of range; allowed (0, {DENSITY_MAX}] (a factor on the absorption: 0.5 paler, 2 darker)", shown(d)),
            )),
            Some(d) => match base {
                Some(c) => Ok(Some(c.with_density(d))),
                None => Err(Error::invalid(
                    fields.density,
                    format!(
                        "there is no colour to scale: give {} or a coloured variety with a published spectrum (facetlab materials)",
                        fields.colour
                    ),
                )),
            },
        }
    }
}

impl BodyColour {
    /// One line for stderr naming the colour, its source, the stone's width and the colour
    /// seen through that width (a picture drawn in the colour prints this).
    pub fn note(&self, width_mm: f64) -> String {
        let width_mm = (width_mm * 100.0).round() / 100.0;
        let density = if self.density == 1.0 {
            String::new()
        } else {
            format!(" × density {}", self.density)
        };
        format!(
            "colour: {}{density} ({}); stone width {width_mm} mm, seen through {width_mm} mm: {}",
            self.name,
            self.source,
            self.hex_through(width_mm)
        )
    }

    /// [`BodyColour::note`], and that this trace does not use it (the photon tracer's
    /// `trace` without the absorption model `colour`); the note names the setting
    /// ([`crate::error::setting`]) for each face to spell.
    pub fn not_traced_note(&self, width_mm: f64) -> String {
        format!(
            "{}; body colour is not yet traced here (give {} colour): the colourless stone's",
            self.note(width_mm),
            crate::error::setting("absorption model")
        )
    }
}

/// Largest ΔE₀₀ between a user's colour and its upsampled spectrum's colour that is accepted.
pub const FIT_TOLERANCE: f64 = 1.0;

/// Jakob & Hanika's sigmoid S(x) = ½ + x / (2 √(1 + x²)).
fn sigmoid(x: f64) -> f64 {
    0.5 + x / (2.0 * (1.0 + x * x).sqrt())
}

/// T(λ) = S(c0 t² + c1 t + c2) with t = (λ − 380) / 400 in [0, 1] (the normalised
/// wavelength keeps the three coefficients of one scale).
pub(super) fn sigmoid_poly(c: [f64; 3], nm: f64) -> f64 {
    let t = (nm - LAMBDA_MIN) / (LAMBDA_MAX - LAMBDA_MIN);
    sigmoid((c[0] * t + c[1]) * t + c[2])
}

/// α per unit path of T(λ) = S(c0 t² + c1 t + c2) at the 10 nm samples: −ln T.
fn sigmoid_alpha(c: [f64; 3]) -> Vec<f64> {
    (0..SAMPLES)
        .map(|i| {
            (-sigmoid_poly(c, LAMBDA_MIN + i as f64 * STEP_NM)
                .max(1e-300)
                .ln())
            .max(0.0)
        })
        .collect()
}

/// CIELAB of D65 light through T(λ) = S(c0 t² + c1 t + c2), sampled and interpolated like a
/// stored [`BodyColour`] (so the fit is exact for what is stored).
fn lab_of(c: [f64; 3]) -> DVec3 {
    BodyColour {
        name: String::new(),
        alpha_per_mm: sigmoid_alpha(c),
        density: 1.0,
        source: String::new(),
    }
    .lab_through(1.0)
}

/// Fit the coefficients of T(λ) = S(c0 t² + c1 t + c2) so that D65 light through T has the
/// CIELAB colour `target`, by Gauss–Newton on the CIELAB residual (Jakob & Hanika 2019 §4,
/// who fit reflectances the same way), damped by step halving, started from T = ½ and walked
/// to the target in steps (their continuation) so that dark and saturated colours converge.
/// Returns the coefficients and the ΔE₀₀ left.
pub fn fit_sigmoid(target: DVec3) -> ([f64; 3], f64) {
    let mut c = [0.0; 3];
    let start = lab_of(c);
    const STEPS: usize = 16;
    for k in 1..=STEPS {
        let goal = start + (target - start) * (k as f64 / STEPS as f64);
        let iters = if k == STEPS { 60 } else { 12 };
        c = gauss_newton(c, goal, iters);
    }
    let de = delta_e2000(lab_of(c), target);
    (c, de)
}

/// Damped Gauss–Newton on r(c) = Lab(c) − goal (three equations, three unknowns, a
/// central-difference Jacobian).
fn gauss_newton(mut c: [f64; 3], goal: DVec3, iters: usize) -> [f64; 3] {
    let cost = |c: [f64; 3]| (lab_of(c) - goal).length_squared();
    let mut f = cost(c);
    for _ in 0..iters {
        if f < 1e-14 {
            break;
        }
        let r = lab_of(c) - goal;
        let h = 1e-4;
        let mut cols = [DVec3::ZERO; 3];
        for (j, col) in cols.iter_mut().enumerate() {
            let (mut p, mut m) = (c, c);
            p[j] += h;
            m[j] -= h;
            *col = (lab_of(p) - lab_of(m)) / (2.0 * h);
        }
        let jac = glam::DMat3::from_cols(cols[0], cols[1], cols[2]);
        if jac.determinant().abs() < 1e-300 {
            break;
        }
        let step = jac.inverse() * r;
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..30 {
            let trial = [
                c[0] - scale * step.x,
                c[1] - scale * step.y,
                c[2] - scale * step.z,
            ];
            let ft = cost(trial);
            if ft.is_finite() && ft < f {
                c = trial;
                f = ft;
                improved = true;
                break;
            }
            scale *= 0.5;
        }
        if !improved {
            break;
        }
    }
    c
}

/// A colour the user gave (`--colour`, `score.colour`): what it looks like through a path.
#[derive(Clone, Debug, PartialEq)]
pub struct UserColour {
    /// The text as given (trimmed).
    pub text: String,
    /// Its CIELAB colour (D65).
    pub lab: DVec3,
    /// The path it is seen through, mm.
    pub path_mm: f64,
}

/// The forms a user's colour may take, for error messages.
pub const COLOUR_FORMS: &str =
    "give #rrggbb or lab(L,a,b), optionally @Nmm (the path it is seen through under D65; default 10mm), e.g. \"#7a3fa0@10mm\" or \"lab(40,30,-40)@10mm\"";

impl UserColour {
    /// Parse `#rrggbb[@Lmm]`, `#rgb[@Lmm]` or `lab(L,a,b)[@Lmm]`. An sRGB colour is taken
    /// to CIELAB relative to sRGB's white and that CIELAB is the colour meant (so `#ffffff`
    /// is the D65 white, a clear stone). Errors name `field` and the forms allowed.
    pub fn parse(text: &str, field: &str) -> Result<UserColour> {
        let whole = text.trim();
        let bad = |why: &str| Error::invalid(field, format!("`{whole}` {why}; {COLOUR_FORMS}"));
        let (colour, path) = match whole.rsplit_once('@') {
            Some((c, p)) => (c.trim(), Some(p.trim())),
            None => (whole, None),
        };
        let path_mm = match path {
            None => DEFAULT_PATH_MM,
            Some(p) => {
                let num = p.strip_suffix("mm").unwrap_or(p).trim();
                match num.parse::<f64>() {
                    Ok(v) if v.is_finite() && v > 0.0 && v <= 1000.0 => v,
                    _ => return Err(bad("has no path in (0, 1000] mm after @")),
                }
            }
        };
        let lower = colour.to_ascii_lowercase();
        let lab = if let Some(hex) = lower.strip_prefix('#') {
            let digits: Vec<u32> = hex.chars().filter_map(|c| c.to_digit(16)).collect();
            if digits.len() != hex.chars().count() || !(digits.len() == 6 || digits.len() == 3) {
                return Err(bad("is not a hex colour"));
            }
            let rgb: Vec<f64> = if digits.len() == 6 {
                digits
                    .chunks(2)
                    .map(|p| (p[0] * 16 + p[1]) as f64 / 255.0)
                    .collect()
            } else {
                digits.iter().map(|d| (d * 17) as f64 / 255.0).collect()
            };
            let lin = DVec3::new(
                srgb_decode(rgb[0]),
                srgb_decode(rgb[1]),
                srgb_decode(rgb[2]),
            );
            xyz_to_lab(linear_srgb_to_xyz(lin), linear_srgb_to_xyz(DVec3::ONE))
        } else if let Some(inner) = lower.strip_prefix("lab(").and_then(|s| s.strip_suffix(')')) {
            let v: Vec<f64> = inner
                .split(',')
                .map(|s| s.trim().parse::<f64>())
                .collect::<std::result::Result<_, _>>()
                .map_err(|_| bad("has a value that is not a number"))?;
            if v.len() != 3 || v.iter().any(|x| !x.is_finite()) {
                return Err(bad("needs three numbers L, a, b"));
            }
            if !(0.0..=100.0).contains(&v[0]) {
                return Err(bad("has L outside [0, 100]"));
            }
            DVec3::new(v[0], v[1], v[2])
        } else {
            return Err(bad("is not a colour"));
        };
        if lab.x <= 0.5 {
            return Err(bad("is black: no light would pass"));
        }
        Ok(UserColour {
            text: whole.to_string(),
            lab,
            path_mm,
        })
    }

    /// XYZ of the colour relative to the D65 white the body colours use.
    pub fn xyz(&self) -> DVec3 {
        lab_to_xyz(self.lab, white())
    }
}

/// The stone's size for body colour, as given: a width W, or a length L (W = L / (L/W)), or
/// both (which must agree with the design's L/W within 1 %).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StoneSize {
    /// The width W in mm (a round's diameter).
    Width(f64),
    /// The length L in mm; the width follows from the design's L/W.
    Length(f64),
    /// Length and width in mm.
    LengthWidth(f64, f64),
}

impl Default for StoneSize {
    fn default() -> Self {
        StoneSize::Width(Self::DEFAULT_WIDTH_MM)
    }
}

impl StoneSize {
    /// The width of a stone whose size is not given, mm.
    pub const DEFAULT_WIDTH_MM: f64 = 6.5;

    /// A stone's sizes (a width, a length, a diameter) are below this, mm; every face checks
    /// them by [`StoneSize::check_mm`] (a length by [`StoneSize::parse_length`]).
    pub const MAX_MM: f64 = 1000.0;

    /// A stone's width `w` in (0, [`StoneSize::MAX_MM`]) mm; the one-line error names `field`.
    pub fn check_mm(w: f64, field: &str) -> Result<f64> {
        if w.is_finite() && w > 0.0 && w < StoneSize::MAX_MM {
            Ok(w)
        } else {
            Err(Error::invalid(
                field,
                format!(
                    "{} is not allowed; give a width in (0, {}) mm",
                    shown(w),
                    StoneSize::MAX_MM
                ),
            ))
        }
    }

    /// `L` or `LxW` in mm (`--size-mm`); errors name `field`.
    pub fn parse_length(text: &str, field: &str) -> Result<StoneSize> {
        let bad = |why: String| Error::invalid(field, format!("`{text}` {why}"));
        let num = |t: &str| -> Result<f64> {
            match t.trim().parse::<f64>() {
                Ok(v) if v.is_finite() && v > 0.0 && v < StoneSize::MAX_MM => Ok(v),
                _ => Err(bad(format!(
                    "is not allowed; give L or LxW in millimetres, each in (0, {}), e.g. 10x5",
                    StoneSize::MAX_MM
                ))),
            }
        };
        let lower = text.to_ascii_lowercase();
        match lower.split_once(['x', '×']) {
            None => Ok(StoneSize::Length(num(&lower)?)),
            Some((l, w)) => Ok(StoneSize::LengthWidth(num(l)?, num(w)?)),
        }
    }

    /// A width in mm (`--diameter-mm`); errors name `field`.
    pub fn width(w: f64, field: &str) -> Result<StoneSize> {
        StoneSize::check_mm(w, field).map(StoneSize::Width)
    }

    /// The width W in mm of a design whose length/width is `l_w`; errors name `field` when
    /// L×W disagrees with the design's L/W by more than 1 %.
    pub fn width_mm(&self, l_w: f64, field: &str) -> Result<f64> {
        match *self {
            StoneSize::Width(w) => Ok(w),
            StoneSize::Length(l) => Ok(l / l_w),
            StoneSize::LengthWidth(l, w) => {
                if ((l / w) / l_w - 1.0).abs() > 0.01 {
                    return Err(Error::invalid(
                        field,
                        format!(
                            "`{l}x{w}` has L/W {:.3}, but the design's is {l_w:.3}; give L alone or LxW with that ratio",
                            l / w
                        ),
                    ));
                }
                Ok(w)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flat(a: f64) -> BodyColour {
        BodyColour::new("flat", vec![a; SAMPLES], "test").unwrap()
    }

    /// A grey filter: every wavelength alike, so the colour is the white times exp(−αL) and
    /// Beer–Lambert composes (T over 2L = T²); density multiplies α.
    #[test]
    fn a_flat_spectrum_is_grey_and_beer_lambert_composes() {
        let c = flat(0.1);
        let w = white();
        let xyz = c.xyz_through(5.0);
        assert!((xyz - w * (-0.5f64).exp()).abs().max_element() < 1e-12);
        let lab = c.lab_through(5.0);
        assert!(lab.y.abs() < 1e-9 && lab.z.abs() < 1e-9, "{lab}");
        assert!((c.transmittance(555.0, 6.0) - c.transmittance(555.0, 3.0).powi(2)).abs() < 1e-15);
        let d = flat(0.1).with_density(3.0);
        assert!((d.alpha(500.0) - 0.3).abs() < 1e-15);
        assert_eq!(flat(0.0).lab_through(100.0), DVec3::new(100.0, 0.0, 0.0));
        assert!(BodyColour::new("x", vec![0.1; 40], "").is_err());
        assert!(BodyColour::new("x", vec![-0.1; SAMPLES], "").is_err());
    }

    #[test]
    fn alpha_interpolates_between_samples() {
        let mut a = vec![0.0; SAMPLES];
        a[1] = 1.0; // 390 nm
        let c = BodyColour::new("spike", a, "").unwrap();
        assert_eq!(c.alpha(390.0), 1.0);
        assert!((c.alpha(385.0) - 0.5).abs() < 1e-15);
        assert!((c.alpha(397.5) - 0.25).abs() < 1e-15);
        assert_eq!(c.alpha(300.0), 0.0);
        assert_eq!(c.alpha(900.0), 0.0);
    }

    /// Issue 25's check 4: a user's colour, upsampled, is seen through its path as the colour
    /// given, within ΔE₀₀ 1; and through half or twice the path it is lighter or darker.
    #[test]
    fn user_colours_round_trip_within_one_delta_e() {
        for text in [
            "#7a3fa0@10mm",
            "#7a3fa0",
            "#2e8b57@10mm",
            "#c8102e@5mm",
            "#1f4e9c@8mm",
            "#f2c14e@10mm",
            "#a0d8ef@20mm",
            "#303030@10mm",
            "#ffffff@3mm",
            "lab(40,30,-40)@10mm",
            "lab(85,-5,20)@6.5mm",
            "lab(25,40,20)@10mm",
        ] {
            let u = UserColour::parse(text, "colour").unwrap();
            let c = BodyColour::from_colour(&u, "colour").unwrap();
            let got = c.lab_through(u.path_mm);
            let de = delta_e2000(got, u.lab);
            assert!(de <= FIT_TOLERANCE, "{text}: {got} vs {} (ΔE {de})", u.lab);
            assert!(c.alpha_per_mm.iter().all(|a| a.is_finite() && *a >= 0.0));
            if u.lab.x < 99.0 {
                assert!(c.lab_through(u.path_mm / 2.0).x > got.x, "{text}");
                assert!(c.lab_through(u.path_mm * 2.0).x < got.x, "{text}");
            }
        }
        // White is a clear stone.
        let u = UserColour::parse("#fff", "colour").unwrap();
        assert!(BodyColour::from_colour(&u, "colour")
            .unwrap()
            .alpha_per_mm
            .iter()
            .all(|a| *a < 1e-3));
    }

    #[test]
    fn impossible_and_malformed_colours_are_one_line_errors() {
        // Light and saturated: no filter passes that much light of one hue.
        let u = UserColour::parse("lab(95,80,80)", "colour").unwrap();
        let e = BodyColour::from_colour(&u, "colour")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("colour: ") && e.contains("cannot be"), "{e}");
        for bad in [
            "",
            "#12345",
            "#gggggg",
            "red",
            "lab(1,2)",
            "lab(120,0,0)",
            "lab(a,b,c)",
            "#7a3fa0@",
            "#7a3fa0@-3mm",
            "#7a3fa0@0mm",
            "#000000",
        ] {
            let e = UserColour::parse(bad, "score.colour")
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("score.colour: ") && e.contains("lab(L,a,b)") && !e.contains('\n'),
                "{bad}: {e}"
            );
        }
        let u = UserColour::parse(" #7A3FA0 @ 12.5 mm ", "colour").unwrap();
        assert_eq!(u.path_mm, 12.5);
        assert_eq!(
            UserColour::parse("#abc", "colour").unwrap().lab,
            UserColour::parse("#aabbcc", "colour").unwrap().lab
        );
    }

    #[test]
    fn stone_sizes_resolve_to_a_width() {
        assert_eq!(StoneSize::default().width_mm(2.0, "f").unwrap(), 6.5);
        assert_eq!(
            StoneSize::parse_length("10", "f")
                .unwrap()
                .width_mm(2.0, "f")
                .unwrap(),
            5.0
        );
        assert_eq!(
            StoneSize::parse_length("10x5", "f")
                .unwrap()
                .width_mm(2.0, "f")
                .unwrap(),
            5.0
        );
        let e = StoneSize::parse_length("10x8", "size")
            .unwrap()
            .width_mm(2.0, "size");
        assert!(e
            .unwrap_err()
            .to_string()
            .starts_with("size: `10x8` has L/W"));
        assert!(StoneSize::parse_length("ten", "size").is_err());
        assert!(StoneSize::width(0.0, "diameter").is_err());
    }

    #[test]
    fn one_chooser_for_colour_and_density() {
        let f = ColourFields {
            colour: "colour",
            density: "colour density",
        };
        let own = flat(0.2);
        assert_eq!(BodyColour::choose(None, None, None, f).unwrap(), None);
        assert_eq!(
            BodyColour::choose(Some(&own), None, None, f).unwrap(),
            Some(own.clone())
        );
        let d = BodyColour::choose(Some(&own), None, Some(2.0), f)
            .unwrap()
            .unwrap();
        assert!((d.alpha(600.0) - 0.4).abs() < 1e-15);
        let user = BodyColour::choose(Some(&own), Some("#7a3fa0@10mm"), Some(0.5), f)
            .unwrap()
            .unwrap();
        assert_eq!(user.name, "#7a3fa0@10mm");
        assert_eq!(user.density, 0.5);
        for (own, density, needle) in [
            (None, Some(2.0), "no colour to scale"),
            (Some(&own), Some(0.0), "out of range"),
            (Some(&own), Some(f64::NAN), "out of range"),
            (Some(&own), Some(101.0), "out of range"),
        ] {
            let e = BodyColour::choose(own, None, density, f)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("colour density: ") && e.contains(needle),
                "{e}"
            );
        }
        let note = own.not_traced_note(6.5);
        assert!(note.contains("6.5 mm") && note.contains("not yet traced") && !note.contains('\n'));
    }
    /// A pleochroic variety's E∥c colour follows its E⊥c one through the chooser: a density
    /// scales both rays, a user's colour replaces both (the E∥c spectrum dropped).
    #[test]
    fn the_e_ray_follows_the_chosen_colour() {
        let f = ColourFields {
            colour: "colour",
            density: "colour density",
        };
        let ruby = crate::optics::Material::by_name("ruby").unwrap();
        let e = ruby.colour_e().unwrap().clone();
        assert_ne!(Some(&e), ruby.colour.as_ref());
        let mut dark = ruby.clone();
        dark.choose_colour(None, Some(2.0), f).unwrap();
        assert_eq!(dark.colour_e().unwrap().density, 2.0);
        assert_eq!(dark.colour.as_ref().unwrap().density, 2.0);
        assert!((dark.colour_e().unwrap().alpha(550.0) - 2.0 * e.alpha(550.0)).abs() < 1e-12);
        let mut same = ruby.clone();
        same.choose_colour(None, None, f).unwrap();
        assert_eq!(same, ruby);
        let mut user = ruby.clone();
        user.choose_colour(Some("#7a3fa0@10mm"), None, f).unwrap();
        assert!(user.uniaxial.as_ref().unwrap().colour_e.is_none());
        assert_eq!(user.colour_e(), user.colour.as_ref());
    }
}
