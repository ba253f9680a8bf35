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
}

impl Dispersion {
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
        }
    }

    /// A one-word kind: `Sellmeier`, `Cauchy` or `constant`.
    pub fn kind(&self) -> &'static str {
        match self {
            Dispersion::Sellmeier(_) => "Sellmeier",
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

/// Which index of a stone the model traces. Birefringent stones are traced with one index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Optic {
    /// Singly refractive (cubic crystal or glass).
    Isotropic,
    /// Uniaxial: the ordinary ray ω; the extraordinary ray is not modelled.
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
            Optic::OrdinaryRay => "ordinary ray (ω)",
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
    /// Body colour (absorption per mm over 380–780 nm); `None` is a colourless stone.
    pub colour: Option<super::body_colour::BodyColour>,
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
    /// Refractive index at `wavelength_nm`.
    #[inline]
    pub fn ri(&self, wavelength_nm: f64) -> f64 {
        match &self.dispersion {
            Dispersion::Constant(n) => *n,
            Dispersion::Sellmeier(terms) => {
                let l2 = (wavelength_nm * 1e-3).powi(2);
                let s: f64 = terms.iter().map(|(b, c)| b * l2 / (l2 - c)).sum();
                (1.0 + s).sqrt()
            }
            Dispersion::Cauchy { a, b } => a + b / (wavelength_nm * 1e-3).powi(2),
        }
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
