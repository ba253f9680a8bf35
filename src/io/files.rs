//! Reading and writing files safely: atomic writes, a folder's writability, reads whose errors
//! name the file, and line numbers of byte offsets.

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
    // Renaming over a device, pipe or socket would replace the node itself.
    if let Some(m) = super::guard::not_regular(path) {
        return Err(Error::io(&shown, m));
    }
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

/// Check that outputs can be written into the folder `dir` before any long work, without
/// creating it: `dir` itself when it exists, otherwise its nearest existing ancestor (where the
/// folder would be created), must be a folder in which a probe file can be made and removed.
///
/// ```
/// let d = tempfile::tempdir().unwrap();
/// let out = d.path().join("run/a");
/// facetlab::io::check_writable(&out).unwrap();
/// assert!(!d.path().join("run").exists(), "nothing is created");
/// let file = d.path().join("f");
/// std::fs::write(&file, "x").unwrap();
/// let e = facetlab::io::check_writable(&file.join("run")).unwrap_err().to_string();
/// assert!(e.contains("is not a folder"), "{e}");
/// ```
pub fn check_writable(dir: &Path) -> Result<()> {
    let shown = dir.display().to_string();
    let mut at = if dir.as_os_str().is_empty() {
        Path::new(".")
    } else {
        dir
    };
    loop {
        if std::fs::symlink_metadata(at).is_ok() || at.exists() {
            break;
        }
        at = match at.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
    }
    if !at.is_dir() {
        return Err(Error::io(
            &shown,
            format!("{} exists and is not a folder", at.display()),
        ));
    }
    // A fresh name each try: a leftover probe (of a killed process) is not an error.
    let mut k = 0u32;
    loop {
        let probe = at.join(format!(".facetlab-probe-{}-{k}", std::process::id()));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&probe)
        {
            Ok(_) => {
                let _ = std::fs::remove_file(&probe);
                return Ok(());
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && k < 100 => k += 1,
            Err(e) => {
                return Err(Error::io(
                    &shown,
                    format!("cannot write in folder {}: {e}", at.display()),
                ))
            }
        }
    }
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
