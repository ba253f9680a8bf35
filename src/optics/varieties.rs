//! Coloured varieties: a host material of the table (`table.rs`) with the absorption spectrum
//! of a published measurement of one stone, or, where no spectrum was found, the host with a
//! note saying so (traced colourless; `--colour` gives it a colour).
//!
//! Every spectrum here is a polarized absorbance measurement of one named sample of the
//! Caltech Mineral Spectroscopy Server (G. R. Rossman, California Institute of Technology,
//! <http://minerals.gps.caltech.edu/>), the ray the model traces (uniaxial stones: E⊥c, the
//! ordinary ray ω; peridot: the α ray), turned into α per mm thus: decadic absorbance A(λ)
//! averaged over 10 nm bins centred on 380, 390, …, 780 nm; the bins' smallest absorbance
//! subtracted (the file's reflection loss and baseline offset are not separable from a flat
//! absorption, so the most transparent wavelength is taken as α = 0 and the spectrum is a lower
//! bound there); α = ln 10 · A / thickness. Each is one stone: `--colour-density` makes it
//! paler or darker.

use super::body_colour::{BodyColour, SAMPLES};
use super::material::Material;
use super::table::TABLE;

/// A published spectrum: α per mm at 380, 390, …, 780 nm and where it is from.
struct Spectrum {
    alpha: [f64; SAMPLES],
    source: &'static str,
}

/// A coloured variety of a table material.
pub struct Variety {
    /// Name on the command line (`--material ruby`).
    pub name: &'static str,
    /// The table material it is (its index, dispersion and density).
    pub host: &'static str,
    /// What colours it, with the band positions the literature gives.
    pub chromophores: &'static str,
    spectrum: Option<Spectrum>,
    /// Why there is no spectrum, when there is none: the sources checked.
    pub missing: &'static str,
}

/// Why no variety has its E ∥ c spectrum (pleochroism): the polarized companions of the
/// spectra above are not reachable from where this was built.
pub const MISSING_E: &str = "no E∥c spectrum: the polarized companion files of the Caltech samples could not be reached from where facetlab was built (its stored copies of the server hold the index pages, not the data), and no other source of E∥c absorption coefficients of the same stones was found; the extraordinary ray takes the E⊥c spectrum (no pleochroism) unless the crystal settings give an E∥c colour";

/// Ruby: Caltech GRR 1843, Chanthaburi, Thailand, 0.787 mm, E⊥c (file ru1843.a); Cr³⁺
/// ⁴A₂→⁴T₁ at 410 nm and ⁴A₂→⁴T₂ at 560 nm, the R lines at 692–694 nm.
const RUBY: [f64; SAMPLES] = [
    2.752, 3.432, 4.071, 4.497, 4.401, 3.632, 2.474, 1.559, 0.9911, 0.5782, 0.4273, 0.4999, 0.7884,
    1.257, 1.875, 2.581, 3.273, 3.817, 4.055, 3.861, 3.227, 2.291, 1.331, 0.6711, 0.3325, 0.1759,
    0.1069, 0.07751, 0.09335, 0.09119, 0.05833, 0.1462, 0.08024, 0.05289, 0.04258, 0.03545,
    0.02843, 0.02165, 0.01276, 0.004774, 0.0,
];

/// Blue sapphire: Caltech GRR 1020a, medium blue, locality unknown (Australia?), 4.289 mm
/// (the file's header; the server's index says normalised to 3.00 mm, unresolved), E⊥c (file
/// sa1020a.am); Fe³⁺ 377/388/450 nm, Fe²⁺–Ti⁴⁺ charge transfer near 580 nm, Fe²⁺–Fe³⁺ near
/// 870 nm.
#[allow(clippy::approx_constant)] // 0.3927 per mm at 610 nm is a measurement, not π/8
const BLUE_SAPPHIRE: [f64; SAMPLES] = [
    0.4841, 0.4177, 0.1122, 0.01171, 0.0, 0.01725, 0.08564, 0.1971, 0.1607, 0.09688, 0.06211,
    0.07184, 0.1079, 0.1525, 0.2001, 0.2462, 0.2882, 0.3246, 0.3529, 0.3729, 0.3849, 0.3906,
    0.3922, 0.3927, 0.3942, 0.3974, 0.4037, 0.4136, 0.4268, 0.4439, 0.4642, 0.4877, 0.5145, 0.545,
    0.5798, 0.618, 0.6597, 0.7042, 0.7527, 0.8021, 0.8409,
];

/// Emerald: Caltech GRR 3570, Afghanistan, 0.859 mm, E⊥c (file Emerald_3570_a.asc); Cr³⁺
/// bands near 430 and 605 nm.
const EMERALD: [f64; SAMPLES] = [
    0.4519, 0.5526, 0.7662, 1.018, 1.268, 1.431, 1.422, 1.271, 1.011, 0.7152, 0.4635, 0.2524, 0.14,
    0.1085, 0.1273, 0.181, 0.2716, 0.4038, 0.5735, 0.7689, 0.9694, 1.148, 1.26, 1.262, 1.148,
    0.9918, 0.8907, 0.6929, 0.5326, 0.4071, 0.3487, 0.2227, 0.1212, 0.06334, 0.03001, 0.01242,
    0.005127, 0.001039, 0.0, 0.000201, 0.001354,
];

