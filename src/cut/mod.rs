//! Cuts: parametric families (round brilliant, princess, …) and the [`Cut`] type, a named convex
//! polyhedron that remembers the family and parameters it came from.
//!
//! Every family declares its parameters ([`ParamDef`]: key, default, allowed range, unit). The
//! same keys are used in TOML specs, in `--set key=value`, by `info` and by the optimizer.
//! Lengths are fractions of the girdle diameter (0.57, not 57), angles are degrees.

mod construct;
mod cushion;
mod emerald;
mod families;
pub mod grade;
mod marquise;
mod measure;
mod old_european;
mod outline;
mod oval;
mod pear;
pub mod plausible;
mod princess;
pub mod record;
pub mod retarget;
mod round;
pub mod space;
mod sphere;
mod steps;
pub mod units;

pub use families::{families, family, Family};
pub use measure::{Proportions, Ratios, TierSummary};
pub use record::GemcadRecord;
pub use space::{CutSpace, ParamRange};

use crate::error::{shown, Error, Result};
use crate::geometry::{FacetPlane, Polyhedron};
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
    values: BTreeMap<String, f64>,
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

#[cfg(test)]
mod testutil;
#[cfg(test)]
mod tests {
    use super::*;

    fn gia() -> Cut {
        let v: BTreeMap<String, f64> = [
            ("table", 0.57),
            ("crown_angle", 34.0),
            ("pavilion_angle", 40.7),
            ("girdle", 0.025),
            ("star", 0.5),
            ("lower_half", 0.8),
        ]
        .iter()
        .map(|(k, v)| (k.to_string(), *v))
        .collect();
        Cut::from_family("gia", "round-brilliant", &v).unwrap()
    }

    #[test]
    fn gia_reference_matches_published_figures() {
        let c = gia();
        let p = c.proportions();
        assert!(
            (p.crown_height - 0.145).abs() < 0.0007,
            "crown height {}",
            p.crown_height
        );
        assert!(
            (p.pavilion_depth - 0.430).abs() < 0.0007,
            "pavilion depth {}",
            p.pavilion_depth
        );
        assert!(
            (p.total_depth - 0.600).abs() < 0.0007,
            "total depth {}",
            p.total_depth
        );
        assert!((p.table - 0.57).abs() < 1e-9);
        assert!((p.crown_angle - 34.0).abs() < 1e-9);
        assert!((p.pavilion_angle - 40.7).abs() < 1e-9);
        assert!((p.girdle - 0.025).abs() < 1e-9);
        let t = c.tiers();
        let angle = |n: &str| t.iter().find(|x| x.name == n).unwrap().angle;
        assert!(
            (angle("star") - 21.1).abs() < 0.05,
            "star {}",
            angle("star")
        );
        assert!(
            (angle("upper-half") - 40.6).abs() < 0.05,
            "upper half {}",
            angle("upper-half")
        );
        assert!(
            (angle("lower-half") - 41.8).abs() < 0.05,
            "lower half {}",
            angle("lower-half")
        );
        // 57 facets (no culet) + 16 girdle facets.
        assert_eq!(c.solid.facets().len(), 57 + 16);
        let count = |n: &str| t.iter().find(|x| x.name == n).unwrap().count;
        assert_eq!(
            (count("bezel"), count("star"), count("upper-half")),
            (8, 8, 16)
        );
        assert_eq!(
            (count("pavilion-main"), count("lower-half"), count("girdle")),
            (8, 16, 16)
        );
    }

    #[test]
    fn set_and_validation() {
        let c = gia();
        let mut ch = BTreeMap::new();
        ch.insert("culet".to_string(), 0.02);
        let c2 = c.with_params(&ch).unwrap();
        assert_eq!(c2.solid.facets().len(), 58 + 16);
        ch.insert("table".into(), 57.0);
        let e = c.with_params(&ch).unwrap_err().to_string();
        assert!(e.starts_with("table:") && e.contains("0.57, not 57"), "{e}");
        let mut ch = BTreeMap::new();
        ch.insert("star".to_string(), 1.0);
        assert!(c
            .with_params(&ch)
            .unwrap_err()
            .to_string()
            .contains("(0, 1)"));
        let mut ch = BTreeMap::new();
        ch.insert("tabel".to_string(), 0.5);
        let e = c.with_params(&ch).unwrap_err().to_string();
        assert!(e.contains("tabel") && e.contains("table"), "{e}");
        let mut ch = BTreeMap::new();
        ch.insert("crown_angle".to_string(), f64::NAN);
        assert!(c
            .with_params(&ch)
            .unwrap_err()
            .to_string()
            .contains("not a number"));
    }

    #[test]
    fn impossible_star_and_lower_half_are_named() {
        // At a 85 % table the bezel ridge meets the table plane at radius 0.92: a 50 % star
        // (tip at 0.893) would stand above the table.
        let mut v = BTreeMap::new();
        v.insert("table".to_string(), 0.85);
        let e = Cut::from_family("r", "round-brilliant", &v)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("star:") && e.contains("above the table"),
            "{e}"
        );
        v.insert("star".to_string(), 0.7);
        assert!(Cut::from_family("r", "round-brilliant", &v).is_ok());
        let mut v = BTreeMap::new();
        v.insert("culet".to_string(), 0.2);
        v.insert("lower_half".to_string(), 0.85);
        let e = Cut::from_family("r", "round-brilliant", &v)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("lower_half:") && e.contains("culet"), "{e}");
    }

    #[test]
    fn random_parameters_build_or_say_which_parameter() {
        use rand::{Rng, SeedableRng};
        let fam = family("round-brilliant").unwrap();
        let mut rng = rand::rngs::SmallRng::seed_from_u64(7);
        let mut built = 0;
        for _ in 0..400 {
            let mut v = BTreeMap::new();
            for p in fam.params.iter().filter(|p| p.key != "girdle_facets") {
                v.insert(
                    p.key.to_string(),
                    p.min + (p.max - p.min) * rng.random_range(0.001..0.999),
                );
            }
            match Cut::from_family("r", "round-brilliant", &v) {
                Ok(c) => {
                    let s = &c.solid;
                    assert_eq!(s.vertices().len() + s.facets().len(), s.edges().len() + 2);
                    assert!(s.volume() > 0.0);
                    built += 1;
                }
                Err(e) => {
                    let e = e.to_string();
                    assert!(
                        e.starts_with("star:") || e.starts_with("lower_half:"),
                        "{e} for {v:?}"
                    );
                }
            }
        }
        assert!(built > 200, "{built}");
    }

    #[test]
    fn girdle_facet_counts() {
        for n in [32.0, 64.0] {
            let mut v = BTreeMap::new();
            v.insert("girdle_facets".to_string(), n);
            let c = Cut::from_family("r", "round-brilliant", &v).unwrap();
            assert_eq!(c.solid.facets().len(), 57 + n as usize);
        }
        let mut v = BTreeMap::new();
        v.insert("girdle".to_string(), 0.0);
        let knife = Cut::from_family("r", "round-brilliant", &v).unwrap();
        assert_eq!(knife.solid.facets().len(), 57);
        assert!(knife.proportions().girdle.abs() < 1e-12);
        let mut v = BTreeMap::new();
        v.insert("girdle_facets".to_string(), 20.0);
        assert!(Cut::from_family("r", "round-brilliant", &v).is_err());
    }
}
