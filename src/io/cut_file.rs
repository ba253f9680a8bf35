//! A cut from or to a file of any kind facetlab reads: presets, TOML specs, GemCad `.asc` and
//! `.gem`, OBJ and STL meshes.

use super::{asc, gem, mesh, presets, read_bytes, recipe, spec};
use crate::error::{Error, Result};
use std::path::Path;

/// Load a cut from a command-line argument: a preset name (see [`presets::names`]) or a path
/// to a `.toml` spec, a GemCad `.asc` or `.gem`, or an `.obj`/`.stl` mesh (convex hull).
///
/// ```
/// let cut = facetlab::io::load_cut("tolkowsky").unwrap();
/// assert_eq!(cut.family.as_deref(), Some("round-brilliant"));
/// // 57 facets of the brilliant plus 16 girdle facets.
/// assert_eq!(cut.solid.facets().len(), 73);
/// // An unknown name is an error that names it.
/// let e = facetlab::io::load_cut("nosuchcut").unwrap_err().to_string();
/// assert!(e.contains("nosuchcut"), "{e}");
/// ```
pub fn load_cut(arg: &str) -> Result<crate::cut::Cut> {
    let path = Path::new(arg);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| arg.to_string());
    match ext.as_deref() {
        Some("toml") => {
            let bytes = read_bytes(path)?;
            toml_cut(&String::from_utf8_lossy(&bytes), &stem, arg)
        }
        Some("asc") => asc::read(path).map_err(|e| {
            read_bytes(path)
                .ok()
                .and_then(|b| binary_gem(&b, &path.display().to_string()))
                .unwrap_or(e)
        }),
        Some("gem") => gem::read(path),
        Some("obj") | Some("stl") => mesh::read(path),
        Some(other) if path.exists() || other.len() <= 4 => Err(Error::invalid(
            arg,
            format!("unknown file type `.{other}`; CUT is a preset ({}) or a .toml, .asc, .gem, .obj or .stl file", presets::names().join(", ")),
        )),
        _ => match presets::load(arg) {
            Some(cut) => cut,
            None => Err(Error::invalid(
                arg,
                format!(
                    "unknown preset{}; presets: {}; or give a path to a .toml, .asc, .gem, .obj or .stl file",
                    presets::suggestion(arg),
                    presets::names().join(", ")
                ),
            )),
        },
    }
}

/// A `.toml` file's cut: a recipe built tier by tier ([`recipe`]) or a cut spec ([`spec`]).
fn toml_cut(text: &str, name: &str, source: &str) -> Result<crate::cut::Cut> {
    if recipe::is_recipe(text) {
        let r = recipe::parse(text, source, name)?;
        Ok(r.build().map_err(|e| e.context(source))?.cut)
    } else {
        spec::parse(text, source)?.to_cut(name, source)
    }
}

/// A binary GemCad `.gem` named `.asc` is told so (the `.asc` reader, which knows no `.gem`,
/// only sees binary bytes): `Some` the error when `bytes` read as a `.gem`.
fn binary_gem(bytes: &[u8], source: &str) -> Option<Error> {
    (bytes.contains(&0) && gem::parse(bytes, source).is_ok()).then(|| {
        Error::parse(
            source,
            "not a GemCad .asc: it is a binary GemCad .gem file; name it .gem",
        )
    })
}

/// The file types [`write_cut`] writes (by extension, lower case): the ones [`load_cut`] reads.
pub const CUT_FORMATS: [&str; 5] = ["toml", "asc", "gem", "obj", "stl"];

/// A cut as the bytes of a file of type `format` (one of [`CUT_FORMATS`]): a TOML spec, a
/// GemCad `.asc` or `.gem` on the design's own gear ([`asc::write`], [`gem::write`]), an OBJ
/// or a binary STL mesh.
///
/// ```
/// use facetlab::io::{load_cut, write_cut};
/// let cut = load_cut("tolkowsky").unwrap();
/// assert!(write_cut(&cut, "asc").unwrap().starts_with(b"GemCad 5.0"));
/// assert_eq!(write_cut(&cut, "gem").unwrap(), facetlab::io::gem::write(&cut, 0).unwrap());
/// assert!(write_cut(&cut, "pdf").is_err());
/// ```
pub fn write_cut(cut: &crate::cut::Cut, format: &str) -> Result<Vec<u8>> {
    match format {
        "toml" => Ok(spec::write(cut).into_bytes()),
        "asc" => asc::check(cut).map(|()| asc::write(cut, 0).into_bytes()),
        "gem" => gem::write(cut, 0),
        "obj" => Ok(mesh::write_obj(cut).into_bytes()),
        "stl" => Ok(mesh::write_stl(cut)),
        other => Err(Error::invalid(
            "format",
            format!(
                "cannot write `.{other}`; allowed: {}",
                CUT_FORMATS.join(", ")
            ),
        )),
    }
}

