//! Guarding the user's files: an output that is one of the inputs is refused before any work
//! ([`refuse_overwrite`], by the paths as the file system resolves them, [`resolved`]), and an
//! output whose folder is missing or read-only is refused before any work too
//! ([`check_folder_of`]).

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// The path as the file system resolves it: canonical when it exists; otherwise its nearest
/// existing ancestor made canonical, with the missing rest appended.
pub fn resolved(path: &Path) -> PathBuf {
    let path = if path.as_os_str().is_empty() {
        Path::new(".")
    } else {
        path
    };
    if let Ok(c) = path.canonicalize() {
        return c;
    }
    let mut rest = Vec::new();
    let mut at = path;
    loop {
        match (at.file_name(), at.parent()) {
            (Some(name), Some(parent)) => {
                rest.push(name.to_os_string());
                let parent = if parent.as_os_str().is_empty() {
                    Path::new(".")
                } else {
                    parent
                };
                if let Ok(c) = parent.canonicalize() {
                    let mut out = c;
                    out.extend(rest.iter().rev());
                    return out;
                }
                at = parent;
            }
            // `..` or a root that cannot be resolved: compare as written.
            _ => return path.to_path_buf(),
        }
    }
}

/// Refuse when an output is one of the inputs, naming its field. `outputs` are `(field, path)` (a folder output
/// is given as the folder and as each file written in it); `inputs` are the files and folders
/// read (a CUT that is a preset name is no file and is left out by the caller).
pub fn refuse_overwrite(outputs: &[(&str, PathBuf)], inputs: &[PathBuf]) -> Result<()> {
    let ins: Vec<(PathBuf, &PathBuf)> = inputs.iter().map(|p| (resolved(p), p)).collect();
    for (flag, out) in outputs {
        let r = resolved(out);
        if let Some((_, input)) = ins.iter().find(|(c, _)| *c == r) {
            return Err(Error::invalid(
                *flag,
                format!(
                    "{} would overwrite the input {}; write the output elsewhere",
                    out.display(),
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Refuse, before any work, an output `path` whose folder (`.` for a bare name) does not
/// exist or cannot be written; the error names the path.
pub fn check_folder_of(path: &Path) -> Result<()> {
    let parent = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(Error::io(
            path.display().to_string(),
            format!("folder {} does not exist", parent.display()),
        ));
    }
    crate::io::check_writable(parent)
}
