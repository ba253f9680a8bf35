//! Files: TOML cut specs, bundled presets, and safe (atomic) writing of outputs.

pub mod asc;
pub mod mesh;
pub mod presets;
pub mod spec;
pub mod svg;

use crate::error::{Error, Result};
use std::path::Path;

/// Write `bytes` to `path` atomically: write a temporary file beside it, then rename, so a
/// failure never leaves a half-written output behind.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let shown = path.display().to_string();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    if !dir.is_dir() {
        return Err(Error::io(
            &shown,
            format!("folder {} does not exist", dir.display()),
        ));
    }
    let file = path
        .file_name()
        .ok_or_else(|| Error::io(&shown, "not a file name"))?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}",
        file.to_string_lossy(),
        std::process::id()
    ));
    std::fs::write(&tmp, bytes).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(&shown, e)
    })?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        Error::io(&shown, e)
    })
}

/// Read a whole file; the error names the file.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| {
        let msg = match e.kind() {
            std::io::ErrorKind::NotFound => "no such file".to_string(),
            _ => e.to_string(),
        };
        Error::io(path.display().to_string(), msg)
    })
}

/// 1-based line number of byte offset `pos` in `text`.
pub fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// Load a cut from a command-line argument: a preset name (see [`presets::names`]) or a path
/// to a `.toml` spec, a GemCad `.asc`, or an `.obj`/`.stl` mesh (convex hull).
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
            let text = String::from_utf8_lossy(&bytes);
            spec::parse(&text, arg)?.to_cut(&stem, arg)
        }
        Some("asc") => asc::read(path),
        Some("obj") | Some("stl") => mesh::read(path),
        Some(other) if path.exists() || other.len() <= 4 => Err(Error::invalid(
            arg,
            format!("unknown file type `.{other}`; CUT is a preset ({}) or a .toml, .asc, .obj or .stl file", presets::names().join(", ")),
        )),
        _ => match presets::load(arg) {
            Some(cut) => cut,
            None => Err(Error::invalid(
                arg,
                format!(
                    "unknown preset; presets: {}; or give a path to a .toml, .asc, .obj or .stl file",
                    presets::names().join(", ")
                ),
            )),
        },
    }
}
