//! The names of the scores: one [`ScoreName`] for every number the scorers give a cut, as the
//! objective's weights, the constraints, sweeps, Pareto fronts, verification and the reports
//! name it. Text becomes a name once, where a config or a flag is read
//! ([`ScoreName::parse`], whose error names the allowed values); past that no score is looked
//! up by a string. [`SCORES`] is the table of every score's range and meaning; a name shows
//! (`Display`, JSON, CSV headers) as it always has: `brilliance`, `aset_red`, `colour_l`, ….

use super::Scores;
use crate::error::{Error, Result};
use std::fmt;

/// A score's name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ScoreName {
    /// Light return under ISO and COS skies, averaged over poses.
    Brilliance,
    /// Light return under an evenly bright (ISO) sky.
    BrillianceIso,
    /// Light return under a sky brightest overhead (COS).
    BrillianceCos,
    /// Coloured light under small spot lights.
    Fire,
    /// Change of the spot-light pattern as the stone rocks.
    Scintillation,
    /// Share of overhead parallel light leaving upward.
    OverheadLightReturn,
    /// ASET share of light from 75–80° elevation (75–90° outside the viewer's port).
    AsetBlue,
    /// ASET share of light from 45–75° elevation.
    AsetRed,
    /// ASET share of light from 0–45° elevation.
    AsetGreen,
    /// ASET share of light from below the horizon.
    AsetLeak,
    /// ASET share of the viewer's dark port (within 10° of the zenith).
    AsetPort,
    /// A coloured stone's face-up lightness L*.
    ColourL,
    /// A coloured stone's face-up chroma C*.
    ColourC,
    /// A coloured stone's extinction (share of the outline too dark).
    Extinction,
    /// A coloured stone's windowing (share of the light seen from below the girdle).
    Windowing,
}

/// One row of [`SCORES`]: a score's name, its range and what it means.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScoreInfo {
    /// The score.
    pub name: ScoreName,
    /// Its name as text (config keys, JSON keys, CSV headers).
    pub key: &'static str,
    /// The values it takes.
    pub range: &'static str,
    /// What it measures, in one line.
    pub meaning: &'static str,
}

/// Every score, in the order a score set lists them: the three the objective weighs, the
/// further light-return and ASET scores, and a coloured stone's four colour scores.
pub const SCORES: [ScoreInfo; 15] = [
    ScoreInfo {
        name: ScoreName::Brilliance,
        key: "brilliance",
        range: "[0, 1]",
        meaning: "light returned to a viewer under even ISO and COS skies, averaged over face-up and tilted poses; 1 = a white diffuser",
    },
    ScoreInfo {
        name: ScoreName::Fire,
        key: "fire",
        range: ">= 0",
        meaning: "coloured light per unit of face-up area under small spot lights (about 0.7 for an ideal diamond)",
    },
    ScoreInfo {
        name: ScoreName::Scintillation,
        key: "scintillation",
        range: "[0, 1]",
        meaning: "how much the pattern of flashes changes as the stone rocks by 3°: 0 none, 1 all",
    },
    ScoreInfo {
        name: ScoreName::BrillianceIso,
        key: "brilliance_iso",
        range: "[0, 1]",
        meaning: "the same under an evenly bright sky",
    },
    ScoreInfo {
        name: ScoreName::BrillianceCos,
        key: "brilliance_cos",
        range: "[0, 1]",
        meaning: "the same under a sky brightest overhead",
    },
    ScoreInfo {
        name: ScoreName::OverheadLightReturn,
        key: "overhead_light_return",
        range: "[0, 1]",
        meaning: "share of light from straight above that leaves upward",
    },
    ScoreInfo {
        name: ScoreName::AsetBlue,
        key: "aset_blue",
        range: "[0, 1]",
        meaning: "share of the face-up view lit from 75–80° elevation, between the red band and the viewer's dark port (ASET blue)",
    },
    ScoreInfo {
        name: ScoreName::AsetRed,
        key: "aset_red",
        range: "[0, 1]",
        meaning: "share of the face-up view lit from 45–75° elevation (ASET red)",
    },
    ScoreInfo {
        name: ScoreName::AsetGreen,
        key: "aset_green",
        range: "[0, 1]",
        meaning: "share of the face-up view lit from 0–45° elevation (ASET green)",
    },
    ScoreInfo {
        name: ScoreName::AsetLeak,
        key: "aset_leak",
        range: "[0, 1]",
        meaning: "share of the face-up view lit from below the horizon, seen through the stone (leakage)",
    },
    ScoreInfo {
        name: ScoreName::AsetPort,
        key: "aset_port",
        range: "[0, 1]",
        meaning: "share of the face-up view lit from 80–90° elevation, the ASET viewer's dark port",
    },
    ScoreInfo {
        name: ScoreName::ColourL,
        key: "colour_l",
        range: "[0, 100]",
        meaning: "lightness L* of a coloured stone's mean face-up colour",
    },
    ScoreInfo {
        name: ScoreName::ColourC,
        key: "colour_c",
        range: ">= 0",
        meaning: "chroma C* of a coloured stone's mean face-up colour",
    },
    ScoreInfo {
        name: ScoreName::Extinction,
        key: "extinction",
        range: "[0, 1]",
        meaning: "share of a coloured stone's outline where the light through it is too dark (extinction)",
    },
    ScoreInfo {
        name: ScoreName::Windowing,
        key: "windowing",
        range: "[0, 1]",
        meaning: "share of the light seen in a coloured stone that comes from below the girdle plane (a window)",
    },
];

