//! Cut spaces: what the optimizer searches, whatever the cuts come from.
//!
//! A [`CutSpace`] names its parameters ([`CutSpace::keys`]), gives each one's default, allowed
//! range and unit ([`CutSpace::range`], a [`ParamRange`]), completes and checks a set of values
//! ([`CutSpace::complete`]) and builds the cut at a set of values ([`CutSpace::build`]). A
//! parametric [`Family`] is one; an imported design whose tier angles are free would be
//! another. The optimizer (its config, objective, sweeps, trade-offs and reports) reaches cuts
//! only through this trait.
//!
//! ```
//! use facetlab::cut::{family, CutSpace};
//! use std::collections::BTreeMap;
//!
//! let space: &dyn CutSpace = family("round-brilliant").unwrap();
//! let crown = space.range("crown_angle").unwrap();
//! assert!(crown.contains(34.5) && !crown.contains(75.0));
//! let cut = space
//!     .build("mine", &BTreeMap::from([("crown_angle".to_string(), 34.5)]))
//!     .unwrap();
//! assert_eq!(cut.params["crown_angle"], 34.5);
//! ```

use super::{Cut, Family, Unit};
use crate::error::Result;
use std::collections::BTreeMap;
use std::fmt;

/// What a cut space says of one parameter: its default, its allowed range and its unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamRange {
    /// Value when not given.
    pub default: f64,
    /// Smallest allowed value.
    pub min: f64,
    /// Largest allowed value.
    pub max: f64,
    /// Whether `min` and `max` themselves are excluded.
    pub open: bool,
    /// Unit.
    pub unit: Unit,
}

impl ParamRange {
    /// Whether `v` is allowed (inside the range, its ends excluded when it is open).
    pub fn contains(&self, v: f64) -> bool {
        if self.open {
            v > self.min && v < self.max
        } else {
            v >= self.min && v <= self.max
        }
    }
}

/// A space of cuts the optimizer can search: named parameters with ranges, and a builder.
///
/// `Send + Sync` because searches build cuts on several threads; `Debug` so configs that hold
/// one can be printed.
pub trait CutSpace: fmt::Debug + Send + Sync {
    /// The space's name in configs and reports (a family's name: `round-brilliant`).
    fn name(&self) -> &str;
    /// The parameter keys, in display order.
    fn keys(&self) -> Vec<&str>;
    /// The default, range and unit of parameter `key`; `None` if the space has no such key.
    fn range(&self, key: &str) -> Option<ParamRange>;
    /// Every parameter at `values`: defaults filled in, each value checked; unknown keys and
    /// out-of-range values are errors naming the key.
    fn complete(&self, values: &BTreeMap<String, f64>) -> Result<BTreeMap<String, f64>>;
    /// The cut called `name` at `values` (completed as by [`CutSpace::complete`]).
    fn build(&self, name: &str, values: &BTreeMap<String, f64>) -> Result<Cut>;
}

impl CutSpace for Family {
    fn name(&self) -> &str {
        self.name
    }

    fn keys(&self) -> Vec<&str> {
        Family::keys(self)
    }

    fn range(&self, key: &str) -> Option<ParamRange> {
        self.param(key).map(|p| ParamRange {
            default: p.default,
            min: p.min,
            max: p.max,
            open: p.open,
            unit: p.unit,
        })
    }

    fn complete(&self, values: &BTreeMap<String, f64>) -> Result<BTreeMap<String, f64>> {
        Ok(self.params(values)?.values().clone())
    }

    fn build(&self, name: &str, values: &BTreeMap<String, f64>) -> Result<Cut> {
        Cut::from_family(name, self.name, values)
    }
}
