//! Guarding the user's files: an output that would overwrite an input is refused (naming the
//! flag) before any work, and the exit status says how a command ended.

use facetlab::error::{Error, Result};
use std::path::{Path, PathBuf};

/// How a command ended, as the process's exit code.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// Done (0).
    Ok,
    /// Done, outputs written, but the photon tracer disagreed with the beam tracer beyond the
    /// tolerance (1).
    Disagreement,
    /// Stopped by Ctrl-C or SIGTERM after writing what was found (130).
    Interrupted,
}

impl Exit {
    /// The process exit code. Bad input is 2 (an `Err`, not an `Exit`).
    pub fn code(self) -> i32 {
        match self {
            Exit::Ok => 0,
            Exit::Disagreement => 1,
            Exit::Interrupted => 130,
        }
    }
}

pub use facetlab::io::guard::{refuse_overwrite, resolved};

/// Check a file output before any work: not a folder, replaced only with `force`, its folder
/// present and writable. (Outputs equal to an input are [`refuse_overwrite`]'s.)
pub fn check_new_file(flag: &str, path: &Path, force: bool) -> Result<()> {
    if path.is_dir() {
        return Err(Error::invalid(
            flag,
            format!("{} is a folder; give a file name", path.display()),
        ));
    }
    if path.exists() && !force {
        return Err(Error::invalid(
            flag,
            format!(
                "{} exists; pass --force to replace it, or choose another name",
                path.display()
            ),
        ));
    }
    facetlab::io::guard::check_folder_of(path)
}

/// The CUT arguments that are files (presets are not).
pub fn cut_files(cuts: &[String]) -> Vec<PathBuf> {
    cuts.iter()
        .map(PathBuf::from)
        .filter(|p| p.is_file())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_equal_to_an_input_is_refused_by_canonical_path() {
        let d = tempfile::tempdir().unwrap();
        let cut = d.path().join("t.toml");
        std::fs::write(&cut, "x").unwrap();
        std::fs::create_dir(d.path().join("sub")).unwrap();
        // The same file spelled differently, and a new file beside it.
        let same = d.path().join("sub").join("..").join("t.toml");
        let e = refuse_overwrite(&[("--json", same)], std::slice::from_ref(&cut))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("--json: ") && e.contains("would overwrite"),
            "{e}"
        );
        let fresh = d.path().join("sub").join("..").join("s.json");
        assert!(refuse_overwrite(&[("--json", fresh)], std::slice::from_ref(&cut)).is_ok());
        // Missing folders on the way are resolved through their nearest existing ancestor.
        assert_eq!(
            resolved(&d.path().join("a/b/c.json")),
            d.path().canonicalize().unwrap().join("a/b/c.json")
        );
        assert_eq!(
            cut_files(&["tolkowsky".into(), cut.display().to_string()]),
            vec![cut.clone()]
        );
        assert_eq!(
            [Exit::Ok, Exit::Disagreement, Exit::Interrupted].map(Exit::code),
            [0, 1, 130]
        );
    }
}