/// Read a cut from a file's contents in memory (an upload, say): `format` is the file type
/// [`load_cut`] picks by extension (`toml`, `asc`, `gem`, `obj` or `stl`, lower case), `name` the
/// cut's name, and `source` names the contents in errors.
///
/// ```
/// use facetlab::io::{load_cut, parse_cut, spec};
/// let text = spec::write(&load_cut("tolkowsky").unwrap());
/// let cut = parse_cut("toml", text.as_bytes(), "mine", "upload").unwrap();
/// assert_eq!(cut.family.as_deref(), Some("round-brilliant"));
/// let mesh = facetlab::io::mesh::write_obj(&cut);
/// assert_eq!(parse_cut("obj", mesh.as_bytes(), "mine", "upload").unwrap().name, "mine");
/// let e = parse_cut("asc", b"g 96 0\na x3 1 2\n", "mine", "upload").unwrap_err();
/// assert!(e.to_string().starts_with("upload:"), "{e}");
/// ```
pub fn parse_cut(format: &str, bytes: &[u8], name: &str, source: &str) -> Result<crate::cut::Cut> {
    match format {
        "toml" => toml_cut(&String::from_utf8_lossy(bytes), name, source),
        "asc" => match binary_gem(bytes, source) {
            Some(e) => Err(e),
            None => asc::parse(bytes, source)?.to_cut(name),
        },
        "gem" => gem::parse(bytes, source)?.to_cut(name),
        "obj" | "stl" => {
            let planes = if format == "obj" {
                mesh::read_obj(bytes, source)?
            } else {
                mesh::read_stl(bytes, source)?
            };
            let solid = crate::geometry::Polyhedron::from_planes(&planes).map_err(|e| match e {
                Error::Geometry(m) => Error::parse(source, format!("convex hull of the mesh: {m}")),
                other => other,
            })?;
            Ok(crate::cut::Cut {
                name: name.to_string(),
                family: None,
                params: Default::default(),
                solid,
                record: None,
            })
        }
        other => Err(Error::invalid("format", format!("unknown format {other}"))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cut::Cut;

    /// One normalisation: every preset written as `.asc`, `.obj` and `.stl` and read back has
    /// the preset's size (W = 1), total depth (±0.2 % of W), crown and pavilion angles
    /// (±0.05°) and weight (±0.5 %).
    #[test]
    fn every_preset_reads_back_from_every_format_at_the_same_size() {
        for name in presets::names() {
            let cut = presets::load(name).unwrap().unwrap();
            let p = cut.proportions();
            let (_, w) = crate::cut::units::outline_size(cut.solid.vertices());
            assert!((w - 1.0).abs() < 1e-9, "{name}: preset width {w}");
            let vol = cut.solid.volume();
            let asc = asc::parse(asc::write(&cut, 0).as_bytes(), name)
                .unwrap()
                .to_cut(name)
                .unwrap();
            let obj = mesh::read_obj(mesh::write_obj(&cut).as_bytes(), name).unwrap();
            let stl = mesh::read_stl(&mesh::write_stl(&cut), name).unwrap();
            let obj = Cut::from_planes(name, &obj).unwrap();
            let stl = Cut::from_planes(name, &stl).unwrap();
            for (fmt, back) in [("asc", asc), ("obj", obj), ("stl", stl)] {
                let q = back.proportions();
                let why = format!("{name} via .{fmt}: {p:?} vs {q:?}");
                assert!((q.total_depth - p.total_depth).abs() < 0.002, "{why}");
                assert!((q.crown_angle - p.crown_angle).abs() < 0.05, "{why}");
                assert!((q.pavilion_angle - p.pavilion_angle).abs() < 0.05, "{why}");
                let v = back.solid.volume();
                assert!((v / vol - 1.0).abs() < 0.005, "{why}: volume {vol} vs {v}");
            }
        }
    }
}
