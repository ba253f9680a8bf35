//! The table of named materials: each stone's dispersion coefficients (or handbook fit),
//! density and traced ray, with its citation, in order of rising n_D; and the constructors
//! and listings that read it ([`Material::table`], [`Material::NAMES`], [`Material::diamond`],
//! …).

use super::material::{Dispersion, Material, Optic, OpticAxis, Uniaxial};

/// How a table entry's index is computed.
enum Model {
    /// Published Sellmeier terms `(B, C)`, C in µm².
    Sellmeier(&'static [(f64, f64)]),
    /// A Cauchy curve fitted exactly to the handbook's n_D and B–G.
    HandbookFit { nd: f64, bg: f64 },
    /// `n² = a + b/(λ² − c) − dλ²`.
    Pole { a: f64, b: f64, c: f64, d: f64 },
}

impl Model {
    fn dispersion(&self) -> Dispersion {
        match *self {
            Model::Sellmeier(terms) => Dispersion::Sellmeier(terms.to_vec()),
            Model::HandbookFit { nd, bg } => Dispersion::cauchy_through(nd, bg),
            Model::Pole { a, b, c, d } => Dispersion::Pole { a, b, c, d },
        }
    }
}

/// A uniaxial stone's extraordinary ray: its index model, where it comes from, and the
/// optic axis cutters most often give the table (with the reason).
struct Extraordinary {
    model: Model,
    source: &'static str,
    axis: OpticAxis,
}

/// The c-axis perpendicular to the table.
const C_UP: OpticAxis = OpticAxis {
    tilt_deg: 0.0,
    azimuth_deg: 0.0,
};
/// The c-axis in the table's plane, along azimuth 0.
const C_FLAT: OpticAxis = OpticAxis {
    tilt_deg: 90.0,
    azimuth_deg: 0.0,
};

/// One row of the material table.
pub(super) struct Entry {
    pub(super) name: &'static str,
    pub(super) aliases: &'static [&'static str],
    model: Model,
    pub(super) density: f64,
    optic: Optic,
    source: &'static str,
    /// A uniaxial stone's extraordinary ray (`None` for singly refractive and biaxial ones).
    extraordinary: Option<Extraordinary>,
}

/// Borosilicate crown glass, SCHOTT N-BK7: Sellmeier from the SCHOTT optical glass catalogue
/// (Zemax catalogue 2017-01-20), valid 0.3–2.5 µm; n_d 1.5168, v_d 64.17; ρ 2.51 g/cm³.
const GLASS: Entry = Entry {
    name: "glass",
    aliases: &["bk7", "n-bk7"],
    model: Model::Sellmeier(&[
        (1.03961212, 0.00600069867),
        (0.231792344, 0.0200179144),
        (1.01046945, 103.560653),
    ]),
    density: 2.51,
    optic: Optic::Isotropic,
    source: "SCHOTT optical glass catalogue, N-BK7 (2017); valid 0.3–2.5 µm; n_d 1.5168, v_d 64.17",
    extraordinary: None,
};

/// Quartz, ordinary ray: G. Ghosh, "Dispersion-equation coefficients for the refractive index
/// and birefringence of calcite and quartz crystals", Opt. Commun. 163, 95–102 (1999); room
/// temperature, valid 0.198–2.05 µm: n² = 1.28604141 + 1.07044083λ²/(λ² − 1.00585997e-2) +
/// 1.10202242λ²/(λ² − 100). Handbook: n_ω 1.544, n_ε 1.553, B–G 0.013, SG 2.66.
const QUARTZ: Entry = Entry {
    name: "quartz",
    aliases: &[],
    model: Model::Sellmeier(&[
        (0.28604141, 0.0),
        (1.07044083, 1.00585997e-2),
        (1.10202242, 100.0),
    ]),
    density: 2.66,
    optic: Optic::OrdinaryRay,
    source: "G. Ghosh, Opt. Commun. 163, 95–102 (1999), ordinary ray; valid 0.198–2.05 µm",
    // G. Ghosh (1999), extraordinary ray; quartz is usually oriented with the table ⟂ c
    // (no preference of colour in colourless quartz; amethyst shows its deeper o-ray purple).
    extraordinary: Some(Extraordinary {
        model: Model::Sellmeier(&[
            (0.28851804, 0.0),
            (1.09509924, 1.02101864e-2),
            (1.15662475, 100.0),
        ]),
        source: "G. Ghosh, Opt. Commun. 163, 95–102 (1999), extraordinary ray; valid 0.198–2.05 µm",
        axis: C_UP,
    }),
};

