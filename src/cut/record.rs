//! What a GemCad file says about itself beyond its facets: its metadata, carried on
//! [`super::Cut::record`] so that a design read from a `.asc` file is written back with its own
//! index, titles, notes, gear, symmetry and cutting instructions.
//!
//! Generated cuts have no GemCad record (`Cut::record` is `None`); a GemCad import always has
//! one. A GemCad file of a generated cut gets the record [`GemcadRecord::for_file`] makes
//! (the one place every GemCad writer asks, `.asc` and binary `.gem` alike): the design's own
//! when it has one, else gear 96, the index of the material it is meant for, its name as the
//! title, and its real symmetry about the axis (`y 8 y` for a round brilliant), which GemCad
//! needs to cut a tier's facets together and to trace the stone in its material.

use super::Cut;
use crate::geometry::axial::axial_symmetry;
use serde::Serialize;
use std::collections::BTreeMap;

/// The index a generated cut's GemCad file gives when no material is named: diamond's n_D at
/// 589.3 nm (2.4173, from its Sellmeier formula; to three decimals, as designs for diamond
/// give it), the material every command traces by default.
pub const DIAMOND_RI: f64 = 2.417;

/// The gear a generated cut is written on.
pub const GENERATED_GEAR: u32 = 96;

/// A GemCad design's own record, as its file gave it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GemcadRecord {
    /// The refractive index the design was cut for (GemCad's `I` line), if given.
    pub ri: Option<f64>,
    /// Title and credit lines (`H`), in order.
    pub title: Vec<String>,
    /// Footnotes (`F`), in order.
    pub footnotes: Vec<String>,
    /// Index gear teeth (`g`); negative: the indices run clockwise.
    pub gear: f64,
    /// Gear offset: the index at 6 o'clock in the top view.
    pub gear_offset: f64,
    /// Rotational symmetry fold count (`y`).
    pub symmetry: u32,
    /// Mirror symmetry (`y … y`).
    pub mirror: bool,
    /// Cutting instructions (`G`), keyed by the name of the first facet of the line that
    /// carried them.
    pub instructions: BTreeMap<String, String>,
    /// Length of one cut unit in the file's units: a distance in the file is the cut's
    /// distance times this (imports are rescaled to the width convention of
    /// [`super::units`]; writing multiplies back so the file's own distances return).
    pub scale: f64,
}

impl Default for GemcadRecord {
    fn default() -> Self {
        GemcadRecord {
            ri: None,
            title: Vec::new(),
            footnotes: Vec::new(),
            gear: 96.0,
            gear_offset: 0.0,
            symmetry: 1,
            mirror: false,
            instructions: BTreeMap::new(),
            scale: 1.0,
        }
    }
}

impl GemcadRecord {
    /// The record a GemCad file of `cut` written on a gear of `gear` teeth (0: the design's
    /// own gear, else [`GENERATED_GEAR`]) carries: the cut's own record when it came from a
    /// design file (as read: its index, titles, notes, gear, symmetry, instructions), else
    /// [`GemcadRecord::generated`] for the index `ri` (the material the cut is meant for;
    /// [`DIAMOND_RI`] when none is named).
    pub fn for_file(cut: &Cut, gear: u32, ri: f64) -> GemcadRecord {
        match &cut.record {
            Some(r) => r.clone(),
            None => GemcadRecord::generated(cut, gear, ri),
        }
    }

    /// The record of a generated cut: gear `gear` (0: [`GENERATED_GEAR`]) with offset 0, the
    /// index `ri` (rounded to 4 decimals), the cut's name as its one title line, no notes, and
    /// its symmetry about the axis as GemCad writes it: the largest rotation order that both
    /// the solid has and the gear can index (a divisor of the teeth), and a mirror when one of
    /// the solid's mirror planes is GemCad's, the line through index 0 (azimuth ±90°, the
    /// vertical of GemCad's top view). A round brilliant is `y 8 y`, a princess `y 4 y`, an
    /// oval `y 2 y`, a pear `y 1 n` (its mirror is its long axis, along x).
    ///
    /// ```
    /// use facetlab::cut::{Cut, GemcadRecord};
    ///
    /// let round = Cut::from_family("r", "round-brilliant", &Default::default()).unwrap();
    /// let r = GemcadRecord::generated(&round, 0, 2.417);
    /// assert_eq!((r.gear, r.symmetry, r.mirror, r.ri), (96.0, 8, true, Some(2.417)));
    /// assert_eq!(r.title, vec!["r".to_string()]);
    /// ```
    pub fn generated(cut: &Cut, gear: u32, ri: f64) -> GemcadRecord {
        let teeth = if gear == 0 { GENERATED_GEAR } else { gear };
        let sym = axial_symmetry(&cut.solid, 1e-7);
        let symmetry = (1..=sym.order)
            .rev()
            .find(|k| sym.order.is_multiple_of(*k) && teeth.is_multiple_of(*k))
            .unwrap_or(1);
        let title = cut.name.split_whitespace().collect::<Vec<_>>().join(" ");
        GemcadRecord {
            ri: Some((ri * 1e4).round() / 1e4),
            title: if title.is_empty() {
                Vec::new()
            } else {
                vec![title]
            },
            gear: f64::from(teeth),
            gear_offset: 0.0,
            symmetry,
            mirror: sym.mirrors_at(std::f64::consts::FRAC_PI_2, 1e-6),
            ..GemcadRecord::default()
        }
    }
}
