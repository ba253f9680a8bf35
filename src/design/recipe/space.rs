//! A recipe's tier angles as a cut space: the optimizer turns tiers and the recipe is cut
//! again, so every tier keeps the recipe's own placement (its meets, centre point, girdle,
//! table) rather than meets inferred from the solid.

use super::{Angle, Recipe};
use crate::cut::{Cut, CutSpace, ParamRange, Unit};
use crate::error::{Error, Result};
use std::collections::BTreeMap;

/// The sloping tiers of a recipe whose angles are numbers (not expressions), as parameters
/// (degrees of tilt, 0–90 open); tiers whose angles are expressions of them follow.
///
/// ```
/// use facetlab::cut::CutSpace;
/// use facetlab::design::recipe::RecipeSpace;
/// use std::collections::BTreeMap;
///
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cuts/recipes/brilliant.toml");
/// let text = std::fs::read_to_string(path).unwrap();
/// let space = RecipeSpace::new(facetlab::io::recipe::parse(&text, path, "b").unwrap()).unwrap();
/// assert_eq!(space.keys(), vec!["P1", "C1", "C3"]);
/// // Flatter crown halves: the bezels (an expression of them) follow, the stars still meet.
/// let cut = space.build("b", &BTreeMap::from([("C1".to_string(), 33.0)])).unwrap();
/// assert_eq!(cut.params["C1"], 33.0);
/// assert_eq!(cut.solid.facets().len(), 73);
/// ```
#[derive(Clone, Debug)]
pub struct RecipeSpace {
    recipe: Recipe,
    keys: Vec<String>,
    base: Cut,
}

impl RecipeSpace {
    /// The space of `recipe`'s free tier angles; an error when it does not build or has none.
    pub fn new(recipe: Recipe) -> Result<RecipeSpace> {
        let base = recipe.build()?.cut;
        let keys: Vec<String> = recipe
            .tiers
            .iter()
            .filter(|t| matches!(t.angle, Angle::Degrees(a) if a != 0.0 && a.abs() < 90.0))
            .map(|t| t.name.clone())
            .collect();
        Ok(RecipeSpace { recipe, keys, base })
    }

    /// The recipe as written.
    pub fn recipe(&self) -> &Recipe {
        &self.recipe
    }

    /// The recipe built as written.
    pub fn base(&self) -> &Cut {
        &self.base
    }

    /// The recipe with the tilts `values` (completed), each tier keeping its side.
    pub fn recipe_at(&self, values: &BTreeMap<String, f64>) -> Result<Recipe> {
        let values = self.complete(values)?;
        let mut r = self.recipe.clone();
        for t in &mut r.tiers {
            if let (Some(v), Angle::Degrees(a)) = (values.get(&t.name), &t.angle) {
                t.angle = Angle::Degrees(if *a < 0.0 { -v } else { *v });
            }
        }
        Ok(r)
    }
}

impl CutSpace for RecipeSpace {
    fn name(&self) -> &str {
        &self.recipe.name
    }

    fn keys(&self) -> Vec<&str> {
        self.keys.iter().map(String::as_str).collect()
    }

    fn range(&self, key: &str) -> Option<ParamRange> {
        let t = self
            .recipe
            .tiers
            .iter()
            .find(|t| t.name == key && self.keys.contains(&t.name))?;
        let Angle::Degrees(a) = t.angle else {
            return None;
        };
        Some(ParamRange {
            default: a.abs(),
            min: 0.0,
            max: 90.0,
            open: true,
            unit: Unit::Degrees,
        })
    }

    fn complete(&self, values: &BTreeMap<String, f64>) -> Result<BTreeMap<String, f64>> {
        let mut out: BTreeMap<String, f64> = self
            .keys
            .iter()
            .filter_map(|k| Some((k.clone(), self.range(k)?.default)))
            .collect();
        for (k, &v) in values {
            let Some(r) = self.range(k) else {
                return Err(Error::invalid(
                    k.as_str(),
                    format!(
                        "not a free tier of the recipe {}; its tiers with angles to turn: {}",
                        self.recipe.name,
                        self.keys.join(", ")
                    ),
                ));
            };
            if !(v.is_finite() && r.contains(v)) {
                return Err(Error::invalid(
                    k.as_str(),
                    format!("{v} is not an angle in (0, 90) degrees"),
                ));
            }
            out.insert(k.clone(), v);
        }
        Ok(out)
    }

    fn build(&self, name: &str, values: &BTreeMap<String, f64>) -> Result<Cut> {
        let params = self.complete(values)?;
        let mut cut = self.recipe_at(&params)?.build()?.cut;
        cut.name = name.to_string();
        cut.params = params;
        Ok(cut)
    }
}