/// Beryl (aquamarine, emerald, morganite), ordinary ray. No published dispersion formula: a
/// Cauchy curve fitted exactly to the GIA handbook's n_ω 1.583 (beryl 1.577–1.583, uniaxial
/// negative, so ω is the higher index) and B–G 0.014. SG 2.72.
const BERYL: Entry = Entry {
    name: "beryl",
    aliases: &["morganite"],
    model: Model::HandbookFit {
        nd: 1.583,
        bg: 0.014,
    },
    density: 2.72,
    optic: Optic::OrdinaryRay,
    source: "Cauchy fitted to handbook n_ω 1.583 (1.577–1.583, uniaxial −), B–G 0.014 (GIA Gem Reference Guide); no published formula",
    // No formula: Cauchy through the handbook's n_ε 1.577 with the same B–G. Emerald is
    // cut with the table ⟂ c where the rough allows (its o-ray is the bluer green).
    extraordinary: Some(Extraordinary {
        model: Model::HandbookFit {
            nd: 1.577,
            bg: 0.014,
        },
        source: "Cauchy fitted to handbook n_ε 1.577, B–G 0.014 (GIA Gem Reference Guide); no published formula",
        axis: C_UP,
    }),
};

/// Topaz, lowest index α. No published dispersion formula: a Cauchy curve fitted exactly to the
/// GIA handbook's n_α 1.619 (1.619–1.627, biaxial positive) and B–G 0.014. SG 3.53.
const TOPAZ: Entry = Entry {
    name: "topaz",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.619,
        bg: 0.014,
    },
    density: 3.53,
    optic: Optic::BiaxialAlpha,
    source: "Cauchy fitted to handbook n_α 1.619 (1.619–1.627, biaxial +), B–G 0.014 (GIA Gem Reference Guide); no published formula",
    extraordinary: None,
};

/// Dense lead flint glass, SCHOTT F2 (the classic "paste"): Sellmeier from the SCHOTT optical
/// glass catalogue (Zemax catalogue 2017-01-20), valid 0.32–2.5 µm; n_d 1.62004, v_d 36.37;
/// ρ 3.599 g/cm³.
const LEAD_GLASS: Entry = Entry {
    name: "lead-glass",
    aliases: &["f2", "flint"],
    model: Model::Sellmeier(&[
        (1.34533359, 0.00997743871),
        (0.209073176, 0.0470450767),
        (0.937357162, 111.886764),
    ]),
    density: 3.599,
    optic: Optic::Isotropic,
    source: "SCHOTT optical glass catalogue, F2 (2017); valid 0.32–2.5 µm; n_d 1.62004, v_d 36.37",
    extraordinary: None,
};

/// Tourmaline, ordinary ray. No published dispersion formula: a Cauchy curve fitted exactly to
/// the GIA handbook's n_ω 1.644 (1.624–1.644, uniaxial negative) and B–G 0.017. SG 3.06.
const TOURMALINE: Entry = Entry {
    name: "tourmaline",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.644,
        bg: 0.017,
    },
    density: 3.06,
    optic: Optic::OrdinaryRay,
    source: "Cauchy fitted to handbook n_ω 1.644 (1.624–1.644, uniaxial −), B–G 0.017 (GIA Gem Reference Guide); no published formula",
    // No formula: Cauchy through the handbook's n_ε 1.624 with the same B–G. Tourmaline's
    // o-ray is the darker ("closed c-axis"): cutters lay the table parallel to c.
    extraordinary: Some(Extraordinary {
        model: Model::HandbookFit {
            nd: 1.624,
            bg: 0.017,
        },
        source: "Cauchy fitted to handbook n_ε 1.624, B–G 0.017 (GIA Gem Reference Guide); no published formula",
        axis: C_FLAT,
    }),
};

