//! Guarding the user's files: an output that is one of the inputs is refused before any work
//! ([`refuse_overwrite`], by the paths as the file system resolves them, [`resolved`]), and an
//! output whose folder is missing or read-only is refused before any work too
//! ([`check_folder_of`]). The checks of a command's outputs before any work ([`check_new_file`],
//! [`check_document_outputs`], [`PictureFiles`]) name each output by its [`setting`], spelled
//! by each face.

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

/// The settings a command's outputs are named by in errors, each face spelling them its own
/// way (the command line: `-o`, `--json`, `--hdr-out`, `--plots`, `--force`).
pub mod setting {
    /// The file a command writes (a picture, a page, a cut).
    pub const OUTPUT: &str = crate::error::Setting::Output.name();
    /// The JSON document written beside the output or the printed table.
    pub const JSON: &str = crate::error::Setting::JsonOutput.name();
    /// A photograph's linear radiance (OpenEXR or Radiance HDR).
    pub const HDR: &str = crate::error::Setting::HdrOutput.name();
    /// The folder of a trace's charts.
    pub const PLOTS: &str = crate::error::Setting::PlotsFolder.name();
    /// Replacing existing files.
    pub const FORCE: &str = crate::error::Setting::Force.name();
    /// A laboratory picture rocked back and forth (an animated PNG).
    pub const ROCK: &str = crate::error::Setting::PictureRock.name();
    /// A photograph's turntable animation (an animated PNG or GIF).
    pub const TURN: &str = crate::error::Setting::PictureTurn.name();
}

/// The CUT arguments that are files (a preset's name is none), as the inputs an output must
/// not overwrite.
pub fn cut_files<S: AsRef<str>>(cuts: &[S]) -> Vec<PathBuf> {
    cuts.iter()
        .map(|c| PathBuf::from(c.as_ref()))
        .filter(|p| p.is_file())
        .collect()
}

/// Why `path` cannot be written as a file, if it exists and is no regular file: a device,
/// a pipe or a socket (following links) is never replaced, whatever [`setting::FORCE`] says;
/// `None` for a regular file, a folder (refused by its own rule) or a new name.
pub fn not_regular(path: &Path) -> Option<&'static str> {
    let t = std::fs::metadata(path).ok()?.file_type();
    (!t.is_file() && !t.is_dir()).then_some(
        "is not a regular file (a device, pipe or socket), which is never replaced; give a file name",
    )
}

/// Check a file output before any work: not a folder, nor a device, pipe or socket
/// ([`not_regular`]), replaced only with [`setting::FORCE`], its folder present and
/// writable; errors name `field`. (Outputs equal to an input are [`refuse_overwrite`]'s.)
pub fn check_new_file(field: &str, path: &Path, force: bool) -> Result<()> {
    if path.is_dir() {
        return Err(Error::invalid(
            field,
            format!("{} is a folder; give a file name", path.display()),
        ));
    }
    if let Some(m) = not_regular(path) {
        return Err(Error::invalid(field, format!("{} {m}", path.display())));
    }
    if path.exists() && !force {
        return Err(Error::invalid(
            field,
            format!(
                "{} exists; pass {} to replace it, or choose another name",
                path.display(),
                crate::error::setting(setting::FORCE)
            ),
        ));
    }
    check_folder_of(path)
}

/// Check the outputs of a scored or traced document before any work: the JSON document
/// (`json`) and a folder of charts (`plots`) none of the `inputs`, the document a new file
/// ([`check_new_file`]).
pub fn check_document_outputs(
    json: Option<&Path>,
    plots: Option<&Path>,
    inputs: &[PathBuf],
    force: bool,
) -> Result<()> {
    let mut outs = Vec::new();
    if let Some(j) = json {
        outs.push((setting::JSON, j.to_path_buf()));
    }
    if let Some(p) = plots {
        outs.push((setting::PLOTS, p.to_path_buf()));
    }
    refuse_overwrite(&outs, inputs)?;
    if let Some(j) = json {
        check_new_file(setting::JSON, j, force)?;
    }
    Ok(())
}

/// The files a picture command writes.
#[derive(Clone, Copy, Debug)]
pub struct PictureFiles<'a> {
    /// The picture (PNG; a photograph's animation also GIF).
    pub picture: &'a Path,
    /// Its JSON record, if asked.
    pub json: Option<&'a Path>,
    /// A photograph's linear radiance, if asked.
    pub hdr: Option<&'a Path>,
}

