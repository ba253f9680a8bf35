//! The TOML cut spec: a family with parameters, or an explicit list of facet planes.
//!
//! ```toml
//! name = "GIA reference"
//! family = "round-brilliant"
//! [params]            # fractions of the girdle diameter, angles in degrees
//! table = 0.57
//! crown_angle = 34.0
//! ```
//!
//! or
//!
//! ```toml
//! name = "octahedron"
//! [[facets]]
//! name = "f1"
//! tier = "crown"
//! normal = [0.577, 0.577, 0.577]   # outward; normalised on reading
//! offset = 0.2887                  # along the normalised normal
//! ```

use super::line_of;
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A cut spec as written in TOML.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutSpec {
    /// Display name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Family name (`round-brilliant`, `princess`, …); absent for an explicit facet list.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// Family parameters; missing ones take the family's defaults.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub params: BTreeMap<String, f64>,
    /// Explicit facet planes (only without `family`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub facets: Vec<FacetSpec>,
}

/// One explicit facet plane.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacetSpec {
    /// Facet name.
    pub name: String,
    /// Tier name.
    #[serde(default)]
    pub tier: String,
    /// Outward normal (any length).
    pub normal: [f64; 3],
    /// Offset along the normalised normal.
    pub offset: f64,
}

/// Parse a spec; `source` (the file name) prefixes errors, with the line number.
pub fn parse(text: &str, source: &str) -> Result<CutSpec> {
    toml::from_str::<CutSpec>(text).map_err(|e| {
        let line = e
            .span()
            .map(|s| format!(":{}", line_of(text, s.start)))
            .unwrap_or_default();
        Error::parse(format!("{source}{line}"), e.message().to_string())
    })
}

impl CutSpec {
    /// Build the cut. `default_name` is used when the spec has no `name`.
    pub fn to_cut(&self, default_name: &str, source: &str) -> Result<Cut> {
        let name = self
            .name
            .clone()
            .unwrap_or_else(|| default_name.to_string());
        match (&self.family, self.facets.is_empty()) {
            (Some(_), false) => Err(Error::invalid(
                format!("{source}: facets"),
                "a spec has either `family` with `params`, or `facets`, not both",
            )),
            (Some(f), true) => Cut::from_family(&name, f, &self.params).map_err(|e| match e {
                Error::Invalid { field, message } => {
                    let field = if field == "family" { field } else { format!("params.{field}") };
                    Error::Invalid { field: format!("{source}: {field}"), message }
                }
                other => Error::parse(source, other.to_string()),
            }),
            (None, true) => Err(Error::invalid(
                format!("{source}: family"),
                "missing: give `family = \"round-brilliant\"` (or another family) or a `[[facets]]` list",
            )),
            (None, false) => {
                if !self.params.is_empty() {
                    return Err(Error::invalid(format!("{source}: params"), "parameters need a `family`"));
                }
                let mut planes = Vec::with_capacity(self.facets.len());
                for (i, f) in self.facets.iter().enumerate() {
                    let n = DVec3::from_array(f.normal);
                    if !(n.is_finite() && f.offset.is_finite() && n.length() > 0.0) {
                        return Err(Error::invalid(
                            format!("{source}: facets[{i}] ({})", f.name),
                            "normal must be three finite numbers, not all zero, and offset finite",
                        ));
                    }
                    let len = n.length();
                    let tier = if f.tier.is_empty() { f.name.clone() } else { f.tier.clone() };
                    planes.push(FacetPlane::new(n / len, f.offset, f.name.clone(), tier));
                }
                Cut::from_planes(&name, &planes).map_err(|e| Error::parse(source, e.to_string()))
            }
        }
    }

    /// The spec of a cut: family and parameters when it has them, else its facet planes.
    pub fn from_cut(cut: &Cut) -> CutSpec {
        match &cut.family {
            Some(f) => CutSpec {
                name: Some(cut.name.clone()),
                family: Some(f.clone()),
                params: cut.params.clone(),
                ..CutSpec::default()
            },
            None => CutSpec {
                name: Some(cut.name.clone()),
                facets: cut
                    .solid
                    .facets()
                    .iter()
                    .map(|f| FacetSpec {
                        name: f.name.clone(),
                        tier: f.tier.clone(),
                        normal: f.plane.normal.to_array(),
                        offset: f.plane.offset,
                    })
                    .collect(),
                ..CutSpec::default()
            },
        }
    }

    /// TOML text of this spec.
    pub fn to_toml(&self) -> String {
        toml::to_string(self).unwrap_or_else(|e| format!("# could not serialise: {e}\n"))
    }
}

/// Write a cut as a TOML spec.
pub fn write(cut: &Cut) -> String {
    CutSpec::from_cut(cut).to_toml()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn family_round_trip() {
        let cut = Cut::from_family("x", "round-brilliant", &BTreeMap::new()).unwrap();
        let text = write(&cut);
        let back = parse(&text, "x.toml")
            .unwrap()
            .to_cut("y", "x.toml")
            .unwrap();
        assert_eq!(back.params, cut.params);
        assert_eq!(back.name, "x");
        assert!((back.solid.volume() - cut.solid.volume()).abs() < 1e-15);
    }

    #[test]
    fn facet_list_round_trip_is_exact() {
        let cut = Cut::from_family("x", "round-brilliant", &BTreeMap::new()).unwrap();
        let mut explicit = cut.clone();
        explicit.family = None;
        let text = write(&explicit);
        let back = parse(&text, "x.toml")
            .unwrap()
            .to_cut("y", "x.toml")
            .unwrap();
        assert_eq!(back.solid.facets().len(), cut.solid.facets().len());
        for (a, b) in back.solid.facets().iter().zip(cut.solid.facets()) {
            assert_eq!(a.plane, b.plane);
            assert_eq!((&a.name, &a.tier), (&b.name, &b.tier));
        }
    }

    #[test]
    fn errors_name_line_and_field() {
        let e = parse(
            "family = \"round-brilliant\"\n[params]\ntable = \n",
            "bad.toml",
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("bad.toml:3:"), "{e}");
        let e = parse("family = \"round-brilliant\"\ncolour = 3\n", "bad.toml")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("bad.toml:2:") && e.contains("colour"), "{e}");
        let spec = parse(
            "family = \"round-brilliant\"\n[params]\ncrown_angle = 75.0\n",
            "c.toml",
        )
        .unwrap();
        let e = spec.to_cut("c", "c.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("c.toml: params.crown_angle:") && e.contains("[5, 60]"),
            "{e}"
        );
        assert!(!e.contains('\n'));
        let spec = parse("family = \"rund\"\n", "c.toml").unwrap();
        let e = spec.to_cut("c", "c.toml").unwrap_err().to_string();
        assert!(
            e.contains("unknown family `rund`") && e.contains("round-brilliant"),
            "{e}"
        );
    }
}
