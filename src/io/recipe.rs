//! Recipes as TOML: a design written tier by tier ([`crate::design::recipe`]).
//!
//! ```toml
//! [design]
//! name = "Simple round"
//! gear = 96          # teeth (default 96); offset = 0 is the index at 6 o'clock
//! symmetry = 8       # the machine cuts a tier's facets from one index (default 1)
//! mirror = true      # (default false)
//! index = 1.54       # the RI the angles are for (default 1.54, GemCad's)
//!
//! [[tier]]           # tiers in cutting order
//! name = "P1"
//! angle = -42        # negative: pavilion (or side = "pavilion"); "=P1-2": an expression
//! indices = [96]     # or "3-93", "0:12:96", "12 x8"
//! centre = true      # one of: centre, meet = ["G1", "P1"], depth, scale, girdle, table
//! ```
//!
//! A `.toml` file with a `[design]` table or `[[tier]]` entries is a recipe; any other is a
//! cut spec ([`super::spec`]). [`load_cut`](super::load_cut) builds either, so every command
//! that takes a design takes a recipe.

use crate::design::recipe::{parse_indices, Angle, Place, Recipe, RecipeTier, Side, DEFAULT_INDEX};
use crate::error::{Error, Result};
use toml::{Table, Value};

/// Whether TOML `text` is a recipe (has `[design]` or `[[tier]]`), not a cut spec.
pub fn is_recipe(text: &str) -> bool {
    text.parse::<Table>()
        .map(|t| t.contains_key("design") || t.contains_key("tier"))
        .unwrap_or(false)
}

const DESIGN_KEYS: [&str; 10] = [
    "name",
    "gear",
    "offset",
    "symmetry",
    "mirror",
    "index",
    "fractional",
    "title",
    "notes",
    "author",
];
const TIER_KEYS: [&str; 11] = [
    "name", "angle", "indices", "side", "note", "meet", "centre", "depth", "scale", "girdle",
    "table",
];
const PLACES: [&str; 6] = ["meet", "centre", "depth", "scale", "girdle", "table"];

/// The recipe at `path` when it is one (a `.toml` file with `[design]` or `[[tier]]`), else
/// `None`; errors name the file.
pub fn read(path: &std::path::Path) -> Result<Option<Recipe>> {
    if !path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
    {
        return Ok(None);
    }
    let text = String::from_utf8_lossy(&super::read_bytes(path)?).to_string();
    if !is_recipe(&text) {
        return Ok(None);
    }
    let stem = path
        .file_stem()
        .map_or(String::new(), |s| s.to_string_lossy().to_string());
    parse(&text, &path.display().to_string(), &stem).map(Some)
}

