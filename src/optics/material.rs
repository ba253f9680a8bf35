//! Materials: refractive index per wavelength. This file holds the index model — the
//! dispersion formulas ([`Dispersion`]: Sellmeier, Cauchy, constant), which ray of a
//! birefringent stone is traced ([`Optic`]) and the [`Material`] type with its index at a
//! wavelength; the named stones and their coefficients are the table of `table.rs`
//! ([`Material::table`]), and the ways to pick one (by name, by flag, by a cut's index) are in
//! `choose.rs`.
//!
//! [`Material::table`] holds the stones faceters cut, each with a published dispersion formula
//! (its source in the doc comment of [`Material::table`] and in [`Material::source`]) or, where
//! no formula has been published, a two-coefficient Cauchy curve fitted exactly to the
//! handbook's n_D and B–G dispersion (said so in its source). Birefringent stones are traced
//! with one index: uniaxial stones with the ordinary ray ω, biaxial stones with their lowest
//! index α ([`Optic`]); the listing says which.
//!
//! Handbook values (n_D, B–G, SG) are those of the GIA *Gem Reference Guide* (1988) and the
//! Gem-A/Read *Gemmology* tables; where those give a range, the ray the model uses is stated.

use super::body_colour::{BodyColour, ColourFields};
use crate::error::Result;

/// How the refractive index depends on wavelength.
#[derive(Clone, Debug, PartialEq)]
pub enum Dispersion {
    /// `n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ)`, λ in µm, Cᵢ in µm². A term with Cᵢ = 0 is the constant
    /// Bᵢ (the `n² = A + …` form some sources use); a negative Cᵢ is a term `Bλ²/(λ² + |C|)`.
    Sellmeier(Vec<(f64, f64)>),
    /// Cauchy's two-term formula `n = a + b / λ²`, λ in µm, b in µm².
    Cauchy {
        /// The index at infinite wavelength.
        a: f64,
        /// The dispersion coefficient, µm².
        b: f64,
    },
    /// The same index at every wavelength (no fire).
    Constant(f64),
    /// `n² = a + b / (λ² − c) − d λ²`, λ in µm (a pole in the ultraviolet and an infrared
    /// term; the form of some crystals' published fits).
    Pole {
        /// The constant term.
        a: f64,
        /// The pole's strength, µm².
        b: f64,
        /// The pole's position, µm².
        c: f64,
        /// The infrared term's coefficient, µm⁻².
        d: f64,
    },
}

impl Dispersion {
    /// The index at `wavelength_nm`.
    #[inline]
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        match self {
            Dispersion::Constant(n) => *n,
            Dispersion::Sellmeier(terms) => {
                let l2 = (wavelength_nm * 1e-3).powi(2);
                let s: f64 = terms.iter().map(|(b, c)| b * l2 / (l2 - c)).sum();
                (1.0 + s).sqrt()
            }
            Dispersion::Cauchy { a, b } => a + b / (wavelength_nm * 1e-3).powi(2),
            Dispersion::Pole { a, b, c, d } => {
                let l2 = (wavelength_nm * 1e-3).powi(2);
                (a + b / (l2 - c) - d * l2).sqrt()
            }
        }
    }

    /// The Cauchy curve `n = a + b/λ²` through index `nd` at the sodium D line whose B–G
    /// dispersion n(G) − n(B) is `bg` (an exact two-point fit).
    pub fn cauchy_through(nd: f64, bg: f64) -> Dispersion {
        let inv2 = |nm: f64| 1.0 / (nm * 1e-3).powi(2);
        let b = bg / (inv2(LINE_G_NM) - inv2(LINE_B_NM));
        Dispersion::Cauchy {
            a: nd - b * inv2(LINE_D_NM),
            b,
        }
    }

    /// The formula with its coefficients, for listings (λ in µm).
    pub fn formula(&self) -> String {
        match self {
            Dispersion::Sellmeier(terms) => {
                let mut s = String::from("Sellmeier n² = 1");
                for (b, c) in terms {
                    if *c == 0.0 {
                        s += &format!(" + {}", sig(*b));
                    } else if *c < 0.0 {
                        s += &format!(" + {}λ²/(λ² + {})", sig(*b), sig(-c));
                    } else {
                        s += &format!(" + {}λ²/(λ² − {})", sig(*b), sig(*c));
                    }
                }
                s + ", λ in µm"
            }
            Dispersion::Cauchy { a, b } => {
                format!("Cauchy n = {} + {}/λ², λ in µm", sig(*a), sig(*b))
            }
            Dispersion::Constant(n) => format!("n = {n} at every wavelength (no dispersion)"),
            Dispersion::Pole { a, b, c, d } => format!(
                "n² = {} + {}/(λ² − {}) − {}λ², λ in µm",
                sig(*a),
                sig(*b),
                sig(*c),
                sig(*d)
            ),
        }
    }

    /// A one-word kind: `Sellmeier`, `Cauchy` or `constant`.
    pub fn kind(&self) -> &'static str {
        match self {
            Dispersion::Sellmeier(_) | Dispersion::Pole { .. } => "Sellmeier",
            Dispersion::Cauchy { .. } => "Cauchy",
            Dispersion::Constant(_) => "constant",
        }
    }
}

