//! A family parameter: its unit, definition (key, default, range) and a validated set.

use crate::error::{shown, Error, Result};
use std::collections::BTreeMap;

/// The unit of a family parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// Degrees.
    Degrees,
    /// A length as a fraction of the girdle diameter (or of the named reference length).
    Fraction,
    /// A dimensionless ratio (length/width).
    Ratio,
    /// A whole number.
    Count,
}

impl Unit {
    /// Short label used in messages and tables.
    pub fn label(self) -> &'static str {
        match self {
            Unit::Degrees => "degrees",
            Unit::Fraction => "fraction of girdle diameter",
            Unit::Ratio => "ratio",
            Unit::Count => "count",
        }
    }
}

/// One parameter of a family.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamDef {
    /// Key in TOML specs and `--set`.
    pub key: &'static str,
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
    /// One-line meaning.
    pub doc: &'static str,
}

impl ParamDef {
    /// Check a value against this definition; the error names the key and the allowed range.
    pub fn check(&self, v: f64) -> Result<f64> {
        let range = if self.open {
            format!("({}, {})", self.min, self.max)
        } else {
            format!("[{}, {}]", self.min, self.max)
        };
        let hint = match self.unit {
            Unit::Fraction if v > 1.0 => {
                " (lengths are fractions of the girdle diameter: 0.57, not 57)"
            }
            _ => "",
        };
        if !v.is_finite() {
            return Err(Error::invalid(
                self.key,
                format!(
                    "{} is not a number; allowed {range} {}",
                    shown(v),
                    self.unit.label()
                ),
            ));
        }
        let inside = if self.open {
            v > self.min && v < self.max
        } else {
            v >= self.min && v <= self.max
        };
        if !inside {
            return Err(Error::invalid(
                self.key,
                format!(
                    "{} is out of range; allowed {range} {}{hint}",
                    shown(v),
                    self.unit.label()
                ),
            ));
        }
        if self.unit == Unit::Count && v.fract() != 0.0 {
            return Err(Error::invalid(
                self.key,
                format!("{v} must be a whole number in {range}"),
            ));
        }
        Ok(v)
    }
}

/// A complete, validated parameter set of a family.
#[derive(Clone, Debug, PartialEq)]
pub struct Params {
    pub(super) values: BTreeMap<String, f64>,
}

impl Params {
    /// The value of `key`; an error naming the key and the set's keys if the key is not one of
    /// the family's.
    pub fn get(&self, key: &str) -> Result<f64> {
        self.values.get(key).copied().ok_or_else(|| {
            let keys: Vec<&str> = self.values.keys().map(String::as_str).collect();
            Error::invalid(
                key,
                format!("not a parameter of this set; known: {}", keys.join(", ")),
            )
        })
    }
    /// All values, by key.
    pub fn values(&self) -> &BTreeMap<String, f64> {
        &self.values
    }
}
