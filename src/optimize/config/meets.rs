//! A design's free keys against its meets and its facets, before a search: which meets the
//! free tier angles (and ties) cannot keep, refused (naming the key, the meet and the smallest
//! tie that keeps it) unless `[cut] open_meets = "allow"`; and where, along each free range,
//! the design stops being itself (a facet vanishes, an edge appears or vanishes), refused
//! with the angle and the range that holds.

use super::fields::At;
use super::free::FreeParam;
use crate::cut::CutSpace;
use crate::design::{DesignSpace, OpenMeets, OpenedMeet, Tie, TieKind};
use crate::error::{Error, Result};
use std::collections::BTreeMap;

/// What lists a design's meets (the command line's `facetlab info DESIGN --meets`), named in
/// an opened meet's error for each face to spell ([`crate::error::setting`]).
pub const MEETS_LISTING: &str = "info with meets";

/// The meets `free` cannot keep: an error naming the first key that opens one when the design
/// refuses open meets, else the list (for the report). Then the walk of each free range
/// ([`DesignSpace::breaches`]): an error at the first value where the design changes.
pub(super) fn check(
    d: &DesignSpace,
    free: &[FreeParam],
    start: &BTreeMap<String, f64>,
    skip_changes: bool,
    at: At,
) -> Result<Vec<OpenedMeet>> {
    // Each tier in one free key.
    let mut owner: BTreeMap<&str, &str> = BTreeMap::new();
    for f in free {
        for t in d.tiers_of(&f.key)? {
            if let Some(other) = owner.insert(t, &f.key) {
                return Err(Error::invalid(
                    at(&format!("free.{}", super::cut::quoted(&f.key))),
                    format!("tier {t} is also free in `{other}`; free each tier in one key"),
                ));
            }
        }
    }
    let bounds: Vec<(String, f64, f64)> =
        free.iter().map(|f| (f.key.clone(), f.lo, f.hi)).collect();
    let opened = d
        .unkeepable(&bounds)
        .map_err(|e| Error::invalid(at("free"), format!("{}: {e}", d.name())))?;
    if d.open_meets() == OpenMeets::Refuse && !opened.is_empty() {
        return Err(refusal(d, free, &opened, at));
    }
    let breaches = if skip_changes {
        Vec::new()
    } else {
        d.breaches(&bounds, start)
    };
    if let Some(b) = breaches.first() {
        let together = Tie::parse(&b.key).is_some_and(|t| t.kind == TieKind::Together)
            && d.keys().iter().all(|k| *k != b.key);
        let deg = |v: f64| {
            if together {
                format!("{v:+.2}°")
            } else {
                format!("{v:.2}°")
            }
        };
        let field = at(&format!("free.{}", super::cut::quoted(&b.key)));
        let message = if b.holds.0 == b.holds.1 {
            format!("at its start, {}, {}", deg(b.at), b.what)
        } else {
            format!(
                "at {} {}; the design holds from {} to {} (the other free keys at their start): narrow the bounds to that",
                deg(b.at),
                b.what,
                deg(b.holds.0),
                deg(b.holds.1)
            )
        };
        let also: Vec<String> = breaches[1..]
            .iter()
            .map(|o| {
                format!(
                    "{} at {:.2} (holds {:.2} to {:.2})",
                    o.key, o.at, o.holds.0, o.holds.1
                )
            })
            .collect();
        let also = if also.is_empty() {
            String::new()
        } else {
            format!("; also {}", also.join(", "))
        };
        return Err(Error::invalid(
            field,
            format!("{message}{also} (or `facet_changes = \"skip\"` in [cut] searches them, counting such points as failed)"),
        ));
    }
    Ok(opened)
}

/// The error of a config whose free keys open a meet: the first key that opens one alone,
/// the meet, and the smallest tie that keeps it ([`DesignSpace::tie_for`]) with its bounds.
fn refusal(d: &DesignSpace, free: &[FreeParam], opened: &[OpenedMeet], at: At) -> Error {
    let first = &opened[0];
    let (field, what, tie) = match first.by.first() {
        Some(key) => {
            let f = free.iter().find(|f| &f.key == key);
            // The bound farthest from the start: where the key opens the meet most.
            let tie = f.and_then(|f| {
                let far = if (f.hi - f.start).abs() >= (f.lo - f.start).abs() {
                    f.hi
                } else {
                    f.lo
                };
                let tie = d.tie_for(key, far)?;
                // As changes of angle: the key's own range less its start (a `+` tie's range
                // is one already).
                let shift = if Tie::parse(key).is_some_and(|t| t.kind == TieKind::Together)
                    && d.keys().iter().all(|k| k != key)
                {
                    0.0
                } else {
                    f.start
                };
                Some(format!(
                    "tie it: `{} = [{:.2}, {:.2}]` turns them by one change of angle and keeps every meet",
                    super::cut::quoted(&tie),
                    f.lo - shift,
                    f.hi - shift
                ))
            });
            (
                format!("free.{}", super::cut::quoted(key)),
                format!("turning {key} alone opens"),
                tie,
            )
        }
        None => (
            "free".to_string(),
            format!(
                "turning {} independently opens",
                free.iter()
                    .map(|f| f.key.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            None,
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
    let advice = tie.unwrap_or_else(|| "free the tiers that meet there too".to_string());
    Error::invalid(
        at(&field),
        format!(
            "{what} the meet {}{more}; {advice}, or set `open_meets = \"allow\"` in [cut] ({} lists the meets)",
            first.name,
            crate::error::setting(MEETS_LISTING)
        ),
    )
}
