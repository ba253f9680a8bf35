//! Recipes in Python: `facetlab.Recipe`, a design written tier by tier as a faceter cuts it
//! ([`crate::design::recipe`]): `add_tier`, `build` (a `Cut`), `steps`, `findings`, the TOML
//! form (`to_toml`, `Recipe.from_toml`) and the recipe of any design (`Recipe.from_design`).

use super::args::whole_in;
use super::call::{error, run};
use super::cuts::{cut_of, PyCut};
use crate::design::recipe::{
    infer, parse_indices, Angle, FindingKind, Place, Recipe, RecipeTier, Side, DEFAULT_INDEX,
};
use crate::error::Error;
use crate::io;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyType};

/// A design written tier by tier, as a faceter cuts it: each tier an angle, indices on the
/// gear (the symmetry cuts the rest) and one placement (`meet`, `centre`, `depth`, `scale`,
/// `girdle` or `table`). ``build()`` cuts it from a block into a `Cut`.
///
/// >>> r = facetlab.Recipe(name="simple", gear=96, symmetry=8, mirror=True, index=1.54)
/// >>> r.add_tier("P1", -42, [96], centre=True)
/// >>> r.add_tier("G1", 90, [96], depth=0.9)
/// >>> r.add_tier("C1", 38, [96], girdle=0.03)
/// >>> r.add_tier("T", 0, table=0.55)
/// >>> r.build().facets
/// 25
#[pyclass(name = "Recipe", module = "facetlab")]
#[derive(Clone)]
pub struct PyRecipe {
    recipe: Recipe,
}

fn tier_err(name: &str, msg: impl Into<String>) -> PyErr {
    error(Error::invalid(format!("tier {name}"), msg))
}

/// A number argument of tier `name`'s keyword `key`: finite.
fn finite(name: &str, key: &str, v: Option<f64>) -> PyResult<Option<f64>> {
    match v {
        Some(x) if !x.is_finite() => Err(tier_err(name, format!("{key} {x}: a finite number"))),
        other => Ok(other),
    }
}

/// `Recipe`'s `gear`: 3 to 1000 teeth.
fn gear(obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    Ok(whole_in(obj, "gear", 3, 1000)? as u32)
}

/// `Recipe`'s `symmetry`: 1 to 1000.
fn symmetry(obj: &Bound<'_, PyAny>) -> PyResult<u32> {
    Ok(whole_in(obj, "symmetry", 1, 1000)? as u32)
}

// The literal default of `index` in `Recipe`'s signature is the library's.
const _: () = assert!(DEFAULT_INDEX == 1.54);

#[pymethods]
impl PyRecipe {
    #[new]
    #[pyo3(signature = (name="recipe", gear=96, symmetry=1, mirror=false, index=1.54, *, offset=0.0, fractional=false))]
    fn new(
        name: &str,
        #[pyo3(from_py_with = gear)] gear: u32,
        #[pyo3(from_py_with = symmetry)] symmetry: u32,
        mirror: bool,
        index: f64,
        offset: f64,
        fractional: bool,
    ) -> PyResult<PyRecipe> {
        let mut recipe = Recipe::new(name, gear, symmetry, mirror, index);
        recipe.offset = offset;
        recipe.fractional = fractional;
        Ok(PyRecipe { recipe })
    }

    /// The design's name.
    #[getter]
    fn name(&self) -> &str {
        &self.recipe.name
    }

    /// The tiers' names, in cutting order.
    #[getter]
    fn tiers(&self) -> Vec<String> {
        self.recipe.tiers.iter().map(|t| t.name.clone()).collect()
    }