/// Amethyst: Caltech sample ameth.bo, Anahí, Bolivia, unheated, 6.17 mm, slab ⊥ c (the
/// ordinary ray); the Fe colour-centre band near 545 nm and the rise to 357 nm.
const AMETHYST: [f64; SAMPLES] = [
    0.1189, 0.1053, 0.09097, 0.07749, 0.06243, 0.04764, 0.03777, 0.03463, 0.03644, 0.04142,
    0.04857, 0.05667, 0.06417, 0.07124, 0.07617, 0.0797, 0.08087, 0.07998, 0.07685, 0.07221,
    0.06572, 0.0594, 0.05247, 0.04561, 0.03967, 0.03381, 0.02818, 0.0226, 0.01803, 0.01445,
    0.01095, 0.007759, 0.005406, 0.005182, 0.002635, 0.0, 0.001093, 0.0006857, 0.0003303,
    0.0004712, 0.0009236,
];

/// Peridot: Caltech GRR 418, forsterite, San Carlos, Arizona, 1.141 mm, α ray (file ol418.a);
/// Fe²⁺ bands near 450–490 nm, 640 nm and the M1/M2 bands from 800 nm into the infrared.
const PERIDOT: [f64; SAMPLES] = [
    0.4603, 0.4222, 0.4053, 0.3186, 0.2696, 0.2393, 0.2181, 0.2205, 0.1952, 0.1638, 0.1322, 0.118,
    0.08907, 0.0653, 0.04947, 0.03077, 0.01433, 0.00451, 0.0, 0.0001993, 0.004185, 0.01304,
    0.02367, 0.04305, 0.06592, 0.08573, 0.09217, 0.08613, 0.08078, 0.07906, 0.08502, 0.1, 0.1229,
    0.1514, 0.1829, 0.222, 0.2731, 0.3297, 0.393, 0.4657, 0.5228,
];

/// The varieties, in the order `facetlab materials` lists them.
pub(super) const VARIETIES: &[Variety] = &[
    Variety {
        name: "amethyst",
        host: "quartz",
        chromophores: "Fe colour centres (band near 545 nm, rise to 357 nm; G. Lehmann, W. J. Moore, Science 152, 1061 (1966))",
        spectrum: Some(Spectrum {
            alpha: AMETHYST,
            source: "Caltech Mineral Spectroscopy Server (G. R. Rossman), amethyst ameth.bo, Anahí, Bolivia, unheated, 6.17 mm, o-ray",
        }),
        missing: "",
    },
    Variety {
        name: "citrine",
        host: "quartz",
        chromophores: "Fe³⁺ charge transfer: an absorption edge rising into the violet, no visible band",
        spectrum: None,
        missing: "no published absorption coefficients found (checked: Caltech server listings, G&G, Am. Mineral. abstracts); the only tabulated curve seen was a secondary, unverified one",
    },
    Variety {
        name: "aquamarine",
        host: "beryl",
        chromophores: "Fe²⁺ at 820 nm (E⊥c) and 970 nm, Fe²⁺–Fe³⁺ near 700 nm (E∥c) (K. Goldman, G. R. Rossman, K. M. Parkin, Phys. Chem. Minerals 3, 225–235 (1978))",
        spectrum: None,
        missing: "band positions published; no absorption coefficients of a measured stone found in the sources checked",
    },
    Variety {
        name: "emerald",
        host: "beryl",
        chromophores: "Cr³⁺ (bands near 430 and 605 nm, lines at 680–683 nm)",
        spectrum: Some(Spectrum {
            alpha: EMERALD,
            source: "Caltech Mineral Spectroscopy Server (G. R. Rossman), emerald GRR 3570, Afghanistan, 0.859 mm, E⊥c",
        }),
        missing: "",
    },
    Variety {
        name: "peridot",
        host: "peridot",
        chromophores: "Fe²⁺ in the M1 and M2 sites (bands near 1050 and 650 nm, spin-forbidden bands 450–495 nm)",
        spectrum: Some(Spectrum {
            alpha: PERIDOT,
            source: "Caltech Mineral Spectroscopy Server (G. R. Rossman), forsterite GRR 418, San Carlos, Arizona, 1.141 mm, α ray",
        }),
        missing: "",
    },
    Variety {
        name: "green-tourmaline",
        host: "tourmaline",
        chromophores: "Fe²⁺ (700 and 1100 nm), intensified by Fe²⁺–Fe³⁺ pairs in E⊥c (S. M. Mattson, G. R. Rossman, Phys. Chem. Minerals 14, 163–171 (1987))",
        spectrum: None,
        missing: "band positions published; no absorption coefficients of a measured stone found in the sources checked",
    },
    Variety {
        name: "pink-tourmaline",
        host: "tourmaline",
        chromophores: "Mn³⁺ band at 19 000 cm⁻¹ (520 nm), strongest in E⊥c (P. G. Manning, Can. Mineral. 9, 678 (1969))",
        spectrum: None,
        missing: "band position published; no absorption coefficients or band width found in the sources checked",
    },
    Variety {
        name: "blue-sapphire",
        host: "sapphire",
        chromophores: "Fe²⁺–Ti⁴⁺ charge transfer near 580 nm, Fe²⁺–Fe³⁺ near 870 nm, Fe³⁺ lines at 377, 388 and 450 nm",
        spectrum: Some(Spectrum {
            alpha: BLUE_SAPPHIRE,
            source: "Caltech Mineral Spectroscopy Server (G. R. Rossman), blue sapphire GRR 1020a, 4.289 mm, E⊥c",
        }),
        missing: "",
    },
    Variety {
        name: "ruby",
        host: "sapphire",
        chromophores: "Cr³⁺ ⁴A₂→⁴T₁ (410 nm) and ⁴A₂→⁴T₂ (560 nm), R lines 692–694 nm",
        spectrum: Some(Spectrum {
            alpha: RUBY,
            source: "Caltech Mineral Spectroscopy Server (G. R. Rossman), ruby GRR 1843, Chanthaburi, Thailand, 0.787 mm, E⊥c",
        }),
        missing: "",
    },
    Variety {
        name: "almandine",
        host: "almandine",
        chromophores: "Fe²⁺ spin-forbidden bands 14 000–25 000 cm⁻¹ (505, 527, 576 nm) (C. A. Geiger, M. N. Taran, G. R. Rossman, Am. Mineral. 108, 1149–1160 (2023)); also rhodolite",
        spectrum: None,
        missing: "band positions published; no absorption coefficients of a measured stone found in the sources checked",
    },
    Variety {
        name: "tsavorite",
        host: "grossular",
        chromophores: "V³⁺ and Cr³⁺ bands near 430 and 605 nm (Crystals 12, 1677 (2022))",
        spectrum: None,
        missing: "band positions published; no absorption coefficients of a measured stone found in the sources checked",
    },
];

