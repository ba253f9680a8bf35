//! The plan config (`plan.toml`) and the price table: parsed with unknown keys refused, every
//! error one line naming the file and field. Every field is optional:
//!
//! ```toml
//! name = "plan"                 # run folder prefix; default: the file's stem
//! seed = 1                      # the random start orientations follow it
//! families = ["round-brilliant", "oval"]   # default: round-brilliant and the fancy shapes
//! material = "diamond"          # density for carats (`facetlab materials`)
//! top = 3                       # distinct plans kept per family
//! min_width_mm = 1.0            # a rough whose widest plan is narrower is refused
//!
//! [objective]
//! kind = "weight"               # "weight" (carats) or "value" (price table × quality)
//! grade = "excellent"           # round brilliants only: the grade estimate must reach it
//! min_brilliance = 0.75         # every family: brilliance (fast scores) at least this
//! prices = "prices.toml"        # for "value", relative to this file
//!
//! [search]
//! starts = 12                   # Nelder–Mead starts per family (start 0: table up)
//! max_iterations = 250          # per start
//!
//! [free.round-brilliant]        # per family: key = [min, max] varied, key = value fixed
//! crown_angle = [31.5, 36.5]
//! pavilion_angle = [40.6, 41.8]
//! ```

use crate::cut::{family, grade::Grade, CutSpace};
use crate::error::{Error, Result};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The families planned when none are named: the round brilliant and the fancy shapes.
pub const DEFAULT_FAMILIES: [&str; 7] = [
    "round-brilliant",
    "oval",
    "cushion",
    "princess",
    "emerald",
    "pear",
    "marquise",
];

/// One parameter's setting for a family: varied within bounds, or fixed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bound {
    /// Fixed at this value.
    Fixed(f64),
    /// Varied within `[min, max]`.
    Free(f64, f64),
}

/// What a plan maximises.
#[derive(Clone, Debug, PartialEq)]
pub enum Objective {
    /// Carats.
    Weight,
    /// Price from a table × a quality factor.
    Value(PriceTable),
}

/// A price table: price per carat by weight band and a quality factor by grade.
#[derive(Clone, Debug, PartialEq)]
pub struct PriceTable {
    /// Currency label.
    pub currency: String,
    /// `(from carats, price per carat)`, ascending.
    pub bands: Vec<(f64, f64)>,
    /// Factor by grade estimate; `ungraded` for cuts without one.
    pub quality: BTreeMap<Grade, f64>,
    /// Factor for cuts the grade estimate does not cover (fancy shapes).
    pub ungraded: f64,
}

impl PriceTable {
    /// Price per carat at `carats` (the band whose lower limit is the largest not above it).
    pub fn per_carat(&self, carats: f64) -> f64 {
        self.bands
            .iter()
            .rev()
            .find(|(from, _)| carats >= *from)
            .map_or(0.0, |(_, p)| *p)
    }

    /// The quality factor of a grade (or of an ungraded cut).
    pub fn factor(&self, grade: Option<Grade>) -> f64 {
        grade.map_or(self.ungraded, |g| {
            self.quality.get(&g).copied().unwrap_or(self.ungraded)
        })
    }

    /// Value of a stone: carats × price per carat × quality factor.
    pub fn value(&self, carats: f64, grade: Option<Grade>) -> f64 {
        carats * self.per_carat(carats) * self.factor(grade)
    }

    /// Parse a price file (`source` names it).
    pub fn parse(text: &str, source: &str) -> Result<PriceTable> {
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct RawBand {
            from_carats: f64,
            per_carat: f64,
        }
        #[derive(Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Raw {
            currency: Option<String>,
            band: Vec<RawBand>,
            #[serde(default)]
            quality: BTreeMap<String, f64>,
        }
        let raw: Raw = toml::from_str(text).map_err(|e| Error::parse(source, e.message()))?;
        let mut bands = Vec::new();
        for (i, b) in raw.band.iter().enumerate() {
            let ok = b.from_carats.is_finite() && b.from_carats >= 0.0 && b.per_carat >= 0.0;
            if !ok || bands.last().is_some_and(|(f, _)| *f >= b.from_carats) {
                return Err(Error::invalid(
                    format!("{source}: band {}", i + 1),
                    "from_carats must be ≥ 0 and rise from band to band, per_carat ≥ 0",
                ));
            }
            bands.push((b.from_carats, b.per_carat));
        }
        if bands.is_empty() {
            return Err(Error::invalid(
                format!("{source}: band"),
                "give at least one [[band]] with from_carats and per_carat",
            ));
        }
        let mut quality = BTreeMap::new();
        let mut ungraded = 1.0;
        for (k, v) in &raw.quality {
            if !(v.is_finite() && *v >= 0.0) {
                return Err(Error::invalid(
                    format!("{source}: quality.{k}"),
                    "a factor must be a number ≥ 0",
                ));
            }
            match (k.as_str(), Grade::parse(k)) {
                ("ungraded", _) => ungraded = *v,
                (_, Some(g)) => {
                    quality.insert(g, *v);
                }
                _ => {
                    return Err(Error::invalid(
                        format!("{source}: quality.{k}"),
                        "unknown key; allowed: excellent, very-good, good, fair, poor, ungraded",
                    ))
                }
            }
        }
        Ok(PriceTable {
            currency: raw.currency.unwrap_or_else(|| "USD".into()),
            bands,
            quality,
            ungraded,
        })
    }
}

