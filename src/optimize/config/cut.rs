//! `[cut]`: the cut space (a family, or a design's tier angles) and the start cut.

use super::fields::At;
use crate::cut::GemcadRecord;
use crate::cut::{family, Cut, CutSpace};
use crate::design::recipe::{Recipe, RecipeSpace};
use crate::design::{DesignSpace, OpenMeets, MEET_TOL};
use crate::error::{shown, Error, Result};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// `[cut]`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCut {
    /// Family name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// A design: a `.asc`, `.toml`, `.obj` or `.stl` file (relative to the config), or a
    /// preset's name; its tier angles are the parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<String>,
    /// A design's meets that the free angles cannot keep: `refuse` (default) or `allow`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub open_meets: Option<String>,
    /// A free range in which the design changes (a facet vanishes, an edge appears or
    /// vanishes): `refuse` (default, the config is refused naming the angle) or `skip` (the
    /// search counts such points as failed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub facet_changes: Option<String>,
    /// Within how much of W four or more facet planes make a meet (default 1e-4).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub meet_tol: Option<f64>,
    /// Parameters of the start cut (fixed ones and the free ones' start values).
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

/// The validated `[cut]`.
pub(super) struct CutSection {
    /// The space searched.
    pub space: Arc<dyn CutSpace>,
    /// The start cut's parameters, every default filled in.
    pub start: BTreeMap<String, f64>,
    /// The design, when the space is one (for the meets check and the writing back).
    pub design: Option<Arc<DesignSpace>>,
    /// The design file as the config names it and where it was found (`None` for a preset).
    pub file: Option<(String, Option<PathBuf>)>,
    /// `facet_changes = "skip"`: free ranges in which the design changes are searched anyway.
    pub skip_changes: bool,
    /// The GemCad record of a design or recipe (its index and notes choose the material).
    pub record: Option<GemcadRecord>,
}

/// Where a `[cut] file` may be read from.
#[derive(Clone, Copy)]
pub(super) enum Designs<'a> {
    /// A file relative to the config's folder, or a preset's name.
    Files,
    /// No file: a preset's name, or a design the function gives (`None`: not one of them).
    Only(&'a dyn Fn(&str) -> Option<Result<Cut>>),
}

/// Validate `[cut]`: the cut space and the start cut's full parameter set (defaults filled in).
/// A `file` is found relative to the config's folder (`source` is the config's path).
pub(super) fn validate(
    rc: &RawCut,
    source: &str,
    at: At,
    designs: Designs<'_>,
) -> Result<CutSection> {
    let (space, design, file): (Arc<dyn CutSpace>, _, _) = match (&rc.family, &rc.file) {
        (Some(_), Some(_)) => {
            return Err(Error::invalid(
                at("cut.file"),
                "give `family` or `file`, not both",
            ))
        }
        (None, None) => {
            return Err(Error::invalid(
                at("cut.family"),
                "missing: give `[cut]` with `family = \"round-brilliant\"` (or another family), or `file = \"design.asc\"` for a design",
            ))
        }
        (Some(fam_name), None) => {
            for key in ["open_meets", "meet_tol", "facet_changes"] {
                let given = match key {
                    "open_meets" => rc.open_meets.is_some(),
                    "facet_changes" => rc.facet_changes.is_some(),
                    _ => rc.meet_tol.is_some(),
                };
                if given {
                    return Err(Error::invalid(
                        at(&format!("cut.{key}")),
                        "applies to a design (`file = …`), not a family",
                    ));
                }
            }
            let fam = family(fam_name).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(at("cut.family"), message),
                other => other,
            })?;
            (Arc::new(*fam) as Arc<dyn CutSpace>, None, None)
        }
        (None, Some(file)) => {
            let open = match rc.open_meets.as_deref() {
                None => OpenMeets::Refuse,
                Some(w) => OpenMeets::parse(w).ok_or_else(|| {
                    Error::invalid(
                        at("cut.open_meets"),
                        format!("`{w}` is not allowed; use \"refuse\" (the default) or \"allow\""),
                    )
                })?,
            };
            let tol = rc.meet_tol.unwrap_or(MEET_TOL);
            if !(tol.is_finite() && tol > 0.0 && tol <= 0.01) {
                return Err(Error::invalid(
                    at("cut.meet_tol"),
                    format!("{} is out of range; allowed (0, 0.01] of the width W", shown(tol)),
                ));
            }
            if let (Designs::Files, Some((recipe, path))) = (designs, load_recipe(file, source, at)?) {
                for (key, given) in [("open_meets", rc.open_meets.is_some()), ("meet_tol", rc.meet_tol.is_some())] {
                    if given {
                        return Err(Error::invalid(
                            at(&format!("cut.{key}")),
                            "a recipe keeps its own meets (each tier is cut again as the recipe places it); leave it out",
                        ));
                    }
                }
                let r = RecipeSpace::new(recipe).map_err(|e| {
                    Error::invalid(at("cut.file"), format!("{file}: {e}"))
                })?;
                if r.keys().is_empty() {
                    return Err(Error::invalid(
                        at("cut.file"),
                        format!("{file}: the recipe has no tier whose angle is a number to turn"),
                    ));
                }
                let record = r.base().record.clone();
                let r = Arc::new(r);
                return finish(rc, at, r as Arc<dyn CutSpace>, None, Some((file.clone(), Some(path))), record);
            }
            let (cut, path) = match designs {
                Designs::Files => load_design(file, source, at)?,
                Designs::Only(given) => (given_design(file, given, at)?, None),
            };
            let d = DesignSpace::new(&cut, tol, open).map_err(|e| {
                Error::invalid(at("cut.file"), format!("{file}: {e}"))
            })?;
            if d.keys().is_empty() {
                return Err(Error::invalid(
                    at("cut.file"),
                    format!("{file}: the design has no tier whose angle can turn"),
                ));
            }
            let d = Arc::new(d);
            (
                d.clone() as Arc<dyn CutSpace>,
                Some(d),
                Some((file.clone(), path)),
            )
        }
    };
    let record = design.as_ref().and_then(|d| d.base().record.clone());
    finish(rc, at, space, design, file, record)
}

