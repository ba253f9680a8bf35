//! Presets bundled into the binary from the `cuts/` folder, so a preset name works from any
//! working directory.

use super::spec;
use crate::cut::Cut;
use crate::error::Result;

/// (name, TOML text) of every bundled preset.
pub const PRESETS: &[(&str, &str)] = &[
    ("tolkowsky", include_str!("../../cuts/tolkowsky.toml")),
    (
        "gia-reference",
        include_str!("../../cuts/gia-reference.toml"),
    ),
];

/// Names of the bundled presets.
pub fn names() -> Vec<&'static str> {
    PRESETS.iter().map(|(n, _)| *n).collect()
}

/// The preset called `name`, or `None`.
pub fn load(name: &str) -> Option<Result<Cut>> {
    let (n, text) = PRESETS.iter().find(|(n, _)| *n == name)?;
    let source = format!("cuts/{n}.toml");
    Some(spec::parse(text, &source).and_then(|s| s.to_cut(n, &source)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_preset_builds() {
        for n in names() {
            let cut = load(n).unwrap().unwrap_or_else(|e| panic!("{n}: {e}"));
            assert!(cut.solid.volume() > 0.0, "{n}");
        }
    }
}