/// `x` with 9 significant digits, trailing zeros dropped.
fn sig(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (8 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Which index (or indices) of a stone the model traces: one for singly refractive and biaxial
/// stones, the ordinary and extraordinary rays for uniaxial ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Optic {
    /// Singly refractive (cubic crystal or glass).
    Isotropic,
    /// Uniaxial: the ordinary ray ω is [`Material::ri`]; the extraordinary ray ε and the
    /// optic axis are [`Material::uniaxial`] (traced birefringent unless switched off).
    OrdinaryRay,
    /// Biaxial: the lowest index α; β and γ are not modelled.
    BiaxialAlpha,
}

impl Optic {
    /// Whether the model is a uniaxial stone's ordinary ray.
    pub fn ordinary_ray(self) -> bool {
        self == Optic::OrdinaryRay
    }
    /// A short label for listings.
    pub fn label(self) -> &'static str {
        match self {
            Optic::Isotropic => "isotropic",
            Optic::OrdinaryRay => "uniaxial (ω, ε)",
            Optic::BiaxialAlpha => "biaxial, α",
        }
    }
}

/// A gem material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name used on the command line.
    pub name: String,
    /// Refractive index model.
    pub dispersion: Dispersion,
    /// Density in g/cm³ (for carat weights): the handbook specific gravity.
    pub density: f64,
    /// Which index of a birefringent stone the model is.
    pub optic: Optic,
    /// Where the formula comes from (author, year, journal, range of validity), or how it
    /// was fitted.
    pub source: String,
    /// Body colour (absorption per mm over 380–780 nm); `None` is a colourless stone. A
    /// uniaxial stone's is the spectrum for light polarized ⊥ its optic axis (E ⊥ c, the
    /// ordinary ray's).
    pub colour: Option<super::body_colour::BodyColour>,
    /// A uniaxial stone's extraordinary ray, E ∥ c spectrum and optic axis, and whether it
    /// is traced birefringent; `None` for singly refractive and biaxial stones.
    pub uniaxial: Option<Uniaxial>,
}

/// A uniaxial stone's second index, its pleochroism and how the stone is cut from the
/// crystal.
#[derive(Clone, Debug, PartialEq)]
pub struct Uniaxial {
    /// The extraordinary index n_ε and its dispersion.
    pub extraordinary: Dispersion,
    /// Where the extraordinary formula comes from (or how it was fitted).
    pub source: String,
    /// The body colour for light polarized ∥ the optic axis (E ∥ c); `None`: the same as
    /// [`Material::colour`] (no pleochroism known).
    pub colour_e: Option<super::body_colour::BodyColour>,
    /// The optic axis in the stone (default: as cutters orient the material).
    pub axis: OpticAxis,
    /// Traced birefringent (default); `false` traces the ordinary ray alone, as before
    /// birefringence was modelled (`--birefringence off`).
    pub traced: bool,
}

