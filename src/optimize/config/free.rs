//! `[free]`: the parameters the optimizer varies, `key = [min, max]`.

use super::fields::At;
use crate::cut::{CutSpace, Unit};
use crate::error::{shown, Error, Result};
use std::collections::BTreeMap;

/// The free parameter that is not the cut's: a uniaxial stone's optic axis, degrees from the
/// table's normal toward the azimuth `[score] optic_axis` gives (0 by default).
pub const OPTIC_AXIS: &str = "optic_axis";

/// One free parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct FreeParam {
    /// Parameter key (of the config's cut space).
    pub key: String,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
    /// The start value (from `[cut.params]` or the space's default).
    pub start: f64,
    /// Unit (for labels).
    pub unit: Unit,
}

impl FreeParam {
    /// Position of `x` in the box, 0 at `lo`, 1 at `hi`.
    pub fn unit_of(&self, x: f64) -> f64 {
        (x - self.lo) / (self.hi - self.lo)
    }
    /// The value at box position `f` (0 → `lo`, 1 → `hi`).
    pub fn at(&self, f: f64) -> f64 {
        self.lo + (self.hi - self.lo) * f
    }
    /// Axis label: the key with its unit.
    pub fn label(&self) -> String {
        axis_label(&self.key, self.unit)
    }
}

/// An axis label for a parameter: `crown_angle (°)`, `table (× D)`.
pub fn axis_label(key: &str, unit: Unit) -> String {
    match unit {
        Unit::Degrees => format!("{key} (°)"),
        Unit::Fraction => format!("{key} (× girdle diameter)"),
        _ => key.to_string(),
    }
}

/// Validate `[free]` against the cut space and the start cut; the result is in the space's
/// parameter order.
pub(super) fn validate(
    raw: &BTreeMap<String, [f64; 2]>,
    space: &dyn CutSpace,
    start: &BTreeMap<String, f64>,
    given: &BTreeMap<String, f64>,
    at: At,
) -> Result<Vec<FreeParam>> {
    if raw.is_empty() {
        return Err(Error::invalid(
            at("free"),
            format!(
                "no free parameters; give at least one as `key = [min, max]`; {} has: {}",
                space.name(),
                space.keys().join(", ")
            ),
        ));
    }
    let mut free = Vec::new();
    // The space's own keys in its order, then any other key it knows (a design's tied tiers,
    // `P1+P2`), in the config's order.
    let own = space.keys();
    let others = raw
        .keys()
        .map(String::as_str)
        .filter(|k| !own.contains(k) && space.range(k).is_some());
    let order: Vec<&str> = own.iter().copied().chain(others).collect();
    for key in order {
        let Some(&[lo, hi]) = raw.get(key) else {
            continue;
        };
        let Some(def) = space.range(key) else {
            continue;
        };
        let field = at(&format!("free.{}", super::cut::quoted(key)));
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(Error::invalid(
                field,
                format!(
                    "bounds [{}, {}] must be finite numbers",
                    shown(lo),
                    shown(hi)
                ),
            ));
        }
        if lo > hi {
            return Err(Error::invalid(
                field,
                format!(
                    "bounds [{}, {}] are reversed; write [min, max]",
                    shown(lo),
                    shown(hi)
                ),
            ));
        }
        if lo == hi {
            return Err(Error::invalid(
                field,
                format!(
                    "bounds [{}, {}] are empty; fix the value in [cut.params] instead",
                    shown(lo),
                    shown(hi)
                ),
            ));
        }
        if def.unit == Unit::Count {
            return Err(Error::invalid(
                field,
                "a whole-number parameter cannot be optimized; fix it in [cut.params]",
            ));
        }
        let (l, r) = if def.open { ("(", ")") } else { ("[", "]") };
        if !(def.contains(lo) && def.contains(hi)) {
            return Err(Error::invalid(
                field,
                format!(
                    "bounds [{}, {}] leave the family's allowed range {l}{}, {}{r} {}",
                    shown(lo),
                    shown(hi),
                    def.min,
                    def.max,
                    def.unit.label()
                ),
            ));
        }
        let s = start.get(key).copied().unwrap_or(def.default);
        if !(lo..=hi).contains(&s) {
            let from = if given.contains_key(key) {
                "cut.params"
            } else {
                "the family default"
            };
            return Err(Error::invalid(
                field,
                format!("the start value {} (from {from}) lies outside the bounds [{}, {}]; widen them or set `{key}` in [cut.params]", shown(s), shown(lo), shown(hi)),
            ));
        }
        free.push(FreeParam {
            key: key.to_string(),
            lo,
            hi,
            start: s,
            unit: def.unit,
        });
    }
    if let Some(&[lo, hi]) = raw.get(OPTIC_AXIS) {
        let field = at("free.optic_axis");
        if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi && hi <= 90.0) {
            return Err(Error::invalid(
                field,
                format!("bounds [{lo}, {hi}] are not allowed; give [min, max] within [0, 90] degrees from the table's normal, min < max"),
            ));
        }
        free.push(FreeParam {
            key: OPTIC_AXIS.to_string(),
            lo,
            hi,
            // The material's own, set once the score section is read.
            start: lo,
            unit: Unit::Degrees,
        });
    }
    if let Some(k) = raw
        .keys()
        .find(|k| k.as_str() != OPTIC_AXIS && space.range(k).is_none())
    {
        return Err(Error::invalid(
            at(&format!("free.{k}")),
            format!(
                "unknown parameter of {}; allowed: {}",
                space.name(),
                space.keys().join(", ")
            ),
        ));
    }
    Ok(free)
}
