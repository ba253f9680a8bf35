//! The keyword arguments of `score`, `score_many` and `render`, listed once ([`SCORE`],
//! [`RENDER`]: each keyword's name, type and default) and parsed from `**kwargs` into
//! [`Keywords`], from which [`super::stone::StoneArgs`], the score and the render settings
//! are read. The stubs (`_facetlab.pyi`) spell the same lists as `TypedDict`s for type
//! checkers; `_keywords()` hands these lists to the test that checks the stubs against them.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A keyword's Python type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Kind {
    Str,
    Float,
    Bool,
    Int,
    /// A number or text (a size in mm or `"LxW"`, a tilt in degrees or `"DEG@AZ"`).
    Size,
}

/// A keyword's default (`None`: the keyword is optional, `Optional[...]` in the stubs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Value {
    None,
    Bool(bool),
    Float(f64),
    Int(i64),
    Str(&'static str),
}

/// One keyword argument.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Keyword {
    pub name: &'static str,
    pub kind: Kind,
    pub default: Value,
}

const fn kw(name: &'static str, kind: Kind, default: Value) -> Keyword {
    Keyword {
        name,
        kind,
        default,
    }
}

/// The keyword argument that sets each library setting an error names, as its field or inside
/// its text ([`crate::error::setting`]), as the command line's `FLAGS` names its flag; a
/// setting with no keyword here is shown by its own name. A picture's settings are
/// [`crate::render::settings::SETTINGS`].
pub(crate) const SETTINGS: &[(&str, &str)] = &[
    ("rough size", "size_mm"),
    ("photon count", "photons"),
    ("output", "path"),
    ("force", "overwrite=True"),
    ("picture light", "light"),
    ("picture size", "size"),
    ("picture tilt", "tilt"),
    ("picture head-shadow", "head_shadow"),
    ("picture exposure", "exposure"),
    ("picture view", "view"),
    ("picture distance", "distance"),
    ("picture aperture", "aperture"),
    ("picture ground", "ground"),
    ("picture ground-gap", "ground_gap"),
    ("picture light-rotation", "light_rotation"),
    ("picture tone", "tone"),
    ("picture bands", "bands"),
    ("picture diameter-mm", "diameter_mm"),
];

/// The keyword argument of the library's setting `name` ([`SETTINGS`]).
pub(crate) fn keyword_of(name: &str) -> Option<String> {
    SETTINGS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, k)| k.to_string())
}

/// The stone: material, body colour, size and crystal settings ([`super::stone::StoneArgs`]).
pub(crate) const STONE: [Keyword; 9] = [
    kw("material", Kind::Str, Value::None),
    kw("ri", Kind::Float, Value::None),
    kw("colour", Kind::Str, Value::None),
    kw("colour_density", Kind::Float, Value::None),
    kw("size_mm", Kind::Size, Value::None),
    kw("diameter_mm", Kind::Float, Value::None),
    kw("birefringence", Kind::Bool, Value::None),
    kw("optic_axis", Kind::Str, Value::None),
    kw("colour_e", Kind::Str, Value::None),
];

/// `score` and `score_many`: the stone, then the scoring settings.
pub(crate) const SCORE: [&[Keyword]; 2] = [
    &STONE,
    &[
        kw("polarization", Kind::Bool, Value::Bool(true)),
        kw(
            "head_shadow",
            Kind::Float,
            Value::Float(crate::metrics::DEFAULT_HEAD_SHADOW_DEG),
        ),
    ],
];

