//! A cut's facets grouped into tiers as a GemCad line lists them: one angle, one depth, the
//! facets' indices on an index gear.

use crate::cut::{Cut, GemcadRecord};
use crate::geometry::DVec3;

/// Decimals of a tier's angle as GemCad writes it (degrees).
pub const ANGLE_DECIMALS: usize = 6;

/// Decimals of a tier's depth as GemCad writes it.
pub const DEPTH_DECIMALS: usize = 8;

/// An index gear: where each facet azimuth sits as an index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gear {
    /// Teeth per turn; negative: the indices run clockwise.
    pub teeth: f64,
    /// The index at 6 o'clock in the top view.
    pub offset: f64,
}

impl Gear {
    /// The gear to lay `record`'s design on when `asked` teeth are asked for: the record's own
    /// gear and offset when `asked` is 0 or its tooth count, else `asked` teeth with offset 0.
    /// (A cut without a record has the default record's gear, 96 with offset 0.)
    pub fn for_record(record: &GemcadRecord, asked: u32) -> Gear {
        let (teeth, offset) = if asked == 0 || f64::from(asked) == record.gear.abs() {
            (record.gear, record.gear_offset)
        } else {
            (f64::from(asked), 0.0)
        };
        Gear { teeth, offset }
    }

    /// The index of a facet with outward normal `n`: `offset + teeth · (azimuth + 90°) / 360°`
    /// modulo the tooth count, an index 0 given as the tooth count; a flat facet (table or
    /// culet) at the offset.
    pub fn index(&self, n: DVec3) -> f64 {
        let (g, offset) = (self.teeth, self.offset);
        let teeth = g.abs();
        let h = n.x.hypot(n.y);
        if h <= 1e-12 {
            let i = offset.rem_euclid(teeth);
            if i == 0.0 {
                teeth
            } else {
                i
            }
        } else {
            let az = n.y.atan2(n.x).to_degrees();
            let i = (offset + g * (az + 90.0) / 360.0).rem_euclid(teeth);
            // Index 0 (within 1e-6 of a tooth either side) is written as the tooth count; a
            // fractional index just past it stays itself.
            if i < 1e-6 || teeth - i < 1e-6 {
                teeth
            } else {
                i
            }
        }
    }
}

/// One facet of a tier: its index on the gear and its name.
#[derive(Clone, Debug, PartialEq)]
pub struct TierFacet {
    /// Index on the gear (see [`Gear::index`]).
    pub index: f64,
    /// The facet's name on the cut.
    pub name: String,
}

/// A tier: one GemCad line. Its facets share a tier name, an angle and a depth.
#[derive(Clone, Debug, PartialEq)]
pub struct Tier {
    /// The facets' tier name as one GemCad word (see [`token`]); may be empty.
    pub name: String,
    /// Angle to the girdle plane in degrees, as GemCad writes it: positive crown (and table),
    /// negative pavilion, −90 girdle; a culet is 0 (with a negative depth).
    pub angle: f64,
    /// The facets' distance from the origin (the stone's axis point in the girdle plane) in
    /// the units asked for; negative for a culet, GemCad's way.
    pub depth: f64,
    /// The facets, in the cut's facet order.
    pub facets: Vec<TierFacet>,
}

/// A name as one GemCad word: whitespace runs become `_`.
pub fn token(name: &str) -> String {
    name.split_whitespace().collect::<Vec<_>>().join("_")
}

/// `x` with `decimals` decimals, never `-0` (`-0.00` is `0.00`).
pub fn fixed(x: f64, decimals: usize) -> String {
    let t = format!("{x:.decimals$}");
    if t.starts_with('-') && t.trim_start_matches(['-', '0', '.']).is_empty() {
        t[1..].to_string()
    } else {
        t
    }
}

/// The tiers of `cut` on `gear`, depths in `unit`s per cut length (a GemCad record's
/// [`GemcadRecord::scale`] gives its file's units), in order of first appearance.
///
/// Facets are one tier when their tier names are the same word ([`token`]) and their angles
/// and depths are written alike at GemCad's precision ([`ANGLE_DECIMALS`],
/// [`DEPTH_DECIMALS`]); the tier keeps its first facet's angle and depth.
///
/// ```
/// use facetlab::cut::GemcadRecord;
/// use facetlab::design::{tiers, Gear};
///
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// let gear = Gear::for_record(&GemcadRecord::default(), 96);
/// let t = tiers(&cut, gear, 1.0);
/// let bezel = t.iter().find(|t| t.name == "bezel").unwrap();
/// assert_eq!(bezel.facets.len(), 8);
/// assert!((bezel.angle - 34.5).abs() < 1e-9);
/// ```
pub fn tiers(cut: &Cut, gear: Gear, unit: f64) -> Vec<Tier> {
    let mut out: Vec<Tier> = Vec::new();
    // Each tier's angle and depth as written: the key facets are grouped by.
    let mut written: Vec<(String, String)> = Vec::new();
    for f in cut.solid.facets() {
        let n = f.plane.normal;
        let h = n.x.hypot(n.y);
        let tilt = h.atan2(n.z.abs()).to_degrees();
        let crown = n.z > 1e-12;
        let d = f.plane.offset * unit;
        let (angle, depth) = if h <= 1e-12 && !crown {
            (0.0, -d) // culet: `a 0 -d`
        } else if crown {
            (tilt, d)
        } else {
            (-tilt, d)
        };
        let facet = TierFacet {
            index: gear.index(n),
            name: f.name.clone(),
        };
        let key = (fixed(angle, ANGLE_DECIMALS), fixed(depth, DEPTH_DECIMALS));
        let name = token(&f.tier);
        match out
            .iter_mut()
            .zip(&written)
            .find(|(t, k)| t.name == name && **k == key)
        {
            Some((t, _)) => t.facets.push(facet),
            None => {
                out.push(Tier {
                    name,
                    angle,
                    depth,
                    facets: vec![facet],
                });
                written.push(key);
            }
        }
    }
    out
}
