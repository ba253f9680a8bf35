//! How each tier of a recipe moves the scores: the change of brilliance, its COS half and fire
//! per degree of the tier's angle, from central differences of the exact beam tracer's scores
//! (the recipe cut again at each angle, so every tier keeps its placement). What a faceter
//! reads while designing: which tier to turn, and which way.

use crate::cut::CutSpace;
use crate::design::recipe::RecipeSpace;
use crate::error::Result;
use crate::metrics::{score, ScoreConfig};
use rayon::prelude::*;
use std::collections::BTreeMap;

/// One free tier's slopes, per degree of tilt (steeper positive).
#[derive(Clone, Debug, PartialEq)]
pub struct TierSlope {
    /// The tier.
    pub tier: String,
    /// Its tilt as written (degrees).
    pub angle: f64,
    /// d brilliance / d angle (per degree).
    pub brilliance: f64,
    /// d brilliance_cos / d angle: the COS look.
    pub brilliance_cos: f64,
    /// d fire / d angle (percent per degree), when `config` scores fire.
    pub fire: f64,
    /// The step used each side (degrees); one-sided (`one_sided`) where the recipe cannot be
    /// cut on one side.
    pub step: f64,
    /// Whether only one side could be cut.
    pub one_sided: bool,
}

/// The slopes of every free tier of `space` (tiers whose angles are numbers) at steps of
/// `step` degrees each side, scored with `config`; tiers that cannot be cut on either side
/// are left out.
///
/// ```no_run
/// use facetlab::design::recipe::RecipeSpace;
/// use facetlab::metrics::ScoreConfig;
/// let path = "cuts/recipes/brilliant.toml";
/// let text = std::fs::read_to_string(path).unwrap();
/// let space = RecipeSpace::new(facetlab::io::recipe::parse(&text, path, "b").unwrap()).unwrap();
/// for s in facetlab::optimize::tier_slopes(&space, &ScoreConfig::default(), 0.5).unwrap() {
///     println!("{} {:+.4}/°", s.tier, s.brilliance);
/// }
/// ```
pub fn tier_slopes(space: &RecipeSpace, config: &ScoreConfig, step: f64) -> Result<Vec<TierSlope>> {
    let base = space.complete(&BTreeMap::new())?;
    let keys: Vec<String> = space.keys().iter().map(|k| k.to_string()).collect();
    let at = |key: &str, v: f64| -> Option<(f64, f64, f64)> {
        let mut values = base.clone();
        values.insert(key.to_string(), v);
        let cut = space.build("slope", &values).ok()?;
        let s = score(&cut.solid, config);
        Some((s.brilliance, s.brilliance_cos, s.fire))
    };
    let centre = {
        let cut = space.build("slope", &base)?;
        let s = score(&cut.solid, config);
        (s.brilliance, s.brilliance_cos, s.fire)
    };
    let out: Vec<Option<TierSlope>> = keys
        .par_iter()
        .map(|k| {
            let a = base[k];
            let (lo, hi) = (at(k, a - step), at(k, a + step));
            let (d, (p, q), one) = match (lo, hi) {
                (Some(l), Some(h)) => (2.0 * step, (l, h), false),
                (None, Some(h)) => (step, (centre, h), true),
                (Some(l), None) => (step, (l, centre), true),
                (None, None) => return None,
            };
            Some(TierSlope {
                tier: k.clone(),
                angle: a,
                brilliance: (q.0 - p.0) / d,
                brilliance_cos: (q.1 - p.1) / d,
                fire: (q.2 - p.2) / d,
                step,
                one_sided: one,
            })
        })
        .collect();
    Ok(out.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::design::recipe::{Place, Recipe, RecipeTier};

    /// A slope is the central difference of the recipe written with the turned angle and
    /// scored from scratch (the tiers whose angles are expressions of it follow), and it
    /// predicts a half-degree turn either way to within 30 % of the change (measured: 21 %;
    /// brilliance curves over a degree, and the fast setting's is bumpy at 0.1°, so the
    /// default setting is the one a faceter reads).
    #[test]
    fn a_slope_predicts_the_change_of_a_turn() {
        let recipe = |p1: f64| {
            let mut r = Recipe::new("b", 96, 8, true, 1.54);
            r.add(RecipeTier::new("P1", -p1, &[3.0], Place::Centre));
            r.add(RecipeTier::new("G1", 90.0, &[3.0], Place::Scale(1.2)));
            let mut p2 = RecipeTier::new(
                "P2",
                -41.0,
                &[96.0],
                Place::Meet(vec!["P1".into(), "G1".into()]),
            );
            p2.angle = crate::design::recipe::Angle::Expr("=P1-1".into());
            p2.side = Some(crate::design::recipe::Side::Pavilion);
            r.add(p2);
            r.add(RecipeTier::new("C1", 34.0, &[3.0], Place::Girdle(0.015)));
            let meet = |a: &str, b: &str| Place::Meet(vec![a.into(), b.into()]);
            r.add(RecipeTier::new("C2", 28.0, &[96.0], meet("G1", "G1")));
            r.add(RecipeTier::new("C3", 16.0, &[6.0], meet("C1", "C1")));
            r.add(RecipeTier::new("T", 0.0, &[], meet("C2", "C3")));
            r
        };
        let config = ScoreConfig {
            material: crate::optics::Material::for_index(1.54).unwrap(),
            parts: crate::metrics::Parts {
                fire: false,
                scintillation: false,
            },
            ..ScoreConfig::default()
        };
        let space = RecipeSpace::new(recipe(42.0)).unwrap();
        let s = tier_slopes(&space, &config, 0.5).unwrap();
        let p1 = s.iter().find(|s| s.tier == "P1").unwrap();
        assert!(!p1.one_sided && s.iter().all(|t| t.tier != "P2"), "{s:?}");
        let b = |a: f64| score(&recipe(a).build().unwrap().cut.solid, &config).brilliance;
        let (lo, mid, hi) = (b(41.5), b(42.0), b(42.5));
        assert!(
            (p1.brilliance - (hi - lo)).abs() < 1e-12,
            "{p1:?} {lo} {hi}"
        );
        for change in [hi - mid, mid - lo] {
            let predicted = 0.5 * p1.brilliance;
            assert!(
                (change - predicted).abs() <= 0.3 * predicted.abs(),
                "a half-degree turn changes brilliance by {change}, the slope predicts {predicted}"
            );
        }
    }
}