/// A validated plan config.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanConfig {
    /// Run folder prefix.
    pub name: String,
    /// Seed of the start orientations.
    pub seed: u64,
    /// Families to plan, in order.
    pub families: Vec<String>,
    /// Material name (density).
    pub material: String,
    /// Distinct plans kept per family.
    pub top: usize,
    /// A rough whose widest plan (over every family) is narrower than this (mm) is too small.
    pub min_width_mm: f64,
    /// What is maximised.
    pub objective: Objective,
    /// Grade the round brilliant's estimate must reach.
    pub grade: Option<Grade>,
    /// Brilliance every plan must reach (the fast score settings, `metrics::ScoreConfig::fast`,
    /// brilliance only), in [0, 1].
    pub min_brilliance: Option<f64>,
    /// Per family: parameter settings (missing keys take the family's defaults).
    pub params: BTreeMap<String, BTreeMap<String, Bound>>,
    /// Nelder–Mead starts per family.
    pub starts: usize,
    /// Iterations per start.
    pub max_iterations: u64,
}

impl Default for PlanConfig {
    fn default() -> Self {
        PlanConfig {
            name: "plan".into(),
            seed: 1,
            families: DEFAULT_FAMILIES.iter().map(|s| s.to_string()).collect(),
            material: "diamond".into(),
            top: 3,
            min_width_mm: 1.0,
            objective: Objective::Weight,
            grade: None,
            min_brilliance: None,
            params: BTreeMap::new(),
            starts: 12,
            max_iterations: 250,
        }
    }
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawBound {
    Fixed(f64),
    Free([f64; 2]),
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawObjective {
    kind: Option<String>,
    grade: Option<String>,
    min_brilliance: Option<f64>,
    prices: Option<PathBuf>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawSearch {
    starts: Option<usize>,
    max_iterations: Option<u64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    name: Option<String>,
    seed: Option<u64>,
    families: Option<Vec<String>>,
    material: Option<String>,
    top: Option<usize>,
    min_width_mm: Option<f64>,
    #[serde(default)]
    objective: RawObjective,
    #[serde(default)]
    search: RawSearch,
    #[serde(default)]
    free: BTreeMap<String, BTreeMap<String, RawBound>>,
}

impl PlanConfig {
    /// Read a config file; a price file it names is read relative to it.
    pub fn load(path: &Path) -> Result<PlanConfig> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| Error::io(&shown, e))?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("plan");
        let dir = path.parent().unwrap_or(Path::new("."));
        PlanConfig::parse(&text, &shown, stem, dir)
    }

    /// Parse a config's text (`source` names it; `dir` is where a price file is looked up).
    pub fn parse(text: &str, source: &str, stem: &str, dir: &Path) -> Result<PlanConfig> {
        let raw: RawConfig = toml::from_str(text).map_err(|e| Error::parse(source, e.message()))?;
        let at = |f: &str| format!("{source}: {f}");
        let mut c = PlanConfig {
            name: raw.name.unwrap_or_else(|| stem.to_string()),
            ..PlanConfig::default()
        };
        c.seed = raw.seed.unwrap_or(c.seed);
        if let Some(f) = raw.families {
            for name in &f {
                family(name).map_err(|e| Error::invalid(at("families"), e.to_string()))?;
            }
            if f.is_empty() {
                return Err(Error::invalid(at("families"), "name at least one family"));
            }
            c.families = f;
        }
        c.material = raw.material.unwrap_or(c.material);
        c.top = raw.top.unwrap_or(c.top);
        if !(1..=50).contains(&c.top) {
            return Err(Error::invalid(at("top"), "allowed 1 to 50"));
        }
        c.min_width_mm = raw.min_width_mm.unwrap_or(c.min_width_mm);
        if !(c.min_width_mm.is_finite() && c.min_width_mm >= 0.0) {
            return Err(Error::invalid(
                at("min_width_mm"),
                "allowed a number ≥ 0 (mm)",
            ));
        }
        c.starts = raw.search.starts.unwrap_or(c.starts);
        if !(1..=1000).contains(&c.starts) {
            return Err(Error::invalid(at("search.starts"), "allowed 1 to 1000"));
        }
        c.max_iterations = raw.search.max_iterations.unwrap_or(c.max_iterations);
        if !(1..=100_000).contains(&c.max_iterations) {
            return Err(Error::invalid(
                at("search.max_iterations"),
                "allowed 1 to 100000",
            ));
        }
        if let Some(g) = &raw.objective.grade {
            c.grade = Some(Grade::parse(g).ok_or_else(|| {
                Error::invalid(
                    at("objective.grade"),
                    format!("unknown grade `{g}`; allowed: excellent, very-good, good, fair, poor"),
                )
            })?);
        }
        if let Some(b) = raw.objective.min_brilliance {
            if !(0.0..=1.0).contains(&b) {
                return Err(Error::invalid(
                    at("objective.min_brilliance"),
                    format!("{b} is not a brilliance; allowed 0 to 1"),
                ));
            }
            c.min_brilliance = Some(b);
        }
        c.objective = match raw.objective.kind.as_deref().unwrap_or("weight") {
            "weight" => Objective::Weight,
            "value" => {
                let Some(p) = &raw.objective.prices else {
                    return Err(Error::invalid(
                        at("objective.prices"),
                        "kind = \"value\" needs a price file: prices = \"prices.toml\"",
                    ));
                };
                let path = dir.join(p);
                let shown = path.display().to_string();
                let text = std::fs::read_to_string(&path).map_err(|e| Error::io(&shown, e))?;
                Objective::Value(PriceTable::parse(&text, &shown)?)
            }
            other => {
                return Err(Error::invalid(
                    at("objective.kind"),
                    format!("unknown objective `{other}`; allowed: weight, value"),
                ))
            }
        };
        for (fam, keys) in raw.free {
            let space = family(&fam).map_err(|e| Error::invalid(at("free"), e.to_string()))?;
            let mut out = BTreeMap::new();
            for (k, b) in keys {
                let field = at(&format!("free.{fam}.{k}"));
                let Some(r) = space.range(&k) else {
                    return Err(Error::invalid(
                        field,
                        format!(
                            "not a parameter of {fam}; allowed: {}",
                            space.keys().join(", ")
                        ),
                    ));
                };
                let ok = |v: f64| r.contains(v);
                let bound = match b {
                    RawBound::Fixed(v) if ok(v) => Bound::Fixed(v),
                    RawBound::Free([lo, hi]) if ok(lo) && ok(hi) && lo < hi => Bound::Free(lo, hi),
                    _ => {
                        return Err(Error::invalid(
                            field,
                            format!(
                                "give a value or [min, max] with min < max, each in {}{}, {}{}",
                                if r.open { "(" } else { "[" },
                                r.min,
                                r.max,
                                if r.open { ")" } else { "]" }
                            ),
                        ))
                    }
                };
                out.insert(k, bound);
            }
            c.params.insert(fam, out);
        }
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_example_config_and_price_table_parse() {
        let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/optim/plan"));
        let c = PlanConfig::load(&dir.join("plan-value.toml")).unwrap();
        assert_eq!(c.families, ["round-brilliant", "oval", "cushion"]);
        assert_eq!(c.grade, Some(Grade::Excellent));
        let Objective::Value(t) = &c.objective else {
            panic!("{:?}", c.objective)
        };
        // 0.6 ct excellent: 0.6 × 2600 × 1.0; an ungraded 1.2 ct: 1.2 × 5200 × 0.85.
        assert!((t.value(0.6, Some(Grade::Excellent)) - 1560.0).abs() < 1e-9);
        assert!((t.value(1.2, None) - 1.2 * 5200.0 * 0.85).abs() < 1e-9);
        assert_eq!(
            c.params["round-brilliant"]["crown_angle"],
            Bound::Free(31.5, 36.5)
        );
    }

    #[test]
    fn bad_fields_are_named() {
        let dir = Path::new(".");
        let e = |t: &str| {
            PlanConfig::parse(t, "p.toml", "p", dir)
                .unwrap_err()
                .to_string()
        };
        assert!(e("colour = 1").contains("colour"));
        assert!(e("families = [\"heart\"]").contains("p.toml: families"));
        assert!(e("[objective]\nkind = \"value\"").contains("objective.prices"));
        assert!(e("[objective]\ngrade = \"superb\"").contains("objective.grade"));
        assert!(e("[objective]\nmin_brilliance = 1.5").contains("objective.min_brilliance"));
        let bad_bound = e("[free.round-brilliant]\ncrown_angle = [36.0, 30.0]");
        assert!(
            bad_bound.contains("free.round-brilliant.crown_angle"),
            "{bad_bound}"
        );
        assert!(e("[free.round-brilliant]\nhue = 3.0").contains("not a parameter"));
    }
}
