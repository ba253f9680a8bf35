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

/// The preset nearest to a mistyped `name` (`tolkowski` → `tolkowsky`): the fewest letters
/// added, dropped or changed, at most a third of the name's length (and at least 1), else
/// `None`; a preset's own name is no typo (another case or spacing of it is).
pub fn nearest(name: &str) -> Option<&'static str> {
    let word: Vec<char> = name.trim().to_lowercase().chars().collect();
    let edits = |other: &str| -> usize {
        // Levenshtein distance, one row at a time.
        let other: Vec<char> = other.chars().collect();
        let mut row: Vec<usize> = (0..=other.len()).collect();
        for (i, a) in word.iter().enumerate() {
            let mut diagonal = row[0];
            row[0] = i + 1;
            for (j, b) in other.iter().enumerate() {
                let up = row[j + 1];
                row[j + 1] = (up + 1).min(row[j] + 1).min(diagonal + usize::from(a != b));
                diagonal = up;
            }
        }
        row[other.len()]
    };
    let most = (word.len() / 3).max(1);
    names()
        .into_iter()
        .map(|n| (edits(n), n))
        .filter(|(d, n)| *d <= most && *n != name)
        .min()
        .map(|(_, n)| n)
}

/// ` (did you mean `NAME`?)` after an unknown preset's name, when one is near ([`nearest`]).
pub fn suggestion(name: &str) -> String {
    nearest(name)
        .map(|n| format!(" (did you mean `{n}`?)"))
        .unwrap_or_default()
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
    fn a_typo_suggests_the_nearest_preset() {
        assert_eq!(nearest("tolkowski"), Some("tolkowsky"));
        assert_eq!(nearest("Tolkowsky "), Some("tolkowsky"));
        assert_eq!(nearest("ovl"), Some("oval"));
        assert_eq!(nearest("princes"), Some("princess"));
        assert_eq!(nearest("tolkowsky"), None);
        assert_eq!(nearest("no-such-preset"), None);
        assert_eq!(nearest("xyz"), None);
        assert_eq!(
            suggestion("gia-referense"),
            " (did you mean `gia-reference`?)"
        );
    }

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
