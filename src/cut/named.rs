//! The [`Cut`] type: a named convex solid with the family and parameters (or the GemCad record)
//! it came from.

use super::{family, measure, GemcadRecord, Proportions, Ratios, TierSummary};
use crate::error::{Error, Result};
use crate::geometry::{FacetPlane, Polyhedron};
use std::collections::BTreeMap;

/// A cut: a named convex solid, with the family and parameters it was generated from (if any).
#[derive(Clone, Debug)]
pub struct Cut {
    /// Display name (preset name, file stem, or the spec's `name`).
    pub name: String,
    /// Family name, when generated from a family.
    pub family: Option<String>,
    /// Full parameter set (defaults filled in), when generated from a family.
    pub params: BTreeMap<String, f64>,
    /// The solid.
    pub solid: Polyhedron,
    /// What the GemCad file said about itself (its index, titles, notes, gear, symmetry,
    /// instructions; see [`GemcadRecord`]), for imports that carry it; `None` for generated cuts.
    pub record: Option<GemcadRecord>,
}

impl Cut {
    /// Generate a cut of `family` with `values` overriding the family's defaults. Unknown keys
    /// and out-of-range values are errors naming the key.
    ///
    /// ```
    /// use facetlab::cut::{family, Cut};
    /// use std::collections::BTreeMap;
    ///
    /// // A family declares its parameters: key, default and allowed range.
    /// let crown = family("round-brilliant").unwrap().param("crown_angle").unwrap();
    /// assert!(crown.min <= 34.0 && 34.0 <= crown.max);
    ///
    /// // Lengths are fractions of the girdle diameter, angles degrees; the rest default.
    /// let mut v = BTreeMap::new();
    /// for (k, x) in [("table", 0.57), ("crown_angle", 34.0), ("pavilion_angle", 40.7),
    ///                ("girdle", 0.025), ("star", 0.5), ("lower_half", 0.8)] {
    ///     v.insert(k.to_string(), x);
    /// }
    /// let cut = Cut::from_family("mine", "round-brilliant", &v).unwrap();
    /// let p = cut.proportions();
    /// assert!((p.crown_height - 0.145).abs() < 0.001, "{p:?}");
    /// assert!((p.total_depth - 0.600).abs() < 0.001, "{p:?}");
    ///
    /// v.insert("crown_angle".to_string(), 75.0);
    /// let e = Cut::from_family("mine", "round-brilliant", &v).unwrap_err().to_string();
    /// assert!(e.starts_with("crown_angle"), "{e}");
    /// ```
    pub fn from_family(
        name: &str,
        family_name: &str,
        values: &BTreeMap<String, f64>,
    ) -> Result<Cut> {
        let fam = family(family_name)?;
        let params = fam.params(values)?;
        let planes = (fam.build)(&params)?;
        let solid = Polyhedron::from_planes(&planes)
            .map_err(|e| e.context(&format!("{family_name} cut")))?;
        Ok(Cut {
            name: name.to_string(),
            family: Some(fam.name.to_string()),
            params: params.values,
            solid,
            record: None,
        })
    }

    /// A cut from explicit facet planes.
    pub fn from_planes(name: &str, planes: &[FacetPlane]) -> Result<Cut> {
        let solid = Polyhedron::from_planes(planes).map_err(|e| e.context(name))?;
        Ok(Cut {
            name: name.to_string(),
            family: None,
            params: BTreeMap::new(),
            solid,
            record: None,
        })
    }

    /// The same family cut with one more parameter changed (the command line's `--set key=value`). Cuts that are
    /// not from a family (imported files) have no parameters to set.
    pub fn with_params(&self, changes: &BTreeMap<String, f64>) -> Result<Cut> {
        if changes.is_empty() {
            return Ok(self.clone());
        }
        let Some(fam) = &self.family else {
            let key = changes.keys().next().cloned().unwrap_or_default();
            return Err(Error::invalid(
                key,
                format!("{} is an explicit facet design, not a parametric family; it has no parameters to set", self.name),
            ));
        };
        let mut values = self.params.clone();
        for (k, v) in changes {
            values.insert(k.clone(), *v);
        }
        Cut::from_family(&self.name, fam, &values)
    }

    /// The refractive index the design file was cut for (GemCad's `I` line), if it names one.
    pub fn design_ri(&self) -> Option<f64> {
        self.record.as_ref().and_then(|d| d.ri)
    }

    /// Proportions measured on the solid (table, crown angle, depths …).
    pub fn proportions(&self) -> Proportions {
        measure::proportions(&self.solid)
    }

    /// GemCad's ratios: L/W, T/W, P/W, C/W, H/W, Vol/W³.
    pub fn ratios(&self) -> Ratios {
        measure::ratios(&self.solid)
    }

    /// Each tier's mean angle and facet count, in order of first appearance.
    pub fn tiers(&self) -> Vec<TierSummary> {
        measure::tiers(&self.solid)
    }
}