/// Peridot (olivine), lowest index α. No published dispersion formula: a Cauchy curve fitted
/// exactly to the GIA handbook's n_α 1.654 (1.654–1.690, biaxial positive) and B–G 0.020.
/// SG 3.34.
const PERIDOT: Entry = Entry {
    name: "peridot",
    aliases: &["olivine"],
    model: Model::HandbookFit {
        nd: 1.654,
        bg: 0.020,
    },
    density: 3.34,
    optic: Optic::BiaxialAlpha,
    source: "Cauchy fitted to handbook n_α 1.654 (1.654–1.690, biaxial +), B–G 0.020 (GIA Gem Reference Guide); no published formula",
    extraordinary: None,
};

/// Spinel (MgAl₂O₄): W. J. Tropf and M. E. Thomas, "Magnesium aluminum spinel (MgAl₂O₄)", in
/// E. D. Palik (ed.), Handbook of Optical Constants of Solids II, Academic Press, 1991,
/// pp. 881–895 (the Sellmeier as improved in Handbook of Optics, 3rd ed., Vol. 4, 2009); room
/// temperature, valid 0.35–5.5 µm. Handbook: n 1.718, B–G 0.020, SG 3.60.
const SPINEL: Entry = Entry {
    name: "spinel",
    aliases: &[],
    model: Model::Sellmeier(&[(1.8938, 0.09942 * 0.09942), (3.0755, 15.826 * 15.826)]),
    density: 3.60,
    optic: Optic::Isotropic,
    source: "W. J. Tropf, M. E. Thomas, Handbook of Optical Constants of Solids II (Palik, ed.), 881–895 (1991); valid 0.35–5.5 µm",
    extraordinary: None,
};

/// Grossular garnet (hessonite, tsavorite). No published dispersion formula: a Cauchy curve
/// fitted exactly to the GIA handbook's n 1.740 and B–G 0.028. SG 3.61.
const GROSSULAR: Entry = Entry {
    name: "grossular",
    aliases: &["hessonite"],
    model: Model::HandbookFit {
        nd: 1.740,
        bg: 0.028,
    },
    density: 3.61,
    optic: Optic::Isotropic,
    source: "Cauchy fitted to handbook n 1.740, B–G 0.028 (GIA Gem Reference Guide); no published formula",
    extraordinary: None,
};

/// Pyrope garnet. No published dispersion formula: a Cauchy curve fitted exactly to the GIA
/// handbook's n 1.746 and B–G 0.022. SG 3.78.
const PYROPE: Entry = Entry {
    name: "pyrope",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.746,
        bg: 0.022,
    },
    density: 3.78,
    optic: Optic::Isotropic,
    source: "Cauchy fitted to handbook n 1.746, B–G 0.022 (GIA Gem Reference Guide); no published formula",
    extraordinary: None,
};

/// Sapphire and ruby (corundum), ordinary ray: I. H. Malitson and M. J. Dodge, "Refractive
/// index and birefringence of synthetic sapphire", J. Opt. Soc. Am. 62, 1405 (1972), formula
/// in M. J. Dodge, Handbook of Laser Science and Technology IV, CRC Press, 1986, p. 30;
/// 20 °C, valid 0.2–5.0 µm. Handbook: n_ω 1.770 (1.762–1.770, uniaxial negative), B–G 0.018,
/// SG 4.00 (synthetic corundum 3.98).
const SAPPHIRE: Entry = Entry {
    name: "sapphire",
    aliases: &["corundum"],
    model: Model::Sellmeier(&[
        (1.4313493, 0.0726631 * 0.0726631),
        (0.65054713, 0.1193242 * 0.1193242),
        (5.3414021, 18.028251 * 18.028251),
    ]),
    density: 3.98,
    optic: Optic::OrdinaryRay,
    source: "I. H. Malitson, M. J. Dodge, J. Opt. Soc. Am. 62, 1405 (1972), ordinary ray; valid 0.2–5.0 µm",
    // Malitson & Dodge (1972), extraordinary ray. Ruby and sapphire are cut with the table
    // ⟂ c for their best (o-ray) colour.
    extraordinary: Some(Extraordinary {
        model: Model::Sellmeier(&[
            (1.5039759, 0.0740288 * 0.0740288),
            (0.55069141, 0.1216529 * 0.1216529),
            (6.5927379, 20.072248 * 20.072248),
        ]),
        source: "I. H. Malitson, M. J. Dodge, J. Opt. Soc. Am. 62, 1405 (1972), extraordinary ray; valid 0.2–5.0 µm",
        axis: C_UP,
    }),
};