impl Variety {
    /// Every variety, in listing order.
    pub fn all() -> &'static [Variety] {
        VARIETIES
    }

    /// A variety by name (case as given is ignored).
    pub fn by_name(name: &str) -> Option<&'static Variety> {
        let key = name.trim().to_ascii_lowercase();
        VARIETIES.iter().find(|v| v.name == key)
    }

    /// Its published body colour, or `None` where no spectrum was found.
    pub fn body_colour(&self) -> Option<BodyColour> {
        self.spectrum.as_ref().map(|s| BodyColour {
            name: self.name.into(),
            alpha_per_mm: s.alpha.to_vec(),
            density: 1.0,
            source: s.source.into(),
        })
    }

    /// The host material named after the variety, with its body colour (colourless where no
    /// spectrum was found).
    pub fn material(&self) -> Material {
        let mut m = TABLE
            .iter()
            .find(|e| e.name == self.host)
            .map(|e| e.material())
            .unwrap_or_else(Material::diamond);
        m.name = self.name.into();
        m.colour = self.body_colour();
        // No variety has an E ∥ c spectrum here (see MISSING_E): `colour_e` stays `None`,
        // the extraordinary ray taking the one spectrum.
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::color::chroma;

    /// The published spectra give the colours the stones are known by (hue angle h° of
    /// CIELAB through 5 mm) and stay within what was measured.
    #[test]
    fn published_spectra_have_their_stones_hues() {
        let hue = |name: &str| {
            let c = Variety::by_name(name).unwrap().body_colour().unwrap();
            let lab = c.lab_through(5.0);
            assert!(chroma(lab) > 5.0, "{name}: {lab}");
            (lab.z.atan2(lab.y).to_degrees() + 360.0) % 360.0
        };
        let ruby = hue("ruby");
        assert!(!(60.0..=300.0).contains(&ruby), "ruby {ruby}"); // red to purplish red
        let emerald = hue("emerald");
        assert!((120.0..200.0).contains(&emerald), "emerald {emerald}");
        let peridot = hue("peridot");
        assert!((90.0..140.0).contains(&peridot), "peridot {peridot}"); // yellowish green
        let sapphire = hue("blue-sapphire");
        assert!(
            (220.0..300.0).contains(&sapphire),
            "blue sapphire {sapphire}"
        );
        let amethyst = hue("amethyst");
        assert!((280.0..345.0).contains(&amethyst), "amethyst {amethyst}");
        for v in Variety::all() {
            assert!(
                crate::optics::Material::NAMES.contains(&v.host),
                "{}",
                v.name
            );
            match v.body_colour() {
                Some(c) => {
                    assert!(c.alpha_per_mm.iter().all(|a| (0.0..6.0).contains(a)));
                    assert!(c.alpha_per_mm.contains(&0.0), "{}: baseline", v.name);
                    assert!(v.missing.is_empty() && c.source.contains("Caltech"));
                }
                None => assert!(!v.missing.is_empty(), "{}", v.name),
            }
            let m = v.material();
            assert_eq!(m.name, v.name);
            assert_eq!(m.colour.is_some(), v.body_colour().is_some());
        }
    }
}