/// Whether `path` ends in `.ext` (any case).
fn has_ext(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

impl PictureFiles<'_> {
    fn named(&self) -> Vec<(&'static str, PathBuf)> {
        let mut outs = vec![(setting::OUTPUT, self.picture.to_path_buf())];
        if let Some(j) = self.json {
            outs.push((setting::JSON, j.to_path_buf()));
        }
        if let Some(h) = self.hdr {
            outs.push((setting::HDR, h.to_path_buf()));
        }
        outs
    }

    /// Check a laboratory picture's outputs before any work: none of the `inputs`, the
    /// picture a .png, the record another file, existing files replaced only with `force`,
    /// folders present and writable.
    pub fn check_laboratory(&self, inputs: &[PathBuf], force: bool) -> Result<()> {
        let outs = self.named();
        refuse_overwrite(&outs, inputs)?;
        if !has_ext(self.picture, "png") {
            return Err(Error::invalid(
                setting::OUTPUT,
                format!(
                    "{} does not end in .png; the picture is a PNG (an animated PNG with {}){}",
                    self.picture.display(),
                    crate::error::setting(setting::ROCK),
                    if has_ext(self.picture, "gif") {
                        format!(
                            "; a GIF is a photograph's animation ({} under a photographic light)",
                            crate::error::setting(setting::TURN)
                        )
                    } else {
                        String::new()
                    }
                ),
            ));
        }
        if let Some(j) = self.json {
            if resolved(j) == resolved(self.picture) {
                return Err(Error::invalid(
                    setting::JSON,
                    format!(
                        "{} is also the {} picture; give another file",
                        j.display(),
                        crate::error::setting(setting::OUTPUT)
                    ),
                ));
            }
        }
        for (field, p) in &outs {
            check_new_file(field, p, force)?;
        }
        Ok(())
    }

    /// Check a photograph's outputs before any work: none of the `inputs`, the picture a
    /// .png or .gif, the radiance a .exr or .hdr, no two the same file, existing files
    /// replaced only with `force`, folders present and writable.
    pub fn check_photograph(&self, inputs: &[PathBuf], force: bool) -> Result<()> {
        let outs = self.named();
        refuse_overwrite(&outs, inputs)?;
        if !(has_ext(self.picture, "png") || has_ext(self.picture, "gif")) {
            return Err(Error::invalid(
                setting::OUTPUT,
                format!(
                    "{} does not end in .png or .gif; a photograph is a PNG, an animation an animated PNG or GIF",
                    self.picture.display()
                ),
            ));
        }
        if let Some(h) = self.hdr {
            if !crate::io::hdr::is_hdr_path(h) {
                return Err(Error::invalid(
                    setting::HDR,
                    format!("{} does not end in .exr or .hdr", h.display()),
                ));
            }
        }
        for (i, (fa, pa)) in outs.iter().enumerate() {
            for (fb, pb) in &outs[i + 1..] {
                if resolved(pa) == resolved(pb) {
                    return Err(Error::invalid(
                        *fb,
                        format!(
                            "{} is also the {} file; give another file",
                            pb.display(),
                            crate::error::setting(fa)
                        ),
                    ));
                }
            }
        }
        for (field, p) in &outs {
            check_new_file(field, p, force)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pic<'a>(
        picture: &'a Path,
        json: Option<&'a Path>,
        hdr: Option<&'a Path>,
    ) -> PictureFiles<'a> {
        PictureFiles { picture, json, hdr }
    }

    /// The error's line with its settings spelled as their names.
    fn line(r: Result<()>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn an_output_equal_to_an_input_is_refused_by_canonical_path() {
        let d = tempfile::tempdir().unwrap();
        let cut = d.path().join("t.toml");
        std::fs::write(&cut, "x").unwrap();
        std::fs::create_dir(d.path().join("sub")).unwrap();
        // The same file spelled differently, and a new file beside it.
        let same = d.path().join("sub").join("..").join("t.toml");
        let e = line(refuse_overwrite(
            &[(setting::JSON, same)],
            std::slice::from_ref(&cut),
        ));
        assert!(
            e.starts_with("json output: ") && e.contains("would overwrite"),
            "{e}"
        );
        let fresh = d.path().join("sub").join("..").join("s.json");
        assert!(refuse_overwrite(&[(setting::JSON, fresh)], std::slice::from_ref(&cut)).is_ok());
        // Missing folders on the way are resolved through their nearest existing ancestor.
        assert_eq!(
            resolved(&d.path().join("a/b/c.json")),
            d.path().canonicalize().unwrap().join("a/b/c.json")
        );
        assert_eq!(
            cut_files(&["tolkowsky".to_string(), cut.display().to_string()]),
            vec![cut.clone()]
        );
    }

    #[test]
    fn outputs_are_checked_before_any_work_naming_their_settings() {
        let d = tempfile::tempdir().unwrap();
        let cut = d.path().join("t.asc");
        let old = d.path().join("old.png");
        std::fs::write(&cut, "x").unwrap();
        std::fs::write(&old, "x").unwrap();
        let inputs = [cut.clone()];
        let new = d.path().join("new.png");
        let json = d.path().join("new.json");
        // A new picture and record pass; an existing one only with force.
        assert!(pic(&new, Some(&json), None)
            .check_laboratory(&inputs, false)
            .is_ok());
        let e = pic(&old, None, None)
            .check_laboratory(&inputs, false)
            .unwrap_err();
        let keyword = |s: &str| (s == setting::FORCE).then(|| "overwrite=True".to_string());
        assert_eq!(
            e.spell_settings(&keyword).to_string(),
            format!(
                "output: {} exists; pass overwrite=True to replace it, or choose another name",
                old.display()
            )
        );
        assert!(pic(&old, None, None)
            .check_laboratory(&inputs, true)
            .is_ok());
        // A folder is no file, whatever force says.
        let e = line(pic(&new, Some(d.path()), None).check_laboratory(&inputs, true));
        assert!(
            e.starts_with("json output: ") && e.ends_with("is a folder; give a file name"),
            "{e}"
        );
        // The extensions each kind writes.
        let gif = d.path().join("a.gif");
        let e = line(pic(&gif, None, None).check_laboratory(&inputs, false));
        assert!(
            e.ends_with("(an animated PNG with picture rock); a GIF is a photograph's animation (picture turn under a photographic light)"),
            "{e}"
        );
        assert!(pic(&gif, None, None)
            .check_photograph(&inputs, false)
            .is_ok());
        let e = line(pic(&new, None, Some(&json)).check_photograph(&inputs, false));
        assert!(
            e.starts_with("hdr output: ") && e.ends_with("does not end in .exr or .hdr"),
            "{e}"
        );
        // Two outputs in one file; an input as an output.
        let e = line(pic(&new, Some(&new), None).check_laboratory(&inputs, false));
        assert!(
            e.ends_with("is also the output picture; give another file"),
            "{e}"
        );
        let exr = d.path().join("a.exr");
        assert!(pic(&new, Some(&json), Some(&exr))
            .check_photograph(&inputs, false)
            .is_ok());
        let e = line(pic(&new, Some(&exr), Some(&exr)).check_photograph(&inputs, false));
        assert!(
            e.starts_with("hdr output: ")
                && e.ends_with("is also the json output file; give another file"),
            "{e}"
        );
        let e = line(check_document_outputs(
            Some(&json),
            Some(&cut),
            &inputs,
            false,
        ));
        assert!(
            e.starts_with("plots folder: ") && e.contains("would overwrite the input"),
            "{e}"
        );
        let e = line(check_document_outputs(Some(&old), None, &inputs, false));
        assert!(
            e.starts_with("json output: ") && e.contains("pass force to replace"),
            "{e}"
        );
    }

    /// Issue 51: a socket (a device or pipe alike) is never replaced by an output, with or
    /// without force: refused before any work, and by the atomic write itself.
    #[cfg(unix)]
    #[test]
    fn a_socket_is_never_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let d = tempfile::tempdir().unwrap();
        let sock = d.path().join("s.json");
        let _l = std::os::unix::net::UnixListener::bind(&sock).unwrap();
        for force in [false, true] {
            let e = line(check_new_file(setting::JSON, &sock, force));
            assert!(
                e.starts_with("json output: ") && e.contains("is not a regular file"),
                "{e}"
            );
        }
        let e = crate::io::write_atomic(&sock, b"{}")
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not a regular file"), "{e}");
        let t = std::fs::symlink_metadata(&sock).unwrap().file_type();
        assert!(t.is_socket());
        assert_eq!(not_regular(d.path()), None);
        assert_eq!(not_regular(&d.path().join("new.json")), None);
    }
}