/// Almandine garnet. No published dispersion formula: a Cauchy curve fitted exactly to the GIA
/// handbook's n 1.790 and B–G 0.024. SG 4.05.
const ALMANDINE: Entry = Entry {
    name: "almandine",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.790,
        bg: 0.024,
    },
    density: 4.05,
    optic: Optic::Isotropic,
    source: "Cauchy fitted to handbook n 1.790, B–G 0.024 (GIA Gem Reference Guide); no published formula",
    extraordinary: None,
};

/// Yttrium aluminium garnet (YAG, Y₃Al₅O₁₂): D. E. Zelmon, D. L. Small and R. Page,
/// "Refractive-index measurements of undoped yttrium aluminum garnet from 0.4 to 5.0 µm",
/// Appl. Opt. 37, 4933–4935 (1998); valid 0.4–5.0 µm. Handbook: n 1.833, B–G 0.028, SG 4.55.
const YAG: Entry = Entry {
    name: "yag",
    aliases: &[],
    model: Model::Sellmeier(&[(2.282, 0.01185), (3.27644, 282.734)]),
    density: 4.55,
    optic: Optic::Isotropic,
    source: "D. E. Zelmon, D. L. Small, R. Page, Appl. Opt. 37, 4933–4935 (1998); valid 0.4–5.0 µm",
    extraordinary: None,
};

/// High zircon, ordinary ray. No published dispersion formula: a Cauchy curve fitted exactly to
/// the GIA handbook's n_ω 1.925 (1.925–1.984, uniaxial positive) and B–G 0.039. SG 4.70.
const ZIRCON: Entry = Entry {
    name: "zircon",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.925,
        bg: 0.039,
    },
    density: 4.70,
    optic: Optic::OrdinaryRay,
    source: "Cauchy fitted to handbook n_ω 1.925 (1.925–1.984, uniaxial +), B–G 0.039 (GIA Gem Reference Guide); no published formula",
    // No formula: Cauchy through the handbook's n_ε 1.984 with the same B–G. Zircon is cut
    // with the table ⟂ c so that its strong doubling is not seen face-up.
    extraordinary: Some(Extraordinary {
        model: Model::HandbookFit {
            nd: 1.984,
            bg: 0.039,
        },
        source: "Cauchy fitted to handbook n_ε 1.984, B–G 0.039 (GIA Gem Reference Guide); no published formula",
        axis: C_UP,
    }),
};

/// Gadolinium gallium garnet (GGG, Gd₃Ga₅O₁₂). No dispersion formula was found in the sources
/// we could check: a Cauchy curve fitted exactly to the GIA handbook's n 1.970 and B–G 0.045.
/// SG 7.05.
const GGG: Entry = Entry {
    name: "ggg",
    aliases: &[],
    model: Model::HandbookFit {
        nd: 1.970,
        bg: 0.045,
    },
    density: 7.05,
    optic: Optic::Isotropic,
    source:
        "Cauchy fitted to handbook n 1.970, B–G 0.045 (GIA Gem Reference Guide); no formula found",
    extraordinary: None,
};

