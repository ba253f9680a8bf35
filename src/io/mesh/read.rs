//! A mesh file read as a cut ([`read`], [`read_with_note`]).

use super::tokens::hull_error;
use super::{obj, stl};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{FacetPlane, Polyhedron};
use std::path::Path;

/// Read a mesh file (`.obj` or `.stl`, by extension) as a cut named after the file stem.
pub fn read(path: impl AsRef<Path>) -> Result<Cut> {
    read_with_note(path).map(|(cut, _)| cut)
}

/// [`read`], also returning a one-line note of what was welded, if anything (see the module
/// documentation).
pub fn read_with_note(path: impl AsRef<Path>) -> Result<(Cut, Option<String>)> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    type Reader = fn(&[u8], &str) -> Result<(Vec<FacetPlane>, Option<String>)>;
    let reader: Reader = match ext.as_str() {
        "obj" => obj::read_obj_noted,
        "stl" => stl::read_stl_noted,
        _ => {
            return Err(Error::parse(
                shown,
                format!("unknown mesh format `.{ext}`; allowed: .obj, .stl"),
            ))
        }
    };
    let bytes = std::fs::read(path).map_err(|e| Error::io(&shown, e))?;
    let (planes, note) = reader(&bytes, &shown)?;
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh");
    let solid = Polyhedron::from_planes(&planes).map_err(|e| hull_error(e, &shown))?;
    let cut = Cut {
        name: name.to_string(),
        family: None,
        params: Default::default(),
        solid,
        record: None,
    };
    Ok((cut, note))
}