impl ScoreName {
    /// The three scores the objective weighs and a trade-off may name.
    pub const OBJECTIVE: [ScoreName; 3] = [
        ScoreName::Brilliance,
        ScoreName::Fire,
        ScoreName::Scintillation,
    ];

    /// A coloured stone's colour scores, in the order `[objective]` weighs them.
    pub const COLOUR: [ScoreName; 4] = [
        ScoreName::ColourL,
        ScoreName::ColourC,
        ScoreName::Extinction,
        ScoreName::Windowing,
    ];

    /// Its row of [`SCORES`].
    pub fn info(self) -> &'static ScoreInfo {
        SCORES
            .iter()
            .find(|i| i.name == self)
            .expect("every score has a row")
    }

    /// Its name as text.
    pub fn as_str(self) -> &'static str {
        self.info().key
    }

    /// The score named `text` (exactly as shown), if any.
    pub fn from_key(text: &str) -> Option<ScoreName> {
        SCORES.iter().find(|i| i.key == text).map(|i| i.name)
    }

    /// The score named `text`, one of `allowed`; the error names `field` and lists `allowed`.
    pub fn parse_among(field: &str, text: &str, allowed: &[ScoreName]) -> Result<ScoreName> {
        ScoreName::from_key(text)
            .filter(|n| allowed.contains(n))
            .ok_or_else(|| {
                Error::invalid(
                    field,
                    format!("unknown score `{text}`; allowed: {}", list(allowed)),
                )
            })
    }

    /// The score named `text`; the error names `field` and every score.
    pub fn parse(field: &str, text: &str) -> Result<ScoreName> {
        let all: Vec<ScoreName> = SCORES.iter().map(|i| i.name).collect();
        ScoreName::parse_among(field, text, &all)
    }

    /// Its value in `s` (`None` for a colour score of a colourless stone).
    pub fn of(self, s: &Scores) -> Option<f64> {
        let colour = s.colour.as_ref();
        Some(match self {
            ScoreName::Brilliance => s.brilliance,
            ScoreName::BrillianceIso => s.brilliance_iso,
            ScoreName::BrillianceCos => s.brilliance_cos,
            ScoreName::Fire => s.fire,
            ScoreName::Scintillation => s.scintillation,
            ScoreName::OverheadLightReturn => s.overhead_light_return,
            ScoreName::AsetBlue => s.aset.blue,
            ScoreName::AsetRed => s.aset.red,
            ScoreName::AsetGreen => s.aset.green,
            ScoreName::AsetLeak => s.aset.leak,
            ScoreName::AsetPort => s.aset.port,
            ScoreName::ColourL => colour?.l,
            ScoreName::ColourC => colour?.c,
            ScoreName::Extinction => colour?.extinction?,
            ScoreName::Windowing => colour?.windowing,
        })
    }
}