/// Cubic zirconia (ZrO₂ stabilised with 12 mol % Y₂O₃): D. L. Wood and K. Nassau, "Refractive
/// index of cubic zirconia stabilized with yttria", Appl. Opt. 21, 2978–2981 (1982); valid
/// 0.361–5.135 µm; n_D 2.1585. Handbook: n 2.15–2.18 (with the stabiliser), B–G 0.060,
/// SG 5.80.
const CUBIC_ZIRCONIA: Entry = Entry {
    name: "cubic-zirconia",
    aliases: &["cz"],
    model: Model::Sellmeier(&[
        (1.347091, 0.062543 * 0.062543),
        (2.117788, 0.166739 * 0.166739),
        (9.452943, 24.320570 * 24.320570),
    ]),
    density: 5.80,
    optic: Optic::Isotropic,
    source: "D. L. Wood, K. Nassau, Appl. Opt. 21, 2978–2981 (1982), 12 mol % Y2O3; valid 0.361–5.135 µm",
    extraordinary: None,
};

/// Strontium titanate (SrTiO₃, "Fabulite"). No dispersion formula was found in the sources we
/// could check: a Cauchy curve fitted exactly to the handbook's n 2.409 and B–G 0.190. It
/// agrees with W. L. Bond's measurements (J. Appl. Phys. 36, 1674–1677 (1965)) within 0.003
/// at 0.5–0.7 µm and within 0.009 at 0.45 and 0.8 µm. SG 5.13.
const STRONTIUM_TITANATE: Entry = Entry {
    name: "strontium-titanate",
    aliases: &["srtio3", "fabulite"],
    model: Model::HandbookFit {
        nd: 2.409,
        bg: 0.190,
    },
    density: 5.13,
    optic: Optic::Isotropic,
    source: "Cauchy fitted to handbook n 2.409, B–G 0.190; within 0.003 of W. L. Bond, J. Appl. Phys. 36, 1674 (1965) at 0.5–0.7 µm",
    extraordinary: None,
};

/// Diamond: F. Peter, "Über Brechungsindizes und Absorptionskonstanten des Diamanten zwischen
/// 644 und 226 mμ", Z. Phys. 15, 358–368 (1923); valid 0.226–0.76 µm: B₁ = 0.3306,
/// C₁ = 0.175² µm², B₂ = 4.3356, C₂ = 0.106² µm² (the thesis's); n_D ≈ 2.4173, B–G ≈ 0.044.
pub(super) const DIAMOND: Entry = Entry {
    name: "diamond",
    aliases: &[],
    model: Model::Sellmeier(&[(0.3306, 0.175 * 0.175), (4.3356, 0.106 * 0.106)]),
    density: 3.515,
    optic: Optic::Isotropic,
    source: "F. Peter, Z. Phys. 15, 358–368 (1923); valid 0.226–0.76 µm",
    extraordinary: None,
};

/// Moissanite (4H-SiC), ordinary ray: S. Wang, M. Zhan, G. Wang, H. Xuan, W. Zhang, C. Liu,
/// C. Xu, Y. Liu, Z. Wei, X. Chen, "4H-SiC: a new nonlinear material for midinfrared lasers",
/// Laser Photonics Rev. 7, 831–838 (2013); valid 0.4047–5 µm. Handbook: n_ω 2.648, n_ε 2.691
/// (uniaxial positive), B–G 0.104, SG 3.22; this formula gives n_ω 2.646 and B–G 0.111.
const MOISSANITE: Entry = Entry {
    name: "moissanite",
    aliases: &["sic"],
    model: Model::Sellmeier(&[
        (0.20075, -12.07224),
        (5.54861, 0.02641),
        (35.65066, 1268.24708),
    ]),
    density: 3.22,
    optic: Optic::OrdinaryRay,
    source: "S. Wang et al., Laser Photonics Rev. 7, 831–838 (2013), 4H-SiC ordinary ray; valid 0.4047–5 µm",
    // S. Wang et al. (2013), extraordinary ray (n² = A + B/(λ² − C) − Dλ²). Moissanite is cut
    // with the table ⟂ c so that its doubling is not seen face-up.
    extraordinary: Some(Extraordinary {
        model: Model::Pole {
            a: 6.79485,
            b: 0.15558,
            c: 0.03535,
            d: 0.02296,
        },
        source: "S. Wang et al., Laser Photonics Rev. 7, 831–838 (2013), 4H-SiC extraordinary ray; valid 0.4047–2.325 µm",
        axis: C_UP,
    }),
};

