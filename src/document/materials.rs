//! The materials document, as `facetlab materials --json` writes it: one row per material of
//! the table (`name`, `nd`, `dispersion`, `formula`, `source`, `ordinary_ray`, `optic`,
//! `density`, `aliases`), then the coloured varieties with `variety_of`, `chromophores` and
//! `colour` (`{source, seen_through_mm, hex, lab}`, or null with `no_spectrum` saying why), and
//! for a uniaxial host `colour_e`, the E ∥ c (extraordinary ray's) colour in the same form, or
//! null with `no_spectrum_e` saying why.

use crate::optics::{Material, Variety};
use serde::Serialize;

/// One material as listed; `dispersion` is the B–G dispersion n(430.8 nm) − n(686.7 nm).
#[derive(Debug, Serialize)]
pub struct Row {
    /// Its name (what `--material` takes).
    pub name: String,
    /// Refractive index at 589.3 nm.
    pub nd: f64,
    /// B–G dispersion n(430.8 nm) − n(686.7 nm).
    pub dispersion: f64,
    /// Whether the index listed is a uniaxial stone's ordinary ray.
    pub ordinary_ray: bool,
    /// Isotropic, uniaxial or biaxial, and the index traced.
    pub optic: &'static str,
    /// Handbook density (specific gravity), for carat weights.
    pub density: f64,
    /// Other names it is known by.
    pub aliases: &'static [&'static str],
    /// Its dispersion formula.
    pub formula: String,
    /// Where its data come from.
    pub source: String,
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    /// A coloured variety's additions.
    pub variety: Option<VarietyRow>,
}

/// What a coloured variety adds to its host's row.
#[derive(Debug, Serialize)]
pub struct VarietyRow {
    /// The host material.
    pub variety_of: &'static str,
    /// What colours it.
    pub chromophores: &'static str,
    /// Its published colour, if a spectrum was found.
    pub colour: Option<ColourRow>,
    #[serde(skip_serializing_if = "str::is_empty")]
    /// Why it has no spectrum (empty when it has one).
    pub no_spectrum: &'static str,
    /// A uniaxial variety's published E ∥ c colour (`Some(None)`: none found); `None` for a
    /// variety that is not uniaxial.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour_e: Option<Option<ColourRow>>,
    #[serde(skip_serializing_if = "str::is_empty")]
    /// Why a uniaxial variety has no E ∥ c spectrum (empty otherwise).
    pub no_spectrum_e: &'static str,
}

/// A published body colour: its source and the colour seen through [`SEEN_MM`].
#[derive(Debug, Serialize)]
pub struct ColourRow {
    /// Where its data come from.
    pub source: String,
    /// The path the colour is seen through, mm.
    pub seen_through_mm: f64,
    /// The colour as #rrggbb.
    pub hex: String,
    /// The colour as CIELAB L*, a*, b*.
    pub lab: [f64; 3],
}

impl ColourRow {
    /// A body colour's row: its source and its colour through [`SEEN_MM`].
    fn of(c: &crate::optics::BodyColour) -> ColourRow {
        let lab = c.lab_through(SEEN_MM);
        ColourRow {
            source: c.source.clone(),
            seen_through_mm: SEEN_MM,
            hex: c.hex_through(SEEN_MM),
            lab: [lab.x, lab.y, lab.z].map(|x| (x * 100.0).round() / 100.0),
        }
    }
}

/// The path the listing shows each variety's colour through, mm.
pub const SEEN_MM: f64 = 5.0;

/// Every material of the table, then every coloured variety.
pub fn rows() -> Vec<Row> {
    let varieties = Variety::all().iter().map(|v| (v.material(), Some(v)));
    Material::table()
        .into_iter()
        .map(|m| (m, None))
        .chain(varieties)
        .map(|(m, v): (Material, Option<&Variety>)| Row {
            variety: v.map(|v| VarietyRow {
                variety_of: v.host,
                chromophores: v.chromophores,
                colour: m.colour.as_ref().map(ColourRow::of),
                no_spectrum: v.missing,
                colour_e: m
                    .uniaxial
                    .as_ref()
                    .map(|u| u.colour_e.as_ref().map(ColourRow::of)),
                no_spectrum_e: v.missing_e,
            }),
            nd: m.ri_d(),
            dispersion: m.bg_dispersion(),
            ordinary_ray: m.optic.ordinary_ray(),
            optic: m.optic.label(),
            density: m.density,
            aliases: m.aliases(),
            formula: m.formula(),
            source: m.source.clone(),
            name: m.name,
        })
        .collect()
}