/// `render`: the picture's settings (a photograph's from `view` to `bands`), the stone, and
/// the array's type.
pub(crate) const RENDER: [&[Keyword]; 3] = [
    &[
        kw("light", Kind::Str, Value::Str("iso")),
        kw("size", Kind::Int, Value::Int(256)),
        kw("tilt", Kind::Size, Value::None),
        kw("view", Kind::Size, Value::None),
        kw("distance", Kind::Float, Value::None),
        kw("aperture", Kind::Float, Value::None),
        kw("ground", Kind::Str, Value::None),
        kw("ground_gap", Kind::Float, Value::None),
        kw("light_rotation", Kind::Float, Value::None),
        kw("tone", Kind::Str, Value::None),
        kw("bands", Kind::Int, Value::None),
        kw("head_shadow", Kind::Float, Value::None),
        kw("exposure", Kind::Float, Value::Float(1.0)),
        kw("polarization", Kind::Bool, Value::Bool(true)),
    ],
    &STONE,
    &[kw("float64", Kind::Bool, Value::Bool(false))],
];

/// The keyword arguments a call was given, checked against its list.
pub(crate) struct Keywords<'py> {
    lists: &'static [&'static [Keyword]],
    given: Vec<(&'static str, Bound<'py, PyAny>)>,
}

impl<'py> Keywords<'py> {
    /// The `kwargs` of `function`: a keyword not in `lists` is a `TypeError` as Python's own
    /// (`score() got an unexpected keyword argument 'x'`); `None` stands for not given.
    pub fn parse(
        function: &str,
        lists: &'static [&'static [Keyword]],
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Keywords<'py>> {
        let mut given = Vec::new();
        for (k, v) in kwargs.into_iter().flat_map(|d| d.iter()) {
            let name: String = k.extract()?;
            let Some(kw) = find(lists, &name) else {
                return Err(PyTypeError::new_err(format!(
                    "{function}() got an unexpected keyword argument '{name}'"
                )));
            };
            if !v.is_none() {
                given.push((kw.name, v));
            }
        }
        Ok(Keywords { lists, given })
    }

    fn keyword(&self, name: &str) -> Keyword {
        find(self.lists, name).unwrap_or_else(|| panic!("`{name}` is in no keyword list"))
    }

    /// The value given for `name` (not `None`), as `T`; a value of another type is
    /// `facetlab.Error` naming the keyword and its type.
    fn get<T: pyo3::conversion::FromPyObjectOwned<'py>>(&self, name: &str) -> PyResult<Option<T>> {
        let kind = self.keyword(name).kind;
        let Some((_, v)) = self.given.iter().find(|(n, _)| *n == name) else {
            return Ok(None);
        };
        let wrong = || {
            super::Error::new_err(format!(
                "{name}: `{v}` is not allowed; give {}",
                match kind {
                    Kind::Str => "a str",
                    Kind::Float => "a number",
                    Kind::Bool => "True or False",
                    Kind::Int => "a whole number",
                    Kind::Size => "a number or a str",
                }
            ))
        };
        // Python's bool is an int: a number keyword takes no True/False.
        let is_bool = v.is_instance_of::<pyo3::types::PyBool>();
        if is_bool != (kind == Kind::Bool) {
            return Err(wrong());
        }
        v.extract::<T>().map(Some).map_err(|_| wrong())
    }

    /// A text keyword, `None` when not given.
    pub fn opt_str(&self, name: &str) -> PyResult<Option<String>> {
        self.get(name)
    }
    /// A number keyword, `None` when not given.
    pub fn opt_f64(&self, name: &str) -> PyResult<Option<f64>> {
        self.get(name)
    }
    /// An on/off keyword, `None` when not given.
    pub fn opt_bool(&self, name: &str) -> PyResult<Option<bool>> {
        self.get(name)
    }
    /// A number-or-text keyword as the command line's text (a number as Rust writes it).
    pub fn size_text(&self, name: &str) -> PyResult<Option<String>> {
        let Some((_, v)) = self.given.iter().find(|(n, _)| *n == name) else {
            return Ok(None);
        };
        if !v.is_instance_of::<pyo3::types::PyBool>() {
            if let Ok(x) = v.extract::<f64>() {
                return Ok(Some(format!("{x}")));
            }
        }
        self.get(name)
    }
    /// Any keyword's value as the command line's text, for the library to parse (a number as
    /// Rust writes it: `0.5`, `11`), or its default; `None` when neither. A value of another
    /// type than the keyword's is refused first, as [`Keywords::get`] refuses it.
    pub fn text(&self, name: &str) -> PyResult<Option<String>> {
        let given = match self.keyword(name).kind {
            Kind::Str => self.get::<String>(name)?,
            // NaN as Python writes it (`str(float("nan"))`), so the error quotes what was given.
            Kind::Float => self.get::<f64>(name)?.map(|x| {
                if x.is_nan() {
                    "nan".to_string()
                } else {
                    format!("{x}")
                }
            }),
            Kind::Int => self.get::<i64>(name)?.map(|x| x.to_string()),
            Kind::Size => self.size_text(name)?,
            Kind::Bool => self.get::<bool>(name)?.map(|b| b.to_string()),
        };
        Ok(given.or_else(|| match self.keyword(name).default {
            Value::None => None,
            Value::Bool(b) => Some(b.to_string()),
            Value::Float(x) => Some(format!("{x}")),
            Value::Int(i) => Some(i.to_string()),
            Value::Str(s) => Some(s.to_string()),
        }))
    }
    /// A text keyword, or its default.
    pub fn str(&self, name: &str) -> PyResult<String> {
        match (self.get(name)?, self.keyword(name).default) {
            (Some(s), _) => Ok(s),
            (None, Value::Str(d)) => Ok(d.to_string()),
            (None, d) => panic!("`{name}` has no text default: {d:?}"),
        }
    }
    /// A number keyword, or its default.
    pub fn f64(&self, name: &str) -> PyResult<f64> {
        match (self.get(name)?, self.keyword(name).default) {
            (Some(x), _) => Ok(x),
            (None, Value::Float(d)) => Ok(d),
            (None, d) => panic!("`{name}` has no number default: {d:?}"),
        }
    }
    /// An on/off keyword, or its default.
    pub fn bool(&self, name: &str) -> PyResult<bool> {
        match (self.get(name)?, self.keyword(name).default) {
            (Some(x), _) => Ok(x),
            (None, Value::Bool(d)) => Ok(d),
            (None, d) => panic!("`{name}` has no on/off default: {d:?}"),
        }
    }
}