/// The optic axis (c-axis) in a stone: tilted `tilt_deg` from the table's normal (+z) toward
/// azimuth `azimuth_deg` (counter-clockwise from +x, the stone's own azimuths). 0 puts the
/// c-axis perpendicular to the table ("c ⟂ table"); 90 lays it in the table's plane.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct OpticAxis {
    /// Angle from the table's normal, degrees in [0, 90].
    pub tilt_deg: f64,
    /// Azimuth it tilts toward, degrees.
    pub azimuth_deg: f64,
}

impl OpticAxis {
    /// `DEG` or `DEG@AZ` (degrees; the azimuth 0 when not given), e.g. `90@0`. Errors name
    /// `field` and say what is allowed.
    pub fn parse(text: &str, field: &str) -> crate::error::Result<OpticAxis> {
        let t = text.trim();
        let (tilt, az) = match t.split_once('@') {
            Some((a, b)) => (a.trim(), Some(b.trim())),
            None => (t, None),
        };
        let bad = || {
            crate::error::Error::invalid(
                field,
                format!(
                    "`{t}` is not an optic axis; give DEG[@AZ]: the angle of the c-axis from the table's normal in [0, 90] degrees, toward azimuth AZ in [-360, 360] degrees (e.g. 0, 90@0, 45@22.5)"
                ),
            )
        };
        let tilt_deg: f64 = tilt.trim_end_matches('°').parse().map_err(|_| bad())?;
        let azimuth_deg: f64 = match az {
            Some(a) => a.trim_end_matches('°').parse().map_err(|_| bad())?,
            None => 0.0,
        };
        OpticAxis::new(tilt_deg, azimuth_deg, field).map_err(|_| bad())
    }

    /// The axis `tilt_deg` (in [0, 90]) from the table's normal toward `azimuth_deg` (in
    /// [-360, 360]), as a face that reads numbers gives it; errors name `field` and say what
    /// is allowed, as [`OpticAxis::parse`]'s.
    pub fn new(tilt_deg: f64, azimuth_deg: f64, field: &str) -> crate::error::Result<OpticAxis> {
        if !((0.0..=90.0).contains(&tilt_deg) && (-360.0..=360.0).contains(&azimuth_deg)) {
            let shown = if azimuth_deg == 0.0 {
                format!("{tilt_deg}")
            } else {
                format!("{tilt_deg}@{azimuth_deg}")
            };
            return Err(crate::error::Error::invalid(
                field,
                format!(
                    "`{shown}` is not an optic axis; give DEG[@AZ]: the angle of the c-axis from the table's normal in [0, 90] degrees, toward azimuth AZ in [-360, 360] degrees (e.g. 0, 90@0, 45@22.5)"
                ),
            ));
        }
        Ok(OpticAxis {
            tilt_deg,
            azimuth_deg,
        })
    }

    /// The axis along `v` (stone coordinates, any length; `v` and `−v` are the same axis),
    /// unrounded: its [`OpticAxis::vector`] is `v` normalised, up or down, to rounding.
    pub fn along(v: glam::DVec3) -> OpticAxis {
        let v = if v.z < 0.0 { -v } else { v }.normalize();
        let h = v.truncate().length();
        OpticAxis {
            tilt_deg: h.atan2(v.z).to_degrees(),
            azimuth_deg: if h > 0.0 {
                v.y.atan2(v.x).to_degrees()
            } else {
                0.0
            },
        }
    }

    /// The unit vector along the axis, in the stone's coordinates.
    pub fn vector(&self) -> glam::DVec3 {
        let (t, a) = (self.tilt_deg.to_radians(), self.azimuth_deg.to_radians());
        glam::DVec3::new(t.sin() * a.cos(), t.sin() * a.sin(), t.cos())
    }