/// `a, b, c`.
pub fn list(names: &[ScoreName]) -> String {
    joined(names, ", ")
}

/// The names with `sep` between them.
pub fn joined(names: &[ScoreName], sep: &str) -> String {
    names
        .iter()
        .map(|n| n.as_str())
        .collect::<Vec<_>>()
        .join(sep)
}

impl fmt::Display for ScoreName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for ScoreName {
    type Err = Error;
    fn from_str(s: &str) -> Result<ScoreName> {
        ScoreName::parse("score", s)
    }
}

/// Names sort as their text does, so maps keyed by them list (and serialise) as maps keyed by
/// the text did.
impl Ord for ScoreName {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.as_str().cmp(other.as_str())
    }
}

impl PartialOrd for ScoreName {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl serde::Serialize for ScoreName {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

impl<'de> serde::Deserialize<'de> for ScoreName {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        ScoreName::parse("score", &text).map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_name_has_one_row_and_reads_back() {
        for (i, row) in SCORES.iter().enumerate() {
            assert!(
                SCORES[..i]
                    .iter()
                    .all(|r| r.name != row.name && r.key != row.key),
                "{} twice",
                row.key
            );
            assert_eq!(row.name.info(), row);
            assert_eq!(row.key.parse::<ScoreName>().unwrap(), row.name);
            assert_eq!(row.name.to_string(), row.key);
            let json = serde_json::to_string(&row.name).unwrap();
            assert_eq!(json, format!("\"{}\"", row.key));
            assert_eq!(serde_json::from_str::<ScoreName>(&json).unwrap(), row.name);
        }
    }

    #[test]
    fn parsing_names_the_allowed_values() {
        let e = ScoreName::parse_among("objective.pareto", "fyre", &ScoreName::OBJECTIVE)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "objective.pareto: unknown score `fyre`; allowed: brilliance, fire, scintillation"
        );
        assert!(ScoreName::parse_among("x", "aset_red", &ScoreName::OBJECTIVE).is_err());
        let e = ScoreName::parse("score", "").unwrap_err().to_string();
        assert!(e.contains("aset_port") && e.contains("windowing"), "{e}");
    }

    #[test]
    fn names_sort_as_their_text() {
        let mut by_name: Vec<ScoreName> = SCORES.iter().map(|i| i.name).collect();
        by_name.sort();
        let mut by_text: Vec<&str> = SCORES.iter().map(|i| i.key).collect();
        by_text.sort();
        let shown: Vec<&str> = by_name.iter().map(|n| n.as_str()).collect();
        assert_eq!(shown, by_text);
    }

    #[test]
    fn values_come_from_the_scores_field_of_the_same_name() {
        let s = Scores {
            brilliance: 0.5,
            fire: 0.25,
            aset: super::super::Aset {
                red: 0.125,
                ..Default::default()
            },
            ..Default::default()
        };
        let v = serde_json::to_value(&s).unwrap();
        for n in [
            ScoreName::Brilliance,
            ScoreName::Fire,
            ScoreName::Scintillation,
        ] {
            assert_eq!(n.of(&s), v[n.as_str()].as_f64());
        }
        assert_eq!(ScoreName::AsetRed.of(&s), Some(0.125));
        assert_eq!(ScoreName::Extinction.of(&s), None);
    }
}
