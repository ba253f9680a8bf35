//! The registry of parametric families.

use super::{
    cushion, emerald, marquise, old_european, oval, pear, princess, round, sphere, ParamDef, Params,
};
use crate::error::{Error, Result};
use crate::geometry::FacetPlane;
use std::collections::BTreeMap;

/// A parametric family of cuts.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// Name used in specs (`family = "round-brilliant"`).
    pub name: &'static str,
    /// One-line description.
    pub doc: &'static str,
    /// The parameters, in display order.
    pub params: &'static [ParamDef],
    /// Build the facet planes from a validated parameter set.
    pub build: fn(&Params) -> Result<Vec<FacetPlane>>,
}

impl Family {
    /// The definition of parameter `key`.
    pub fn param(&self, key: &str) -> Option<&'static ParamDef> {
        self.params.iter().find(|p| p.key == key)
    }

    /// Fill defaults and validate `values`; unknown keys and out-of-range values are errors.
    pub fn params(&self, values: &BTreeMap<String, f64>) -> Result<Params> {
        for k in values.keys() {
            if self.param(k).is_none() {
                return Err(Error::invalid(
                    k.as_str(),
                    format!(
                        "unknown parameter for {}; allowed: {}",
                        self.name,
                        self.keys().join(", ")
                    ),
                ));
            }
        }
        let mut out = BTreeMap::new();
        for p in self.params {
            let v = values.get(p.key).copied().unwrap_or(p.default);
            out.insert(p.key.to_string(), p.check(v)?);
        }
        Ok(Params { values: out })
    }

    /// The parameter keys in display order.
    pub fn keys(&self) -> Vec<&'static str> {
        self.params.iter().map(|p| p.key).collect()
    }
}

static FAMILIES: &[Family] = &[
    round::FAMILY,
    princess::FAMILY,
    emerald::FAMILY,
    oval::FAMILY,
    marquise::FAMILY,
    pear::FAMILY,
    cushion::FAMILY,
    old_european::FAMILY,
    sphere::FAMILY,
];

/// Every family.
pub fn families() -> &'static [Family] {
    FAMILIES
}

/// The family called `name`.
pub fn family(name: &str) -> Result<&'static Family> {
    FAMILIES.iter().find(|f| f.name == name).ok_or_else(|| {
        let names: Vec<&str> = FAMILIES.iter().map(|f| f.name).collect();
        Error::invalid(
            "family",
            format!("unknown family `{name}`; known: {}", names.join(", ")),
        )
    })
}