/// Read a recipe from TOML `text`; `source` (the file name) and the field prefix errors.
/// `default_name` names a recipe without `name`.
///
/// ```
/// let text = "[design]\nsymmetry = 8\nmirror = true\n\
///     [[tier]]\nname = \"P1\"\nangle = -42\nindices = [96]\ncentre = true\n";
/// let r = facetlab::io::recipe::parse(text, "r.toml", "r").unwrap();
/// assert_eq!((r.gear, r.symmetry, r.tiers.len()), (96, 8, 1));
/// let e = facetlab::io::recipe::parse("[[tier]]\nname = \"P1\"\nangle = 40\n", "r.toml", "r");
/// assert!(e.unwrap_err().to_string().contains("tier P1"));
/// ```
pub fn parse(text: &str, source: &str, default_name: &str) -> Result<Recipe> {
    let table: Table = text.parse().map_err(|e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| format!(":{}", super::line_of(text, s.start)))
            .unwrap_or_default();
        Error::parse(format!("{source}{line}"), e.message().to_string())
    })?;
    let bad = |field: &str, msg: String| Error::parse(source, format!("{field}: {msg}"));
    for k in table.keys() {
        if k != "design" && k != "tier" {
            return Err(bad(
                k,
                "unknown table; a recipe has [design] and [[tier]]".into(),
            ));
        }
    }
    let empty = Table::new();
    let design = match table.get("design") {
        None => &empty,
        Some(Value::Table(t)) => t,
        Some(_) => return Err(bad("design", "must be a table ([design])".into())),
    };
    for k in design.keys() {
        if !DESIGN_KEYS.contains(&k.as_str()) {
            return Err(bad(
                &format!("design.{k}"),
                format!("unknown key; allowed: {}", DESIGN_KEYS.join(", ")),
            ));
        }
    }
    let int = |key: &str, default: u32| -> Result<u32> {
        match design.get(key) {
            None => Ok(default),
            Some(Value::Integer(i)) if *i > 0 && *i <= 100_000 => Ok(*i as u32),
            Some(v) => Err(bad(
                &format!("design.{key}"),
                format!("`{v}`: a whole number from 1"),
            )),
        }
    };
    let float = |v: &Value| -> Option<f64> {
        match v {
            Value::Float(x) => Some(*x),
            Value::Integer(i) => Some(*i as f64),
            _ => None,
        }
    };
    let strings = |key: &str| -> Result<Vec<String>> {
        match design.get(key) {
            None => Ok(Vec::new()),
            Some(Value::String(s)) => Ok(vec![s.clone()]),
            Some(Value::Array(a)) => a
                .iter()
                .map(|v| v.as_str().map(str::to_string))
                .collect::<Option<Vec<_>>>()
                .ok_or_else(|| bad(&format!("design.{key}"), "a list of strings".into())),
            Some(_) => Err(bad(
                &format!("design.{key}"),
                "a string or a list of strings".into(),
            )),
        }
    };
    let gear = int("gear", 96)?;
    let mut recipe = Recipe::new(
        design
            .get("name")
            .and_then(Value::as_str)
            .unwrap_or(default_name),
        gear,
        int("symmetry", 1)?,
        match design.get("mirror") {
            None => false,
            Some(Value::Boolean(b)) => *b,
            Some(v) => return Err(bad("design.mirror", format!("`{v}`: true or false"))),
        },
        match design.get("index") {
            None => DEFAULT_INDEX,
            Some(v) => float(v).ok_or_else(|| bad("design.index", format!("`{v}`: a number")))?,
        },
    );
    if let Some(v) = design.get("offset") {
        recipe.offset = float(v).ok_or_else(|| bad("design.offset", format!("`{v}`: a number")))?;
    }
    recipe.fractional = match design.get("fractional") {
        None => false,
        Some(Value::Boolean(b)) => *b,
        Some(v) => return Err(bad("design.fractional", format!("`{v}`: true or false"))),
    };
    recipe.title = strings("title")?;
    if let Some(a) = design.get("author").and_then(Value::as_str) {
        recipe.title.push(a.to_string());
    }
    recipe.notes = strings("notes")?;
    let tiers = match table.get("tier") {
        None => return Err(bad("tier", "the recipe has no [[tier]]".into())),
        Some(Value::Array(a)) => a,
        Some(_) => return Err(bad("tier", "tiers are [[tier]] tables".into())),
    };
    for (i, t) in tiers.iter().enumerate() {
        let Value::Table(t) = t else {
            return Err(bad("tier", "tiers are [[tier]] tables".into()));
        };
        let name = match t.get("name") {
            Some(Value::String(s)) => s.clone(),
            Some(Value::Integer(k)) => k.to_string(),
            _ => format!("{}", i + 1),
        };
        let field = format!("tier {name}");
        let tb = |msg: String| Error::parse(source, format!("{field}: {msg}"));
        for k in t.keys() {
            if !TIER_KEYS.contains(&k.as_str()) {
                return Err(tb(format!(
                    "unknown key `{k}`; allowed: {}",
                    TIER_KEYS.join(", ")
                )));
            }
        }
        if !t.contains_key("name") {
            return Err(tb("has no name".into()));
        }
        let angle = match t.get("angle") {
            Some(Value::String(s)) if s.trim_start().starts_with('=') => Angle::Expr(s.clone()),
            Some(Value::String(s)) => match s.trim().parse::<f64>() {
                Ok(x) => Angle::Degrees(x),
                Err(_) => {
                    return Err(tb(format!(
                    "angle `{s}`: a number of degrees or an expression starting with = (\"=P1-2\")"
                )))
                }
            },
            Some(v) => {
                Angle::Degrees(float(v).ok_or_else(|| tb(format!("angle `{v}`: a number")))?)
            }
            None => return Err(tb("has no angle".into())),
        };
        let side = match t.get("side").map(|v| v.as_str()) {
            None => None,
            Some(Some("crown")) => Some(Side::Crown),
            Some(Some("pavilion")) => Some(Side::Pavilion),
            Some(_) => return Err(tb("side: \"crown\" or \"pavilion\"".into())),
        };
        let indices = match t.get("indices") {
            None => Vec::new(),
            Some(Value::String(s)) => {
                parse_indices(s, gear).map_err(|m| tb(format!("indices {m}")))?
            }
            Some(Value::Integer(k)) => vec![*k as f64],
            Some(Value::Array(a)) => {
                let mut out = Vec::new();
                for v in a {
                    match v {
                        Value::String(s) => out.extend(
                            parse_indices(s, gear).map_err(|m| tb(format!("indices {m}")))?,
                        ),
                        v => out.push(
                            float(v)
                                .ok_or_else(|| tb(format!("indices: `{v}` is not an index")))?,
                        ),
                    }
                }
                out
            }
            Some(v) => return Err(tb(format!("indices `{v}`: a list or a text like \"3-93\""))),
        };
        let given: Vec<&str> = PLACES
            .iter()
            .copied()
            .filter(|k| t.contains_key(*k))
            .collect();
        if given.len() != 1 {
            return Err(tb(format!(
                "give exactly one of {} (how deep the tier is cut){}",
                PLACES.join(", "),
                if given.is_empty() {
                    String::new()
                } else {
                    format!("; got {}", given.join(" and "))
                }
            )));
        }
        let key = given[0];
        let v = &t[key];
        let number = || {
            float(v)
                .filter(|x| x.is_finite())
                .ok_or_else(|| tb(format!("{key} `{v}`: a number")))
        };
        let place = match key {
            "meet" => {
                let names = match v {
                    Value::String(s) => s
                        .split(['-', ',', ' '])
                        .filter(|x| !x.is_empty())
                        .map(str::to_string)
                        .collect(),
                    Value::Array(a) => a
                        .iter()
                        .map(|x| match x {
                            Value::String(s) => Some(s.clone()),
                            Value::Integer(k) => Some(k.to_string()),
                            _ => None,
                        })
                        .collect::<Option<Vec<_>>>()
                        .ok_or_else(|| tb("meet: a list of tier names".into()))?,
                    _ => return Err(tb("meet: a list of tier names, [\"G1\", \"P1\"]".into())),
                };
                Place::Meet(names)
            }
            "centre" => match v {
                Value::Boolean(true) => Place::Centre,
                _ => {
                    return Err(tb(
                        "centre: write centre = true (or another placement)".into()
                    ))
                }
            },
            "depth" => Place::Depth(number()?),
            "scale" => Place::Scale(number()?),
            "girdle" => Place::Girdle(number()?),
            _ => Place::Table(number()?),
        };
        let note = match t.get("note") {
            None => None,
            Some(Value::String(s)) => Some(s.clone()),
            Some(_) => return Err(tb("note: a string".into())),
        };
        recipe.tiers.push(RecipeTier {
            name,
            angle,
            side,
            indices,
            place,
            note,
        });
    }
    Ok(recipe)
}