/// The table, in order of rising n_D.
pub(super) const TABLE: &[Entry] = &[
    GLASS,
    QUARTZ,
    BERYL,
    TOPAZ,
    LEAD_GLASS,
    TOURMALINE,
    PERIDOT,
    SPINEL,
    GROSSULAR,
    PYROPE,
    SAPPHIRE,
    ALMANDINE,
    YAG,
    ZIRCON,
    GGG,
    CUBIC_ZIRCONIA,
    STRONTIUM_TITANATE,
    DIAMOND,
    MOISSANITE,
];

impl Entry {
    pub(super) fn material(&self) -> Material {
        Material {
            name: self.name.into(),
            dispersion: self.model.dispersion(),
            density: self.density,
            optic: self.optic,
            source: self.source.into(),
            colour: None,
            uniaxial: self.extraordinary.as_ref().map(|x| Uniaxial {
                extraordinary: x.model.dispersion(),
                source: x.source.into(),
                colour_e: None,
                axis: x.axis,
                traced: true,
            }),
        }
    }
}

impl Material {
    /// Diamond (Peter 1923): n_D ≈ 2.4173, B–G dispersion ≈ 0.044.
    pub fn diamond() -> Material {
        DIAMOND.material()
    }
    /// Cubic zirconia (yttria-stabilised; Wood & Nassau 1982), n_D ≈ 2.1585, B–G ≈ 0.060.
    pub fn cubic_zirconia() -> Material {
        CUBIC_ZIRCONIA.material()
    }
    /// Sapphire, ordinary ray (Malitson & Dodge 1972), n_D ≈ 1.768. (The extraordinary ray
    /// differs by 0.008 and is not modelled.)
    pub fn sapphire() -> Material {
        SAPPHIRE.material()
    }
    /// Borosilicate crown glass (SCHOTT N-BK7), n_D ≈ 1.5168.
    pub fn glass() -> Material {
        GLASS.material()
    }

    /// Every material of the table, in order of rising n_D.
    pub fn table() -> Vec<Material> {
        TABLE.iter().map(Entry::material).collect()
    }

