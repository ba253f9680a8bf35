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
//! kind = "weight"               # "weight" (carats), "value" (price table × quality) or
//!                               # "colour": a coloured rough's kept plans (found by weight)
//!                               # ranked by their face-up colour's chroma C*, each scored
//!                               # at its own size and optic axis (src/plan/colour.rs);
//!                               # a layout's stones by value (or carats) × colour factor
//! grade = "excellent"           # round brilliants only: the grade estimate must reach it
//! min_brilliance = 0.65         # every family: brilliance (fast scores) at least this
//! prices = "prices.toml"        # for "value" (and "colour"), relative to this file
//!
//! [rough]
//! c_axis = [0.0, 0.0, 1.0]      # a uniaxial stone's c-axis in the rough's coordinates:
//!                               # each plan is scored with its optic axis where the rough
//!                               # puts it (default: the material's, as cutters orient it)
//!
//! [search]
//! starts = 12                   # Nelder–Mead starts per family (start 0: table up)
//! max_iterations = 250          # per start
//!
//! [free.round-brilliant]        # per family: key = [min, max] varied, key = value fixed
//! crown_angle = [31.5, 36.5]
//! pavilion_angle = [40.6, 41.8]
//! ```

use crate::cut::{family, grade::Grade, CutSpace, Unit};
use crate::error::{shown, Error, Result};
use crate::optics::Material;
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
    /// Face-up colour (a coloured material): the weight search finds each family's plans,
    /// which are then ranked by the chroma C* of their face-up colour ([`super::colour`]); a
    /// layout's stones by worth × colour factor, worth the price (with a table) or carats.
    Colour(Option<PriceTable>),
}

