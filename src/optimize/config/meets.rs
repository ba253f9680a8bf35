//! A design's meets against `[free]`: which meets the free tier angles cannot keep, refused
//! (naming the tier and the meet) unless `[cut] open_meets = "allow"`.

use super::{At, FreeParam};
use crate::cut::CutSpace;
use crate::design::{DesignSpace, OpenMeets, OpenedMeet};
use crate::error::{Error, Result};

/// The meets `free` cannot keep: an error naming the first tier that opens one when the design
/// refuses open meets, else the list (for the report).
pub(super) fn check(d: &DesignSpace, free: &[FreeParam], at: At) -> Result<Vec<OpenedMeet>> {
    let bounds: Vec<(String, f64, f64)> =
        free.iter().map(|f| (f.key.clone(), f.lo, f.hi)).collect();
    let opened = d
        .unkeepable(&bounds)
        .map_err(|e| Error::invalid(at("free"), format!("{}: {e}", d.name())))?;
    if d.open_meets() == OpenMeets::Allow || opened.is_empty() {
        return Ok(opened);
    }
    let first = &opened[0];
    let (field, what) = match first.by.first() {
        Some(tier) => (
            format!("free.{}", super::cut::quoted(tier)),
            format!("turning {tier} alone opens"),
        ),
        None => (
            "free".to_string(),
            format!(
                "turning {} independently opens",
                free.iter()
                    .map(|f| f.key.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ),
    };
    let more = match opened.len() {
        1 => String::new(),
        n => format!(
            " (and {} more meet{})",
            n - 1,
            if n == 2 { "" } else { "s" }
        ),
    };
    Err(Error::invalid(
        at(&field),
        format!(
            "{what} the meet {}{more}; free the tiers that meet there too, or set `open_meets = \"allow\"` in [cut] (`facetlab info DESIGN --meets` lists the meets)",
            first.name
        ),
    ))
}
