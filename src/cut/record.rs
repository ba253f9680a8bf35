//! What a GemCad file says about itself beyond its facets: its metadata, carried on
//! [`super::Cut::record`] so that a design read from a `.asc` file is written back with its own
//! index, titles, notes, gear, symmetry and cutting instructions.
//!
//! Generated cuts have no GemCad record (`Cut::record` is `None`); a GemCad import always has
//! one. Writers fall back to their defaults (gear 96, `y 1 n`, the cut's name as the title,
//! no `I` line) for the fields a cut does not carry.

use serde::Serialize;
use std::collections::BTreeMap;

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