/// A number as TOML, exactly (shortest round trip).
fn num(x: f64) -> String {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        format!("{x:.1}")
    } else {
        format!("{x}")
    }
}

fn quoted(s: &str) -> String {
    Value::String(s.to_string()).to_string()
}

/// A recipe as TOML text that [`parse`] reads back to the same recipe.
///
/// ```
/// use facetlab::design::recipe::{Place, Recipe, RecipeTier};
/// let mut r = Recipe::new("r", 96, 8, true, 1.54);
/// r.add(RecipeTier::new("P1", -42.0, &[96.0], Place::Centre));
/// let back = facetlab::io::recipe::parse(&facetlab::io::recipe::write(&r), "r.toml", "x").unwrap();
/// assert_eq!(back, r);
/// ```
pub fn write(r: &Recipe) -> String {
    let mut s = String::new();
    s.push_str("# A facetlab recipe: the design's tiers in cutting order (facetlab design RECIPE -o OUT.asc).\n");
    s.push_str("[design]\n");
    s.push_str(&format!("name = {}\n", quoted(&r.name)));
    s.push_str(&format!("gear = {}\n", r.gear));
    if r.offset != 0.0 {
        s.push_str(&format!("offset = {}\n", num(r.offset)));
    }
    s.push_str(&format!("symmetry = {}\n", r.symmetry));
    s.push_str(&format!("mirror = {}\n", r.mirror));
    s.push_str(&format!("index = {}\n", num(r.index)));
    if r.fractional {
        s.push_str("fractional = true\n");
    }
    let list = |v: &[String]| v.iter().map(|x| quoted(x)).collect::<Vec<_>>().join(", ");
    if !r.title.is_empty() {
        s.push_str(&format!("title = [{}]\n", list(&r.title)));
    }
    if !r.notes.is_empty() {
        s.push_str(&format!("notes = [{}]\n", list(&r.notes)));
    }
    for t in &r.tiers {
        s.push_str("\n[[tier]]\n");
        s.push_str(&format!("name = {}\n", quoted(&t.name)));
        match &t.angle {
            Angle::Degrees(a) if *a == 0.0 && a.is_sign_negative() => s.push_str("angle = -0.0\n"),
            Angle::Degrees(a) => s.push_str(&format!("angle = {}\n", num(*a))),
            Angle::Expr(e) => s.push_str(&format!("angle = {}\n", quoted(e))),
        }
        if let Some(side) = t.side {
            s.push_str(&format!("side = \"{}\"\n", side.name()));
        }
        if !t.indices.is_empty() {
            let ix: Vec<String> = t
                .indices
                .iter()
                .map(|&x| {
                    if x.fract() == 0.0 {
                        format!("{}", x as i64)
                    } else {
                        num(x)
                    }
                })
                .collect();
            s.push_str(&format!("indices = [{}]\n", ix.join(", ")));
        }
        match &t.place {
            Place::Meet(m) => s.push_str(&format!("meet = [{}]\n", list(m))),
            Place::Centre => s.push_str("centre = true\n"),
            Place::Depth(d) => s.push_str(&format!("depth = {}\n", num(*d))),
            Place::Scale(d) => s.push_str(&format!("scale = {}\n", num(*d))),
            Place::Girdle(g) => s.push_str(&format!("girdle = {}\n", num(*g))),
            Place::Table(w) => s.push_str(&format!("table = {}\n", num(*w))),
        }
        if let Some(n) = &t.note {
            s.push_str(&format!("note = {}\n", quoted(n)));
        }
    }
    s
}