    /// Add a tier, cut after those added before. `angle`: degrees from the girdle plane
    /// (negative: pavilion; 90: girdle; 0: table, or culet with ``side="pavilion"``) or an
    /// expression of earlier tiers (``"=P1-2"``); `indices`: a list, or a text such as
    /// ``"3-93"``, ``"0:12:96"`` or ``"12 x8"``; exactly one placement: ``meet=["G1", "P1"]``
    /// (or ``"G1-P1"``), ``centre=True``, ``depth=``, ``scale=``, ``girdle=`` (a fraction of
    /// the width) or ``table=`` (a fraction of the width). Bad input is `facetlab.Error`
    /// naming the tier.
    ///
    /// >>> r = facetlab.Recipe(symmetry=8, mirror=True)
    /// >>> r.add_tier("P1", -42, "0:12:96", centre=True)
    /// >>> try:
    /// ...     r.add_tier("P2", "=P1-1", [6], centre=True, depth=1.0)
    /// ... except facetlab.Error as e:
    /// ...     print(e)
    /// tier P2: give exactly one of meet, centre, depth, scale, girdle, table (how deep the tier is cut); got centre and depth
    #[pyo3(signature = (name, angle, indices=None, *, meet=None, centre=false, depth=None,
        scale=None, girdle=None, table=None, side=None, note=None))]
    #[allow(clippy::too_many_arguments)]
    fn add_tier(
        &mut self,
        name: &str,
        angle: &Bound<'_, PyAny>,
        indices: Option<&Bound<'_, PyAny>>,
        meet: Option<&Bound<'_, PyAny>>,
        centre: bool,
        depth: Option<f64>,
        scale: Option<f64>,
        girdle: Option<f64>,
        table: Option<f64>,
        side: Option<&str>,
        note: Option<String>,
    ) -> PyResult<()> {
        let gear = self.recipe.gear;
        let angle = if let Ok(s) = angle.cast::<PyString>() {
            let s: String = s.extract()?;
            if s.trim_start().starts_with('=') {
                Angle::Expr(s)
            } else {
                Angle::Degrees(s.trim().parse::<f64>().map_err(|_| {
                    tier_err(
                        name,
                        format!("angle `{s}`: a number of degrees or an expression starting with = (\"=P1-2\")"),
                    )
                })?)
            }
        } else {
            match angle.extract::<f64>() {
                Ok(a) if a.is_finite() => Angle::Degrees(a),
                _ => {
                    return Err(tier_err(
                        name,
                        format!(
                            "angle `{angle}`: a number of degrees or an expression (\"=P1-2\")"
                        ),
                    ))
                }
            }
        };
        let parse =
            |s: &str| parse_indices(s, gear).map_err(|m| tier_err(name, format!("indices {m}")));
        let indices: Vec<f64> = match indices {
            None => Vec::new(),
            Some(v) if v.is_none() => Vec::new(),
            Some(v) => {
                if let Ok(s) = v.cast::<PyString>() {
                    parse(&s.extract::<String>()?)?
                } else if let Ok(x) = v.extract::<f64>() {
                    vec![x]
                } else if let Ok(list) = v.try_iter() {
                    let mut out = Vec::new();
                    for item in list {
                        let item = item?;
                        if let Ok(s) = item.cast::<PyString>() {
                            out.extend(parse(&s.extract::<String>()?)?);
                        } else {
                            out.push(item.extract::<f64>().map_err(|_| {
                                tier_err(name, format!("indices: `{item}` is not an index"))
                            })?);
                        }
                    }
                    out
                } else {
                    return Err(tier_err(
                        name,
                        format!("indices `{v}`: a list of indices or a text like \"3-93\""),
                    ));
                }
            }
        };
        let depth = finite(name, "depth", depth)?;
        let scale = finite(name, "scale", scale)?;
        let girdle = finite(name, "girdle", girdle)?;
        let table = finite(name, "table", table)?;
        let meet: Option<Vec<String>> = match meet {
            None => None,
            Some(m) if m.is_none() => None,
            Some(m) => Some(if let Ok(s) = m.cast::<PyString>() {
                s.extract::<String>()?
                    .split(['-', ',', ' '])
                    .filter(|x| !x.is_empty())
                    .map(str::to_string)
                    .collect()
            } else {
                m.extract::<Vec<String>>().map_err(|_| {
                    tier_err(
                        name,
                        "meet: a list of tier names, [\"G1\", \"P1\"], or \"G1-P1\"",
                    )
                })?
            }),
        };
        let given: Vec<&str> = [
            ("meet", meet.is_some()),
            ("centre", centre),
            ("depth", depth.is_some()),
            ("scale", scale.is_some()),
            ("girdle", girdle.is_some()),
            ("table", table.is_some()),
        ]
        .iter()
        .filter(|(_, g)| *g)
        .map(|(k, _)| *k)
        .collect();
        if given.len() != 1 {
            return Err(tier_err(
                name,
                format!(
                    "give exactly one of meet, centre, depth, scale, girdle, table (how deep the tier is cut){}",
                    if given.is_empty() {
                        String::new()
                    } else {
                        format!("; got {}", given.join(" and "))
                    }
                ),
            ));
        }
        let place = if let Some(m) = meet {
            Place::Meet(m)
        } else if centre {
            Place::Centre
        } else if let Some(d) = depth {
            Place::Depth(d)
        } else if let Some(d) = scale {
            Place::Scale(d)
        } else if let Some(g) = girdle {
            Place::Girdle(g)
        } else {
            Place::Table(table.unwrap_or_default())
        };
        let side = match side {
            None => None,
            Some("crown") => Some(Side::Crown),
            Some("pavilion") => Some(Side::Pavilion),
            Some(s) => {
                return Err(tier_err(
                    name,
                    format!("side `{s}`: \"crown\" or \"pavilion\""),
                ))
            }
        };
        self.recipe.tiers.push(RecipeTier {
            name: name.to_string(),
            angle,
            side,
            indices,
            place,
            note,
        });
        Ok(())
    }

    /// Cut the tiers in order from a block: the stone as a `Cut` (width 1, with the recipe's
    /// gear, symmetry and index as its GemCad record), to score, render or write. A tier that
    /// cannot be cut is `facetlab.Error` naming it.
    ///
    /// >>> r = facetlab.Recipe.from_design("tolkowsky")
    /// >>> c = r.build()
    /// >>> c.facets, round(facetlab.score(c).brilliance, 2) > 0.5
    /// (73, True)
    fn build(&self, py: Python<'_>) -> PyResult<PyCut> {
        let r = &self.recipe;
        let built = run(py, || r.build())?;
        Ok(PyCut { cut: built.cut })
    }

    /// One dict per tier as it is cut (the cutting sheet's rows): ``tier``, ``angle`` (GemCad's:
    /// negative on the pavilion), ``indices`` (after the symmetry), ``depth`` (distance from the
    /// axis point in widths), ``instruction`` and ``facets`` (their names on the cut).
    ///
    /// >>> s = facetlab.Recipe.from_design("tolkowsky").steps()
    /// >>> s[0]["tier"], s[0]["instruction"]
    /// ('P1', 'cut to centre point')
    fn steps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let r = &self.recipe;
        let built = run(py, || r.build())?;
        let out = PyList::empty(py);
        for s in &built.steps {
            let d = PyDict::new(py);
            d.set_item("tier", &s.tier)?;
            d.set_item("angle", s.angle)?;
            d.set_item("indices", s.indices.clone())?;
            d.set_item("depth", s.depth)?;
            d.set_item("instruction", &s.instruction)?;
            d.set_item("facets", s.facets.clone())?;
            out.append(d)?;
        }
        Ok(out)
    }

    /// What a faceter should hear about the recipe (it builds all the same): one dict per
    /// finding, ``tier``, ``kind`` (``"small-facet"``: under 1 % of the width;
    /// ``"below-critical"``: a pavilion tier flatter than the critical angle) and ``message``.
    ///
    /// >>> r = facetlab.Recipe(symmetry=8, mirror=True, index=1.54)
    /// >>> r.add_tier("P1", -38, [96], centre=True)
    /// >>> r.add_tier("G1", 90, [96], depth=0.9)
    /// >>> r.add_tier("C1", 38, [96], girdle=0.03)
    /// >>> r.add_tier("T", 0, table=0.55)
    /// >>> [(f["tier"], f["kind"]) for f in r.findings()]
    /// [('P1', 'below-critical')]
    fn findings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let r = &self.recipe;
        let built = run(py, || r.build())?;
        let out = PyList::empty(py);
        for f in &built.findings {
            let d = PyDict::new(py);
            d.set_item("tier", &f.tier)?;
            d.set_item(
                "kind",
                match f.kind {
                    FindingKind::SmallFacet => "small-facet",
                    FindingKind::BelowCritical => "below-critical",
                },
            )?;
            d.set_item("message", &f.message)?;
            out.append(d)?;
        }
        Ok(out)
    }

    /// The recipe as TOML, the file `facetlab design RECIPE.toml -o OUT` builds.
    ///
    /// >>> r = facetlab.Recipe(name="r", symmetry=8, mirror=True)
    /// >>> r.add_tier("P1", -42, [96], centre=True)
    /// >>> print(r.to_toml().split("[[tier]]")[1].strip())
    /// name = "P1"
    /// angle = -42.0
    /// indices = [96]
    /// centre = true
    fn to_toml(&self) -> String {
        io::recipe::write(&self.recipe)
    }

    /// A recipe from its TOML text (a recipe file's contents); `name` names it when the text
    /// has no ``name``. An error names `text` and the tier (``text: tier P2: …``).
    ///
    /// >>> r = facetlab.Recipe.from_toml(facetlab.Recipe.from_design("tolkowsky").to_toml())
    /// >>> r.tiers[:3]
    /// ['P1', 'G1', 'P2']
    #[classmethod]
    #[pyo3(signature = (text, name="recipe"))]
    fn from_toml(
        _cls: &Bound<'_, PyType>,
        py: Python<'_>,
        text: &str,
        name: &str,
    ) -> PyResult<PyRecipe> {
        let recipe = run(py, || io::recipe::parse(text, "text", name))?;
        Ok(PyRecipe { recipe })
    }

    /// The recipe of an existing design (a `Cut`, a preset name or a path), as
    /// `facetlab design --from` writes it: each tier placed as a faceter would place it, so
    /// that building it gives back the same solid.
    ///
    /// >>> r = facetlab.Recipe.from_design("tolkowsky")
    /// >>> abs(r.build().info()["volume"] - facetlab.cut("tolkowsky").info()["volume"]) < 1e-9
    /// True
    #[classmethod]
    fn from_design(_cls: &Bound<'_, PyType>, design: &Bound<'_, PyAny>) -> PyResult<PyRecipe> {
        let cut = cut_of(design)?;
        let recipe = run(design.py(), || infer(&cut).map(|i| i.recipe))?;
        Ok(PyRecipe { recipe })
    }

    fn __len__(&self) -> usize {
        self.recipe.tiers.len()
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyRecipe>()
            .is_ok_and(|o| o.borrow().recipe == self.recipe)
    }

    fn __repr__(&self) -> String {
        format!(
            "<Recipe {} ({} tiers, {} gear, {}-fold{})>",
            self.recipe.name,
            self.recipe.tiers.len(),
            self.recipe.gear,
            self.recipe.symmetry,
            if self.recipe.mirror { ", mirror" } else { "" }
        )
    }
}

/// Add the `Recipe` class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyRecipe>()
}
