//! A plan's run folder checked before any planning ([`check_out`]), as `facetlab plan --out`
//! and the Python package's `plan(out=…)` both check it.

use super::PlanConfig;
use crate::error::{Error, Result};
use crate::io::guard::refuse_overwrite;
use std::path::{Path, PathBuf};

/// Check the run folder `out` (named `field` in errors) of a plan of `rough` (a path or a
/// crystal form's name) with `config` (read from `config_path`, if any): none of the inputs
/// (the rough, the config, the price table it names), a new or empty folder (a plan never
/// writes into a folder holding files), in a folder that exists and can be written.
pub fn check_out(
    field: &str,
    out: &Path,
    rough: &str,
    config_path: Option<&Path>,
    config: &PlanConfig,
) -> Result<()> {
    let mut inputs = vec![PathBuf::from(rough)];
    inputs.extend(config_path.map(Path::to_path_buf));
    inputs.extend(config.inputs());
    refuse_overwrite(&[(field, out.to_path_buf())], &inputs)?;
    if out.is_file() || (out.is_dir() && out.read_dir().map_or(true, |mut d| d.next().is_some())) {
        return Err(Error::invalid(
            field,
            format!(
                "{} exists and is not an empty folder; choose a new folder",
                out.display()
            ),
        ));
    }
    crate::io::guard::check_folder_of(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plan_folder_is_new_or_empty_and_never_an_input() {
        let d = tempfile::tempdir().unwrap();
        let config = PlanConfig::default();
        let rough = d.path().join("rough.obj");
        std::fs::write(&rough, "v 0 0 0\n").unwrap();
        let r = rough.display().to_string();
        let e = check_out("out", &rough, &r, None, &config)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("out: ") && e.contains("would overwrite the input"),
            "{e}"
        );
        let fresh = d.path().join("run");
        check_out("out", &fresh, &r, None, &config).unwrap();
        std::fs::create_dir(&fresh).unwrap();
        check_out("out", &fresh, &r, None, &config).unwrap();
        std::fs::write(fresh.join("x"), "").unwrap();
        let e = check_out("out", &fresh, &r, None, &config)
            .unwrap_err()
            .to_string();
        assert!(e.contains("is not an empty folder"), "{e}");
        let e = check_out("out", &d.path().join("no/run"), "octahedron", None, &config)
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not exist"), "{e}");
    }
}