    /// `DEG@AZ` as [`OpticAxis::parse`] reads it (`DEG` alone when the azimuth is 0).
    pub fn label(&self) -> String {
        if self.azimuth_deg == 0.0 {
            format!("{}", self.tilt_deg)
        } else {
            format!("{}@{}", self.tilt_deg, self.azimuth_deg)
        }
    }
}

impl Material {
    /// Whether the stone is traced birefringent: uniaxial with birefringence on.
    pub fn birefringent(&self) -> bool {
        self.uniaxial.as_ref().is_some_and(|u| u.traced)
    }

    /// The extraordinary index at `wavelength_nm` of a uniaxial stone (its ordinary index
    /// for any other).
    pub fn ri_e(&self, wavelength_nm: f64) -> f64 {
        match &self.uniaxial {
            Some(u) => u.extraordinary.at(wavelength_nm),
            None => self.ri(wavelength_nm),
        }
    }

    /// The body colour for light polarized ∥ the optic axis: a uniaxial stone's E ∥ c
    /// spectrum, or its one spectrum when none is known.
    pub fn colour_e(&self) -> Option<&super::body_colour::BodyColour> {
        self.uniaxial
            .as_ref()
            .and_then(|u| u.colour_e.as_ref())
            .or(self.colour.as_ref())
    }
}

/// The names under which a material choice reaches [`Material::choose`] (a flag pair such as
/// `--material`/`--ri`, or a config's `score.material`/`score.ri`), for its error messages.
#[derive(Clone, Copy, Debug)]
pub struct MaterialFields<'a> {
    /// Where the material's name was given.
    pub material: &'a str,
    /// Where the fixed refractive index was given.
    pub ri: &'a str,
}

/// Fraunhofer B (686.7 nm) and G (430.8 nm) lines used for "dispersion" in gemmology.
pub const LINE_B_NM: f64 = 686.7;
/// See [`LINE_B_NM`].
pub const LINE_G_NM: f64 = 430.8;
/// Sodium D line, the reference wavelength for "the" refractive index.
pub const LINE_D_NM: f64 = 589.3;

impl Material {
    /// Refractive index at `wavelength_nm` (a birefringent stone's ordinary ray ω; see
    /// [`Material::uniaxial`] for its extraordinary one).
    #[inline]
    pub fn ri(&self, wavelength_nm: f64) -> f64 {
        self.dispersion.at(wavelength_nm)
    }

    /// Refractive index at the sodium D line.
    pub fn ri_d(&self) -> f64 {
        self.ri(LINE_D_NM)
    }

    /// Gemmological dispersion n(G) − n(B).
    pub fn bg_dispersion(&self) -> f64 {
        self.ri(LINE_G_NM) - self.ri(LINE_B_NM)
    }

    /// The dispersion formula with its coefficients (see [`Dispersion::formula`]).
    pub fn formula(&self) -> String {
        self.dispersion.formula()
    }
}

impl Material {
    /// Choose this stone's body colour as [`BodyColour::choose`] does with its own, and keep a
    /// uniaxial stone's E ∥ c colour in step: a user's colour replaces the variety's spectra
    /// of both rays (its E ∥ c one is dropped: the crystal settings' E ∥ c colour gives one
    /// back), and a density scales both. Errors as [`BodyColour::choose`]'s.
    pub fn choose_colour(
        &mut self,
        user: Option<&str>,
        density: Option<f64>,
        fields: ColourFields<'_>,
    ) -> Result<()> {
        let colour = BodyColour::choose(self.colour.as_ref(), user, density, fields)?;
        if let Some(u) = self.uniaxial.as_mut() {
            u.colour_e = match (user, u.colour_e.take(), density) {
                (Some(_), _, _) | (None, None, _) => None,
                (None, Some(c), Some(d)) => Some(c.with_density(d)),
                (None, Some(c), None) => Some(c),
            };
        }
        self.colour = colour;
        Ok(())
    }
}