/// The heaviest band limit a price table may give (carats).
pub const MAX_CARATS: f64 = 1e4;
/// The largest price per carat a price table may give: prices are finite, and a plan's value
/// (carats × price × factor) stays far from overflowing.
pub const MAX_PRICE: f64 = 1e12;
/// The largest quality factor.
pub const MAX_FACTOR: f64 = 100.0;

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
    /// Factor for a stone of a layout that keeps an inclusion inside (its lower clarity),
    /// the price file's `included`; `None`: no stone may hold an inclusion.
    pub included: Option<f64>,
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

    /// The lightest weight that has a price (the first band with a price above 0).
    pub fn first_priced(&self) -> f64 {
        self.bands
            .iter()
            .find(|(_, p)| *p > 0.0)
            .map_or(f64::INFINITY, |(f, _)| *f)
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
            included: Option<f64>,
        }
        let raw: Raw = toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| format!(":{}", crate::io::line_of(text, s.start)))
                .unwrap_or_default();
            Error::parse(format!("{source}{line}"), e.message())
        })?;
        let mut bands = Vec::new();
        for (i, b) in raw.band.iter().enumerate() {
            let field = |k: &str| format!("{source}: band {}: {k}", i + 1);
            if !(b.from_carats.is_finite() && (0.0..=MAX_CARATS).contains(&b.from_carats)) {
                return Err(Error::invalid(
                    field("from_carats"),
                    format!(
                        "{} is not allowed; give carats from 0 to {}",
                        shown(b.from_carats),
                        shown(MAX_CARATS)
                    ),
                ));
            }
            if let Some((f, _)) = bands.last() {
                if *f >= b.from_carats {
                    return Err(Error::invalid(
                        field("from_carats"),
                        format!(
                            "{} does not rise above the band before ({}); list the bands from the lightest up",
                            shown(b.from_carats),
                            shown(*f)
                        ),
                    ));
                }
            }
            if !(b.per_carat.is_finite() && (0.0..=MAX_PRICE).contains(&b.per_carat)) {
                return Err(Error::invalid(
                    field("per_carat"),
                    format!(
                        "{} is not allowed; give a price per carat from 0 to {}",
                        shown(b.per_carat),
                        shown(MAX_PRICE)
                    ),
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
        if bands.iter().all(|(_, p)| *p == 0.0) {
            return Err(Error::invalid(
                format!("{source}: band"),
                "every band's per_carat is 0: every plan would be worth nothing; give the prices",
            ));
        }
        let mut quality = BTreeMap::new();
        let mut ungraded = 1.0;
        for (k, v) in &raw.quality {
            if !(v.is_finite() && (0.0..=MAX_FACTOR).contains(v)) {
                return Err(Error::invalid(
                    format!("{source}: quality.{k}"),
                    format!(
                        "{} is not allowed; a factor is a number from 0 to {}",
                        shown(*v),
                        shown(MAX_FACTOR)
                    ),
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
        if let Some(f) = raw.included {
            if !(f.is_finite() && (0.0..=1.0).contains(&f)) {
                return Err(Error::invalid(
                    format!("{source}: included"),
                    format!(
                        "{} is not allowed; the factor of a stone holding an inclusion is a number from 0 to 1",
                        shown(f)
                    ),
                ));
            }
        }
        Ok(PriceTable {
            currency: raw.currency.unwrap_or_else(|| "USD".into()),
            bands,
            quality,
            ungraded,
            included: raw.included,
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
    /// The price file read for `value` (an input of the run, never to be overwritten).
    pub price_file: Option<PathBuf>,
    /// A uniaxial stone's c-axis in the rough's coordinates (unit), `[rough] c_axis`: each
    /// plan is scored with its optic axis where the rough puts it ([`Plan::optic_axis`]).
    /// `None`: the material's default axis, relative to each plan's table.
    ///
    /// [`Plan::optic_axis`]: super::Plan::optic_axis
    pub c_axis: Option<glam::DVec3>,
    /// Stones planned in the rough, `[rough] stones` (1: the single best cut of each family,
    /// as before; 2 and more: a layout of sawn pieces, [`super::layout`]).
    pub stones: usize,
    /// The saw's kerf (mm), `[rough] kerf_mm`: the slab a saw cut takes away.
    pub kerf_mm: f64,
    /// The polishing allowance per stone (mm), `[rough] allowance_mm`: every stone of a layout
    /// keeps at least this far inside its piece (its sawn faces and the rough's surface).
    pub allowance_mm: f64,
    /// How far a stone keeps from an inclusion (mm), `[rough] inclusion_margin_mm`.
    pub margin_mm: f64,
    /// Saw offsets tried per direction and piece, `[search] saw_offsets`.
    pub saw_offsets: usize,
    /// How a layout's stones are parted, `[rough] cutter`: straight saw cuts through a piece
    /// or laser cuts between pairs of stones ([`super::layout`]).
    pub cutter: Cutter,
}

/// How the stones of a layout are parted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Cutter {
    /// Sequential sawing: each cut a plane through the whole piece (guillotine cuts).
    #[default]
    Saw,
    /// A laser: each pair of stones apart by a kerf-wide gap along a plane, cut only between
    /// them.
    Laser,
}

impl Cutter {
    /// The names, as written in configs.
    pub const NAMES: [&'static str; 2] = ["saw", "laser"];

    /// The cutter named `name` (`saw` or `laser`); an error names `field`.
    pub fn named(field: &str, name: &str) -> Result<Cutter> {
        match name.trim() {
            "saw" => Ok(Cutter::Saw),
            "laser" => Ok(Cutter::Laser),
            _ => Err(Error::invalid(
                field,
                format!(
                    "\"{}\" is not allowed; give saw (straight cuts through a piece) or laser (a cut between each pair of stones)",
                    name.escape_default()
                ),
            )),
        }
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Cutter::Saw => "saw",
            Cutter::Laser => "laser",
        }
    }
}

/// The most stones a layout plans.
pub const MAX_STONES: usize = 8;
/// The largest kerf, allowance or inclusion margin (mm).
pub const MAX_GAP_MM: f64 = 10.0;

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
            price_file: None,
            c_axis: None,
            stones: 1,
            kerf_mm: 0.30,
            allowance_mm: 0.20,
            margin_mm: 0.30,
            saw_offsets: 5,
            cutter: Cutter::Saw,
        }
    }
}

/// The config file as written: numbers and lists are read as TOML values and checked here, so
/// that an error names the field and says what is allowed (not `expected usize`).
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawObjective {
    kind: Option<toml::Value>,
    grade: Option<toml::Value>,
    min_brilliance: Option<toml::Value>,
    prices: Option<toml::Value>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawRough {
    c_axis: Option<toml::Value>,
    stones: Option<toml::Value>,
    kerf_mm: Option<toml::Value>,
    allowance_mm: Option<toml::Value>,
    inclusion_margin_mm: Option<toml::Value>,
    cutter: Option<toml::Value>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawSearch {
    starts: Option<toml::Value>,
    max_iterations: Option<toml::Value>,
    saw_offsets: Option<toml::Value>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    name: Option<toml::Value>,
    seed: Option<toml::Value>,
    families: Option<toml::Value>,
    material: Option<toml::Value>,
    top: Option<toml::Value>,
    min_width_mm: Option<toml::Value>,
    #[serde(default)]
    objective: RawObjective,
    #[serde(default)]
    rough: RawRough,
    #[serde(default)]
    search: RawSearch,
    #[serde(default)]
    free: BTreeMap<String, BTreeMap<String, toml::Value>>,
}

/// `[rough] c_axis` named `field`: three numbers, not all 0, for a uniaxial `material`.
fn c_axis(field: String, v: &toml::Value, material: &str) -> Result<glam::DVec3> {
    let xyz: Option<Vec<f64>> = v
        .as_array()
        .filter(|a| a.len() == 3)
        .and_then(|a| a.iter().map(as_number).collect());
    let axis = xyz
        .map(|x| glam::DVec3::new(x[0], x[1], x[2]))
        .filter(|a| a.is_finite() && a.length() > 1e-9)
        .ok_or_else(|| {
            Error::invalid(
                field.clone(),
                format!(
                    "{} is not allowed; give the c-axis's direction in the rough's coordinates, three numbers not all 0, e.g. [0, 0, 1]",
                    quote(v)
                ),
            )
        })?;
    let uniaxial = Material::by_name(material).is_ok_and(|m| m.uniaxial.is_some());
    if !uniaxial {
        return Err(Error::invalid(
            field,
            format!(
                "{material} has no optic axis to place; a c-axis is for the uniaxial stones (quartz, beryl, tourmaline, sapphire and ruby, zircon, moissanite and their varieties)"
            ),
        ));
    }
    Ok(axis.normalize())
}

impl PlanConfig {
    /// Read a config file; a price file it names is read relative to it.
    pub fn load(path: &Path) -> Result<PlanConfig> {
        let shown = path.display().to_string();
        let bytes = crate::io::read_bytes(path)?;
        let text = String::from_utf8(bytes)
            .map_err(|_| Error::parse(&shown, "not UTF-8 text; a plan config is TOML"))?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("plan");
        let dir = path.parent().unwrap_or(Path::new("."));
        PlanConfig::parse(&text, &shown, stem, dir)
    }

    /// The files this config reads besides itself (its price table), as found.
    pub fn inputs(&self) -> Vec<PathBuf> {
        self.price_file.iter().cloned().collect()
    }

    /// Parse a config's text (`source` names it; `dir` is where a price file is looked up).
    pub fn parse(text: &str, source: &str, stem: &str, dir: &Path) -> Result<PlanConfig> {
        let raw: RawConfig = toml::from_str(text).map_err(|e| {
            let line = e
                .span()
                .map(|s| format!(":{}", crate::io::line_of(text, s.start)))
                .unwrap_or_default();
            Error::parse(format!("{source}{line}"), e.message())
        })?;
        let at = |f: &str| format!("{source}: {f}");
        let name = match &raw.name {
            Some(v) => string(at("name"), v, "\"rough-12\"")?.to_string(),
            None => stem.to_string(),
        };
        let mut c = PlanConfig {
            name,
            ..PlanConfig::default()
        };
        if let Some(v) = &raw.seed {
            c.seed = whole(at("seed"), v, 0, i64::MAX as u64, "a seed")?;
        }
        if let Some(v) = &raw.families {
            let names: Vec<String> = match v.as_array() {
                Some(list) => list
                    .iter()
                    .map(|f| string(at("families"), f, "\"oval\"").map(str::to_string))
                    .collect::<Result<_>>()?,
                None => {
                    return Err(Error::invalid(
                        at("families"),
                        format!(
                            "{} is not allowed; give a list of families, e.g. [\"round-brilliant\", \"oval\"]",
                            quote(v)
                        ),
                    ))
                }
            };
            c.families = check_families(&names).map_err(|m| Error::invalid(at("families"), m))?;
        }
        if let Some(v) = &raw.material {
            let name = string(at("material"), v, "\"diamond\"")?;
            Material::by_name(name).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(at("material"), message),
                other => other,
            })?;
            c.material = name.to_string();
        }
        if let Some(v) = &raw.top {
            c.top = whole(at("top"), v, 1, 50, "the plans kept per family")? as usize;
        }
        if let Some(v) = &raw.min_width_mm {
            c.min_width_mm = ranged(at("min_width_mm"), v, 0.0, 1000.0, "a width in mm")?;
        }
        if let Some(v) = &raw.search.starts {
            c.starts = whole(at("search.starts"), v, 1, 1000, "the starts per family")? as usize;
        }
        if let Some(v) = &raw.search.max_iterations {
            c.max_iterations = whole(
                at("search.max_iterations"),
                v,
                1,
                100_000,
                "the iterations per start",
            )?;
        }
        if let Some(v) = &raw.objective.grade {
            let g = string(at("objective.grade"), v, "\"excellent\"")?;
            c.grade = Some(Grade::parse(g).ok_or_else(|| {
                Error::invalid(
                    at("objective.grade"),
                    format!(
                        "unknown grade `{}`; allowed: excellent, very-good, good, fair, poor",
                        quote(v)
                    ),
                )
            })?);
        }
        if let Some(v) = &raw.objective.min_brilliance {
            c.min_brilliance = Some(ranged(
                at("objective.min_brilliance"),
                v,
                0.0,
                1.0,
                "a brilliance",
            )?);
        }
        let kind = match &raw.objective.kind {
            Some(v) => string(at("objective.kind"), v, "\"weight\"")?,
            None => "weight",
        };
        // The price file: "value" needs one; "colour" may price a layout's stones with one.
        let prices = match &raw.objective.prices {
            Some(p) if matches!(kind, "value" | "colour" | "color") => {
                let p = string(at("objective.prices"), p, "\"prices.toml\"")?;
                let path = dir.join(p);
                let shown = path.display().to_string();
                let bytes = crate::io::read_bytes(&path)?;
                let text = String::from_utf8_lossy(&bytes);
                c.price_file = Some(path);
                Some(PriceTable::parse(&text, &shown)?)
            }
            _ => None,
        };
        c.objective = match (kind, prices) {
            ("weight", _) => Objective::Weight,
            ("colour" | "color", t) => Objective::Colour(t),
            ("value", Some(t)) => Objective::Value(t),
            ("value", None) => {
                return Err(Error::invalid(
                    at("objective.prices"),
                    "kind = \"value\" needs a price file: prices = \"prices.toml\"",
                ))
            }
            (other, _) => {
                return Err(Error::invalid(
                    at("objective.kind"),
                    format!("unknown objective `{other}`; allowed: weight, value, colour"),
                ))
            }
        };
        for (fam, keys) in &raw.free {
            let space = family(fam).map_err(|e| Error::invalid(at("free"), e.to_string()))?;
            let mut out = BTreeMap::new();
            for (k, b) in keys {
                let field = at(&format!("free.{fam}.{k}"));
                let Some(r) = space.range(k) else {
                    return Err(Error::invalid(
                        field,
                        format!(
                            "not a parameter of {fam}; allowed: {}",
                            space.keys().join(", ")
                        ),
                    ));
                };
                let (l, h) = if r.open { ("(", ")") } else { ("[", "]") };
                let range = format!("{l}{}, {}{h}", shown(r.min), shown(r.max));
                let count = r.unit == Unit::Count;
                let pair = b
                    .as_array()
                    .filter(|a| a.len() == 2)
                    .and_then(|a| Some((as_number(&a[0])?, as_number(&a[1])?)));
                let bound = match (as_number(b), pair) {
                    (Some(v), _) if r.contains(v) && (!count || v.fract() == 0.0) => {
                        Bound::Fixed(v)
                    }
                    (_, Some(_)) if count => {
                        return Err(Error::invalid(
                            field,
                            format!(
                            "a whole-number parameter cannot be varied; fix it, e.g. `{k} = {}`",
                            shown(r.default)
                        ),
                        ))
                    }
                    (_, Some((lo, hi))) if r.contains(lo) && r.contains(hi) && lo < hi => {
                        Bound::Free(lo, hi)
                    }
                    _ => {
                        let what = if count {
                            format!("give a whole number in {range}")
                        } else {
                            format!("give a value or [min, max] with min < max, each in {range}")
                        };
                        return Err(Error::invalid(
                            field,
                            format!("{} is not allowed; {what}", quote(b)),
                        ));
                    }
                };
                out.insert(k.clone(), bound);
            }
            c.params.insert(fam.clone(), out);
        }
        if let Some(v) = &raw.rough.c_axis {
            c.c_axis = Some(c_axis(at("rough.c_axis"), v, &c.material)?);
        }
        if let Some(v) = &raw.rough.stones {
            c.stones = whole(
                at("rough.stones"),
                v,
                1,
                MAX_STONES as u64,
                "the stones planned in the rough",
            )? as usize;
        }
        let gap = |key: &str, v: &toml::Value| {
            ranged(
                at(&format!("rough.{key}")),
                v,
                0.0,
                MAX_GAP_MM,
                "a distance in mm",
            )
        };
        if let Some(v) = &raw.rough.kerf_mm {
            c.kerf_mm = gap("kerf_mm", v)?;
        }
        if let Some(v) = &raw.rough.allowance_mm {
            c.allowance_mm = gap("allowance_mm", v)?;
        }
        if let Some(v) = &raw.rough.inclusion_margin_mm {
            c.margin_mm = gap("inclusion_margin_mm", v)?;
        }
        if let Some(v) = &raw.rough.cutter {
            c.cutter = Cutter::named(
                &at("rough.cutter"),
                string(at("rough.cutter"), v, "\"laser\"")?,
            )?;
        }
        if let Some(v) = &raw.search.saw_offsets {
            c.saw_offsets = whole(
                at("search.saw_offsets"),
                v,
                1,
                50,
                "the saw offsets tried per direction",
            )? as usize;
        }
        Ok(c)
    }
}

mod families;
mod values;

use values::{as_number, quote, ranged, string, whole};

pub use families::check_families;

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
        // [rough] c_axis: three numbers not all 0, for a uniaxial stone.
        for bad in ["[0, 0, 0]", "[1, 2]", "\"up\"", "[1, \"a\", 0]"] {
            let m = e(&format!("material = \"sapphire\"\n[rough]\nc_axis = {bad}"));
            assert!(m.contains("p.toml: rough.c_axis"), "{m}");
        }
        let m = e("[rough]\nc_axis = [0, 0, 1]");
        assert!(m.contains("rough.c_axis") && m.contains("diamond"), "{m}");
    }

    #[test]
    fn a_c_axis_is_read_as_a_unit_direction() {
        let c = PlanConfig::parse(
            "material = \"ruby\"\n[rough]\nc_axis = [0, 3, 4]",
            "p.toml",
            "p",
            Path::new("."),
        )
        .unwrap();
        let a = c.c_axis.unwrap();
        assert!(
            (a - glam::DVec3::new(0.0, 0.6, 0.8)).length() < 1e-15,
            "{a}"
        );
        assert_eq!(PlanConfig::default().c_axis, None);
    }
}