    /// The other names a table material answers to (`cz` for `cubic-zirconia`, …).
    pub fn aliases(&self) -> &'static [&'static str] {
        TABLE
            .iter()
            .find(|e| e.name == self.name)
            .map_or(&[], |e| e.aliases)
    }

    /// Names accepted by [`Material::by_name`] (besides aliases and `ri:N[:BG]`), the table's
    /// order.
    pub const NAMES: &'static [&'static str] = &[
        "glass",
        "quartz",
        "beryl",
        "topaz",
        "lead-glass",
        "tourmaline",
        "peridot",
        "spinel",
        "grossular",
        "pyrope",
        "sapphire",
        "almandine",
        "yag",
        "zircon",
        "ggg",
        "cubic-zirconia",
        "strontium-titanate",
        "diamond",
        "moissanite",
    ];

    #[cfg(test)]
    fn quartz_formula_for_test() -> String {
        QUARTZ.material().formula()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    /// Handbook n_D and B–G (GIA Gem Reference Guide; glasses: SCHOTT's n_d and v_d are
    /// checked separately), with the tolerance each source fits: (name, n_D, ±, B–G, ±).
    const HANDBOOK: &[(&str, f64, f64, f64, f64)] = &[
        ("quartz", 1.544, 0.003, 0.013, 0.0013), // n_ω 1.544, B–G 0.013
        ("beryl", 1.583, 0.003, 0.014, 0.0014),  // n_ω 1.583 (1.577–1.583), 0.014
        ("topaz", 1.619, 0.003, 0.014, 0.0014),  // n_α 1.619, 0.014
        ("tourmaline", 1.644, 0.003, 0.017, 0.0017), // n_ω 1.644 (1.624–1.644), 0.017
        ("peridot", 1.654, 0.003, 0.020, 0.002), // n_α 1.654, 0.020
        ("spinel", 1.718, 0.003, 0.020, 0.002),  // 1.718, 0.020
        ("grossular", 1.740, 0.003, 0.028, 0.0028), // 1.740, 0.028
        ("pyrope", 1.746, 0.003, 0.022, 0.0022), // 1.746, 0.022
        ("sapphire", 1.768, 0.003, 0.018, 0.0018), // n_ω 1.768–1.770, 0.018
        ("almandine", 1.790, 0.003, 0.024, 0.0024), // 1.790, 0.024
        ("yag", 1.833, 0.003, 0.028, 0.0028),    // 1.833, 0.028
        ("zircon", 1.925, 0.003, 0.039, 0.0039), // n_ω 1.925, 0.039
        ("ggg", 1.970, 0.003, 0.045, 0.0045),    // 1.970, 0.045
        ("cubic-zirconia", 2.165, 0.015, 0.060, 0.003), // 2.15–2.18 with the stabiliser, 0.060
        ("strontium-titanate", 2.409, 0.003, 0.190, 0.019), // 2.409, 0.190
        ("diamond", 2.417, 0.003, 0.044, 0.003), // 2.417, 0.044
        ("moissanite", 2.648, 0.003, 0.104, 0.0104), // n_ω 2.648, 0.104 (formula: 0.111)
    ];

    #[test]
    fn every_material_matches_its_handbook_values() {
        let table = Material::table();
        for (name, nd, nd_tol, bg, bg_tol) in HANDBOOK {
            let m = Material::by_name(name).unwrap();
            assert!(
                (m.ri_d() - nd).abs() <= *nd_tol,
                "{name}: n_D {} vs handbook {nd}",
                m.ri_d()
            );
            assert!(
                (m.bg_dispersion() - bg).abs() <= *bg_tol,
                "{name}: B–G {} vs handbook {bg}",
                m.bg_dispersion()
            );
            assert!(table.iter().any(|t| t.name == *name), "{name}");
        }
        // Every table entry is checked: here or (the glasses) below.
        for m in &table {
            assert!(
                HANDBOOK.iter().any(|h| h.0 == m.name) || m.name.contains("glass"),
                "{} has no handbook test",
                m.name
            );
        }
        // Cubic zirconia: Wood & Nassau's own n_D.
        assert!((Material::cubic_zirconia().ri_d() - 2.1585).abs() < 3e-4);
    }

    /// The uniaxial stones' extraordinary index at the D line against the handbook's n_ε
    /// (sapphire 1.760, quartz 1.553, beryl 1.577, tourmaline 1.624, zircon 1.984,
    /// moissanite 2.691 (4H-SiC's formula: 2.699)), the sign of the birefringence, and the
    /// optic axis cutters give each.
    #[test]
    fn uniaxial_stones_have_their_handbook_extraordinary_index() {
        for (name, ne, tol, axis) in [
            ("sapphire", 1.760, 0.002, 0.0),
            ("quartz", 1.553, 0.001, 0.0),
            ("beryl", 1.577, 1e-9, 0.0),
            ("tourmaline", 1.624, 1e-9, 90.0),
            ("zircon", 1.984, 1e-9, 0.0),
            ("moissanite", 2.691, 0.01, 0.0),
        ] {
            let m = Material::by_name(name).unwrap();
            let u = m.uniaxial.as_ref().expect(name);
            assert!(
                (m.ri_e(LINE_D) - ne).abs() <= tol,
                "{name}: {}",
                m.ri_e(LINE_D)
            );
            assert!(u.traced && u.axis.tilt_deg == axis, "{name}");
            assert!(m.birefringent() && !u.source.is_empty());
            // Dispersion: the index falls with wavelength.
            assert!(m.ri_e(430.8) > m.ri_e(686.7), "{name}");
        }
        // Negative (ω > ε) and positive stones.
        for (name, negative) in [
            ("sapphire", true),
            ("quartz", false),
            ("zircon", false),
            ("tourmaline", true),
        ] {
            let m = Material::by_name(name).unwrap();
            assert_eq!(m.ri(LINE_D) > m.ri_e(LINE_D), negative, "{name}");
        }
        for name in ["diamond", "spinel", "topaz", "peridot", "glass"] {
            assert!(
                Material::by_name(name).unwrap().uniaxial.is_none(),
                "{name}"
            );
        }
    }

    const LINE_D: f64 = 589.3;

    #[test]
    fn glasses_match_schott_nd_and_abbe_number() {
        // SCHOTT: N-BK7 n_d 1.5168, v_d 64.17; F2 n_d 1.62004, v_d 36.37 (d 587.56 nm,
        // F 486.13 nm, C 656.27 nm).
        for (name, nd, vd) in [("glass", 1.5168, 64.17), ("lead-glass", 1.62004, 36.37)] {
            let m = Material::by_name(name).unwrap();
            let n_d = m.ri(587.56);
            let v_d = (n_d - 1.0) / (m.ri(486.13) - m.ri(656.27));
            assert!((n_d - nd).abs() < 2e-4, "{name}: n_d {n_d}");
            assert!((v_d - vd).abs() < 0.3, "{name}: v_d {v_d}");
        }
    }

    #[test]
    fn table_order_names_aliases_and_listing_fields() {
        let table = Material::table();
        let names: Vec<&str> = table.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, Material::NAMES);
        for w in table.windows(2) {
            assert!(w[0].ri_d() < w[1].ri_d(), "{} {}", w[0].name, w[1].name);
        }
        for m in &table {
            assert!(
                !m.source.is_empty() && !m.formula().is_empty(),
                "{}",
                m.name
            );
            assert!(m.density > 2.0 && m.density < 8.0, "{}", m.name);
            for a in m.aliases() {
                assert_eq!(Material::by_name(a).unwrap().name, m.name);
            }
            // Handbook fits say so.
            if matches!(m.dispersion, Dispersion::Cauchy { .. }) {
                assert!(m.source.contains("Cauchy fitted to handbook"), "{}", m.name);
            }
        }
        for (n, ray) in [
            ("quartz", Optic::OrdinaryRay),
            ("tourmaline", Optic::OrdinaryRay),
            ("sapphire", Optic::OrdinaryRay),
            ("moissanite", Optic::OrdinaryRay),
            ("zircon", Optic::OrdinaryRay),
            ("topaz", Optic::BiaxialAlpha),
            ("spinel", Optic::Isotropic),
        ] {
            assert_eq!(Material::by_name(n).unwrap().optic, ray, "{n}");
        }
        assert_eq!(Material::by_name("CZ").unwrap().name, "cubic-zirconia");
        assert_eq!(Material::by_name("bk7").unwrap().name, "glass");
        assert_eq!(Material::sapphire().name, "sapphire");
        // Diamond's formula is the thesis's, bit for bit.
        assert_eq!(
            Material::diamond().dispersion,
            Dispersion::Sellmeier(vec![(0.3306, 0.175 * 0.175), (4.3356, 0.106 * 0.106)])
        );
        assert_eq!(
            Material::quartz_formula_for_test(),
            "Sellmeier n² = 1 + 0.28604141 + 1.07044083λ²/(λ² − 0.0100585997) + 1.10202242λ²/(λ² − 100), λ in µm"
        );
    }

    #[test]
    fn index_falls_with_wavelength() {
        let mut all = Material::table();
        all.push(Material::by_name("ri:1.54").unwrap());
        for m in all {
            let mut prev = f64::INFINITY;
            for l in (380..=780).step_by(10) {
                let n = m.ri(l as f64);
                assert!(n < prev && n > 1.0, "{} at {l}", m.name);
                prev = n;
            }
        }
    }
}
