//! Proportions no cutter would cut, measured as GemCad's ratios ([`super::Ratios`]): a stone
//! deeper than it is wide (H/W over 1: its face-up size falls far below its weight, and its
//! depth leaks light back out of the pavilion) or so shallow it is a slab (H/W under 0.3), and
//! a table that is nearly the whole crown (T/W over 0.85: no crown left to refract light into
//! fire). A design retargeted to another index can land there (a quartz design made for
//! sapphire by tangent ratios deepens its pavilion); `facetlab retarget` says so.

use super::Cut;
use serde::Serialize;

/// Allowed total height over width, H/W.
pub const DEPTH: [f64; 2] = [0.3, 1.0];
/// Largest table over width, T/W (a cut without a table is not judged by it).
pub const MAX_TABLE: f64 = 0.85;

/// One proportion outside its plausible range.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Implausible {
    /// `total_depth` (H/W) or `table` (T/W).
    pub name: &'static str,
    /// Its value, over the width W.
    pub value: f64,
    /// The plausible range, over W.
    pub range: [f64; 2],
}

impl std::fmt::Display for Implausible {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let what = match self.name {
            "total_depth" => "total depth (H/W)",
            _ => "table (T/W)",
        };
        let side = if self.value > self.range[1] {
            format!("over {:.0} %", 100.0 * self.range[1])
        } else {
            format!("under {:.0} %", 100.0 * self.range[0])
        };
        write!(
            f,
            "{what} {:.1} % of the width is {side}: not a stone a cutter would cut",
            100.0 * self.value
        )
    }
}

/// The proportions of `cut` outside the plausible ranges of the [module documentation](self),
/// empty when it is plausible.
///
/// ```
/// use facetlab::cut::{plausible::implausible, Cut};
///
/// let round = Cut::from_family("r", "round-brilliant", &Default::default()).unwrap();
/// assert!(implausible(&round).is_empty());
/// let mut deep = std::collections::BTreeMap::new();
/// deep.insert("pavilion_angle".to_string(), 60.0);
/// let deep = Cut::from_family("d", "round-brilliant", &deep).unwrap();
/// assert_eq!(implausible(&deep)[0].name, "total_depth");
/// ```
pub fn implausible(cut: &Cut) -> Vec<Implausible> {
    let r = cut.ratios();
    let mut out = Vec::new();
    if !(DEPTH[0]..=DEPTH[1]).contains(&r.h_w) {
        out.push(Implausible {
            name: "total_depth",
            value: r.h_w,
            range: DEPTH,
        });
    }
    if r.t_w > MAX_TABLE {
        out.push(Implausible {
            name: "table",
            value: r.t_w,
            range: [0.0, MAX_TABLE],
        });
    }
    out
}