/// The `[cut]` section of a space: its start and the facet-changes rule.
fn finish(
    rc: &RawCut,
    at: At,
    space: Arc<dyn CutSpace>,
    design: Option<Arc<DesignSpace>>,
    file: Option<(String, Option<PathBuf>)>,
    record: Option<GemcadRecord>,
) -> Result<CutSection> {
    let start = space.complete(&rc.params).map_err(|e| match e {
        Error::Invalid { field, message } => {
            let field = field
                .strip_prefix(&format!("{}: ", space.name()))
                .unwrap_or(&field)
                .to_string();
            Error::invalid(at(&format!("cut.params.{}", quoted(&field))), message)
        }
        other => other,
    })?;
    let skip_changes = match rc.facet_changes.as_deref() {
        None | Some("refuse") => false,
        Some("skip") => true,
        Some(w) => {
            return Err(Error::invalid(
                at("cut.facet_changes"),
                format!("`{w}` is not allowed; use \"refuse\" (the default) or \"skip\""),
            ))
        }
    };
    Ok(CutSection {
        space,
        start,
        design,
        file,
        skip_changes,
        record,
    })
}

/// The recipe `file` names (a `.toml` with `[design]` or `[[tier]]`, relative to the config's
/// folder) and where it was found; `None` when it is not a recipe.
fn load_recipe(file: &str, source: &str, at: At) -> Result<Option<(Recipe, PathBuf)>> {
    let path = beside_config(file, source);
    // A file that is not there falls through to the design loader, whose error (or, for a
    // config sent to the server, whose refusal) is the one to give.
    if !path.is_file() {
        return Ok(None);
    }
    let recipe = crate::io::recipe::read(&path)
        .map_err(|e| Error::invalid(at("cut.file"), e.to_string()))?;
    Ok(recipe.map(|r| (r, path)))
}

/// The path `file` names, relative to the folder of the config at `source`.
fn beside_config(file: &str, source: &str) -> PathBuf {
    let given = Path::new(file);
    if given.is_absolute() {
        given.to_path_buf()
    } else {
        Path::new(source)
            .parent()
            .unwrap_or(Path::new(""))
            .join(given)
    }
}

/// A TOML key as written: bare when it can be, else quoted.
pub(super) fn quoted(key: &str) -> String {
    if !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        key.to_string()
    } else {
        format!("\"{key}\"")
    }
}

/// The design `file` names when no file may be read: a preset, or one `given` knows.
fn given_design(file: &str, given: &dyn Fn(&str) -> Option<Result<Cut>>, at: At) -> Result<Cut> {
    if let Some(cut) = crate::io::presets::load(file) {
        return cut;
    }
    match given(file) {
        Some(cut) => cut.map_err(|e| match e {
            Error::Invalid { message, .. } | Error::Parse { message, .. } => {
                Error::invalid(at("cut.file"), message)
            }
            other => other,
        }),
        None => Err(Error::invalid(
            at("cut.file"),
            format!(
                "not allowed here: no file is read for a config sent to the server; name a preset ({}) or the design sent with it",
                crate::io::presets::names().join(", ")
            ),
        )),
    }
}

/// The design `file` names: a path relative to the config's folder, or a preset's name.
fn load_design(file: &str, source: &str, at: At) -> Result<(Cut, Option<PathBuf>)> {
    let path = beside_config(file, source);
    let is_file = Path::new(file).extension().is_some();
    let arg = if is_file {
        path.to_string_lossy().to_string()
    } else {
        file.to_string()
    };
    let cut = crate::io::load_cut(&arg).map_err(|e| match e {
        Error::Invalid { message, .. } => {
            Error::invalid(at("cut.file"), format!("{file}: {message}"))
        }
        other => other,
    })?;
    Ok((cut, is_file.then_some(path)))
}
