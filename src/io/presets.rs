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
    ("eulitz", include_str!("../../cuts/eulitz.toml")),
    ("ags-ideal", include_str!("../../cuts/ags-ideal.toml")),
    ("old-european", include_str!("../../cuts/old-european.toml")),
    ("princess", include_str!("../../cuts/princess.toml")),
    ("emerald", include_str!("../../cuts/emerald.toml")),
    ("oval", include_str!("../../cuts/oval.toml")),
    ("marquise", include_str!("../../cuts/marquise.toml")),
    ("pear", include_str!("../../cuts/pear.toml")),
    ("cushion", include_str!("../../cuts/cushion.toml")),
    ("sphere", include_str!("../../cuts/sphere.toml")),
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
        // Every family has a preset.
        for f in crate::cut::families() {
            let tag = format!("family = \"{}\"", f.name);
            assert!(
                PRESETS.iter().any(|(_, t)| t.contains(&tag)),
                "no preset for family {}",
                f.name
            );
        }
    }
}