fn find(lists: &[&[Keyword]], name: &str) -> Option<Keyword> {
    lists
        .iter()
        .flat_map(|l| l.iter())
        .find(|k| k.name == name)
        .copied()
}

/// A keyword for the test of the stubs: `(name, type, default)`, e.g. `("ri", "float",
/// "None")` (the stubs' `TypedDict`s annotate each `Optional[type]`: None is "not given").
fn stub(k: &Keyword) -> (&'static str, &'static str, String) {
    let kind = match k.kind {
        Kind::Str => "str",
        Kind::Float => "float",
        Kind::Bool => "bool",
        Kind::Int => "int",
        Kind::Size => "Size",
    };
    let default = match k.default {
        Value::None => "None".into(),
        Value::Bool(b) => if b { "True" } else { "False" }.into(),
        Value::Float(x) => format!("{x:?}"),
        Value::Int(i) => i.to_string(),
        Value::Str(s) => format!("'{s}'"),
    };
    (k.name, kind, default)
}

/// For the test of the stubs: each function's keyword arguments, `{function: [(name, type,
/// default), …]}`.
#[pyfunction]
fn _keywords(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    let all: [(&str, &[&[Keyword]]); 3] = [
        ("score", &SCORE),
        ("score_many", &SCORE),
        ("render", &RENDER),
    ];
    for (f, lists) in all {
        let rows: Vec<_> = lists.iter().flat_map(|l| l.iter()).map(stub).collect();
        out.set_item(f, rows)?;
    }
    Ok(out)
}

/// Add `_keywords` to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(_keywords, m)?)?;
    Ok(())
}
