//! Materials: refractive index per wavelength.

use crate::error::{Error, Result};

/// How the refractive index depends on wavelength.
#[derive(Clone, Debug, PartialEq)]
pub enum Dispersion {
    /// `n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ)`, λ in µm, Cᵢ in µm².
    Sellmeier(Vec<(f64, f64)>),
    /// The same index at every wavelength (no fire).
    Constant(f64),
}

/// A gem material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name used on the command line.
    pub name: String,
    /// Refractive index model.
    pub dispersion: Dispersion,
    /// Density in g/cm³ (for carat weights).
    pub density: f64,
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
    /// Diamond: two-term Sellmeier, B₁ = 0.3306, C₁ = 0.175² µm², B₂ = 4.3356, C₂ = 0.106² µm²;
    /// n_D ≈ 2.4173, B–G dispersion ≈ 0.044.
    pub fn diamond() -> Material {
        Material {
            name: "diamond".into(),
            dispersion: Dispersion::Sellmeier(vec![
                (0.3306, 0.175 * 0.175),
                (4.3356, 0.106 * 0.106),
            ]),
            density: 3.515,
        }
    }
    /// Cubic zirconia (yttria-stabilised; Wood & Nassau 1982), n_D ≈ 2.17, B–G ≈ 0.06.
    pub fn cubic_zirconia() -> Material {
        Material {
            name: "cubic-zirconia".into(),
            dispersion: Dispersion::Sellmeier(vec![
                (1.347091, 0.062543 * 0.062543),
                (2.117788, 0.166739 * 0.166739),
                (9.452943, 24.320570 * 24.320570),
            ]),
            density: 5.9,
        }
    }
    /// Sapphire, ordinary ray (Malitson 1972), n_D ≈ 1.768. (Birefringence is ignored; the
    /// extraordinary ray differs by 0.008.)
    pub fn sapphire() -> Material {
        Material {
            name: "sapphire".into(),
            dispersion: Dispersion::Sellmeier(vec![
                (1.4313493, 0.0726631 * 0.0726631),
                (0.65054713, 0.1193242 * 0.1193242),
                (5.3414021, 18.028251 * 18.028251),
            ]),
            density: 3.98,
        }
    }
    /// Borosilicate crown glass (Schott N-BK7), n_D ≈ 1.5168.
    pub fn glass() -> Material {
        Material {
            name: "glass".into(),
            dispersion: Dispersion::Sellmeier(vec![
                (1.03961212, 0.00600069867),
                (0.231792344, 0.0200179144),
                (1.01046945, 103.560653),
            ]),
            density: 2.51,
        }
    }
    /// A fixed refractive index (no dispersion), with diamond's density.
    pub fn constant(n: f64) -> Material {
        Material {
            name: format!("ri-{n}"),
            dispersion: Dispersion::Constant(n),
            density: 3.515,
        }
    }

    /// Names accepted by [`Material::by_name`].
    pub const NAMES: &'static [&'static str] = &["diamond", "cubic-zirconia", "sapphire", "glass"];

    /// A material by name (`diamond`, `cubic-zirconia` or `cz`, `sapphire`, `glass`).
    /// Moissanite is birefringent and deliberately not offered.
    pub fn by_name(name: &str) -> Result<Material> {
        match name.to_ascii_lowercase().as_str() {
            "diamond" => Ok(Material::diamond()),
            "cubic-zirconia" | "cz" => Ok(Material::cubic_zirconia()),
            "sapphire" => Ok(Material::sapphire()),
            "glass" | "bk7" => Ok(Material::glass()),
            "moissanite" => Err(Error::invalid(
                "--material",
                "moissanite is birefringent and not modelled; use --ri 2.65 for a single-index stand-in",
            )),
            _ => Err(Error::invalid(
                "--material",
                format!("unknown material `{name}`; known: {}", Material::NAMES.join(", ")),
            )),
        }
    }

    /// A fixed refractive index must be above this (1 is vacuum: nothing would refract).
    pub const RI_ABOVE: f64 = 1.0;
    /// The largest fixed refractive index accepted.
    pub const RI_MAX: f64 = 10.0;

    /// The one chooser of a material, for the command line (`--material`, `--ri`) and the
    /// config (`score.material`, `score.ri`): a material by name ([`Material::by_name`]), or a
    /// fixed index in ([`RI_ABOVE`](Material::RI_ABOVE), [`RI_MAX`](Material::RI_MAX)], or
    /// diamond when neither is given. Errors name `fields.material` or `fields.ri`.
    pub fn choose(
        name: Option<&str>,
        ri: Option<f64>,
        fields: MaterialFields<'_>,
    ) -> Result<Material> {
        match (name, ri) {
            (Some(_), Some(_)) => Err(Error::invalid(
                fields.ri,
                format!("give either {} or {}, not both", fields.material, fields.ri),
            )),
            (None, Some(n)) => {
                if n > Material::RI_ABOVE && n <= Material::RI_MAX {
                    Ok(Material::constant(n))
                } else {
                    Err(Error::invalid(
                        fields.ri,
                        format!(
                            "{n} is out of range; allowed ({}, {}] (a refractive index)",
                            Material::RI_ABOVE,
                            Material::RI_MAX
                        ),
                    ))
                }
            }
            (Some(m), None) => Material::by_name(m).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(fields.material, message),
                other => other,
            }),
            (None, None) => Ok(Material::diamond()),
        }
    }

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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_chooser_for_name_index_or_default() {
        let f = MaterialFields {
            material: "--material",
            ri: "--ri",
        };
        assert_eq!(Material::choose(None, None, f).unwrap().name, "diamond");
        assert_eq!(
            Material::choose(Some("cz"), None, f).unwrap().name,
            "cubic-zirconia"
        );
        assert_eq!(
            Material::choose(None, Some(10.0), f).unwrap().ri(500.0),
            10.0
        );
        for bad in [1.0, 0.5, 10.001, f64::NAN, f64::INFINITY] {
            let e = Material::choose(None, Some(bad), f)
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("--ri: ") && e.contains("allowed (1, 10]"),
                "{e}"
            );
        }
        let e = Material::choose(Some("cz"), Some(2.0), f)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--ri: give either --material or --ri"), "{e}");
        let e = Material::choose(Some("kryptonite"), None, f)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--material: unknown material"), "{e}");
    }

    #[test]
    fn diamond_index_and_dispersion() {
        let d = Material::diamond();
        assert!((d.ri_d() - 2.4173).abs() < 2e-4, "{}", d.ri_d());
        assert!(
            (d.bg_dispersion() - 0.044).abs() < 0.002,
            "{}",
            d.bg_dispersion()
        );
    }

    #[test]
    fn other_materials_match_handbook_values() {
        assert!((Material::cubic_zirconia().ri_d() - 2.17).abs() < 0.02);
        assert!(Material::cubic_zirconia().bg_dispersion() > Material::diamond().bg_dispersion());
        assert!((Material::sapphire().ri_d() - 1.768).abs() < 0.003);
        assert!((Material::glass().ri_d() - 1.5168).abs() < 5e-4);
        assert_eq!(Material::constant(2.0).bg_dispersion(), 0.0);
        assert!(Material::by_name("moissanite")
            .unwrap_err()
            .to_string()
            .contains("birefringent"));
        assert!(Material::by_name("unobtainium")
            .unwrap_err()
            .to_string()
            .contains("diamond"));
    }

    #[test]
    fn index_falls_with_wavelength() {
        for m in [
            Material::diamond(),
            Material::cubic_zirconia(),
            Material::sapphire(),
            Material::glass(),
        ] {
            let mut prev = f64::INFINITY;
            for l in (380..=780).step_by(10) {
                let n = m.ri(l as f64);
                assert!(n < prev && n > 1.0, "{} at {l}", m.name);
                prev = n;
            }
        }
    }
}
