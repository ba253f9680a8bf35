//! A proportion grade *estimate* for round brilliants, from the ranges commonly published for
//! GIA's cut grades. Not a laboratory grade: a laboratory also judges polish, symmetry,
//! painting and digging, the girdle's variation, the weight ratio, and the interplay of crown
//! and pavilion angles in its own tables.
//!
//! # The ranges
//!
//! Each parameter's value is placed in the best grade whose range holds it; the estimate is
//! the worst of those (GIA's system is deductive: the lowest component sets the grade), and
//! `limiting` names the parameters that set it. The ranges (inclusive) are those widely
//! reproduced from GIA's cut-grading work (GIA's estimated cut-grade charts, 2006, at the
//! default star 55 %, lower half 80 %, girdle 3 %, culet none to small; and the summaries of
//! the Excellent ranges in GIA's and the trade's guides: table 52–62 %, crown angle
//! 31.5–36.5°, pavilion angle 40.6–41.8°, total depth 57.5–63 %, star 40–70 %, lower half
//! 70–85 %, girdle thin to slightly thick, culet none to small):
//!
//! | parameter | Excellent | Very good | Good | Fair |
//! |---|---|---|---|---|
//! | table % | 52–62 | 50–66 | 47–69 | 44–72 |
//! | crown angle ° | 31.5–36.5 | 26.5–38.5 | 22–40 | 20–41.5 |
//! | pavilion angle ° | 40.6–41.8 | 40.0–42.2 | 38.8–43.0 | 37.4–44.0 |
//! | total depth % | 57.5–63.0 | 56.0–64.5 | 53.0–66.0 | 51.0–70.9 |
//! | star % | 40–70 | 35–75 | any | any |
//! | lower half % | 70–85 | 65–90 | any | any |
//! | girdle % | 1.5–4.5 | 1.0–5.5 | 0.5–7.0 | 0–10 |
//! | culet % | 0–2 | 0–4 | 0–6 | 0–10 |
//!
//! Outside the Fair range a parameter is Poor. Girdle thickness is the cut's `girdle`
//! parameter (thickness at the mains' corners over the diameter); "thin" to "slightly thick"
//! is read as 1.5–4.5 %. The crown–pavilion interplay of GIA's charts is not reproduced:
//! each angle is graded alone, so a steep crown on a deep pavilion may estimate higher here
//! than at a laboratory.

use super::Cut;
use serde::{Deserialize, Serialize};

/// A proportion grade, best first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Grade {
    /// Excellent.
    Excellent,
    /// Very good.
    VeryGood,
    /// Good.
    Good,
    /// Fair.
    Fair,
    /// Poor.
    Poor,
}

impl Grade {
    /// Every grade, best first.
    pub const ALL: [Grade; 5] = [
        Grade::Excellent,
        Grade::VeryGood,
        Grade::Good,
        Grade::Fair,
        Grade::Poor,
    ];

    /// The name used in files and flags (`excellent`, `very-good`, `good`, `fair`, `poor`).
    pub fn name(self) -> &'static str {
        match self {
            Grade::Excellent => "excellent",
            Grade::VeryGood => "very-good",
            Grade::Good => "good",
            Grade::Fair => "fair",
            Grade::Poor => "poor",
        }
    }

    /// The grade called `name`.
    pub fn parse(name: &str) -> Option<Grade> {
        Grade::ALL.into_iter().find(|g| g.name() == name)
    }
}

/// One graded parameter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GradedParameter {
    /// Parameter name (`table`, `crown_angle`, `pavilion_angle`, `total_depth`, `star`,
    /// `lower_half`, `girdle`, `culet`).
    pub name: String,
    /// Its value (percent for lengths, degrees for angles).
    pub value: f64,
    /// The best grade whose range holds it.
    pub grade: Grade,
    /// That grade's range, [min, max].
    pub range: [f64; 2],
}

/// A grade estimate.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GradeEstimate {
    /// The estimate: the worst grade of the parameters.
    pub estimate: Grade,
    /// The parameters that set it (empty when Excellent).
    pub limiting: Vec<String>,
    /// Every parameter graded.
    pub parameters: Vec<GradedParameter>,
    /// What this is.
    pub note: &'static str,
}

/// Ranges per grade (Excellent, Very good, Good, Fair), in the units of [`GradedParameter`].
const RANGES: [(&str, [[f64; 2]; 4]); 8] = [
    (
        "table",
        [[52.0, 62.0], [50.0, 66.0], [47.0, 69.0], [44.0, 72.0]],
    ),
    (
        "crown_angle",
        [[31.5, 36.5], [26.5, 38.5], [22.0, 40.0], [20.0, 41.5]],
    ),
    (
        "pavilion_angle",
        [[40.6, 41.8], [40.0, 42.2], [38.8, 43.0], [37.4, 44.0]],
    ),
    (
        "total_depth",
        [[57.5, 63.0], [56.0, 64.5], [53.0, 66.0], [51.0, 70.9]],
    ),
    (
        "star",
        [[40.0, 70.0], [35.0, 75.0], [0.0, 100.0], [0.0, 100.0]],
    ),
    (
        "lower_half",
        [[70.0, 85.0], [65.0, 90.0], [0.0, 100.0], [0.0, 100.0]],
    ),
    ("girdle", [[1.5, 4.5], [1.0, 5.5], [0.5, 7.0], [0.0, 10.0]]),
    ("culet", [[0.0, 2.0], [0.0, 4.0], [0.0, 6.0], [0.0, 10.0]]),
];

/// The range of parameter `name` for grade `g` (units of [`GradedParameter`]); `None` for
/// a name not graded or for [`Grade::Poor`] (no range).
pub fn range(name: &str, g: Grade) -> Option<[f64; 2]> {
    let (_, ranges) = RANGES.iter().find(|(n, _)| *n == name)?;
    let k = Grade::ALL.iter().position(|x| *x == g)?;
    ranges.get(k).copied()
}

/// Grade one parameter by name (units of [`GradedParameter`]); `None` for a name not graded.
pub fn grade_parameter(name: &str, value: f64) -> Option<GradedParameter> {
    let (_, ranges) = RANGES.iter().find(|(n, _)| *n == name)?;
    // A little room for rounding at the published limits (41.8° written as 41.800000001).
    let eps = 1e-9;
    for (g, r) in Grade::ALL.iter().zip(ranges) {
        if value >= r[0] - eps && value <= r[1] + eps {
            return Some(GradedParameter {
                name: name.into(),
                value,
                grade: *g,
                range: *r,
            });
        }
    }
    Some(GradedParameter {
        name: name.into(),
        value,
        grade: Grade::Poor,
        range: [f64::NEG_INFINITY, f64::INFINITY],
    })
}

/// The grade estimate of a round brilliant made by the `round-brilliant` family (its
/// parameters and measured total depth); `None` for other cuts.
pub fn estimate(cut: &Cut) -> Option<GradeEstimate> {
    if cut.family.as_deref() != Some("round-brilliant") {
        return None;
    }
    let p = &cut.params;
    let pct = |k: &str| p.get(k).map(|v| 100.0 * v);
    let values = [
        ("table", pct("table")),
        ("crown_angle", p.get("crown_angle").copied()),
        ("pavilion_angle", p.get("pavilion_angle").copied()),
        ("total_depth", Some(100.0 * cut.proportions().total_depth)),
        ("star", pct("star")),
        ("lower_half", pct("lower_half")),
        ("girdle", pct("girdle")),
        ("culet", Some(pct("culet").unwrap_or(0.0))),
    ];
    let parameters: Vec<GradedParameter> = values
        .iter()
        .filter_map(|(n, v)| grade_parameter(n, (*v)?))
        .collect();
    let estimate = parameters
        .iter()
        .map(|g| g.grade)
        .max()
        .unwrap_or(Grade::Excellent);
    let limiting = if estimate == Grade::Excellent {
        Vec::new()
    } else {
        parameters
            .iter()
            .filter(|g| g.grade == estimate)
            .map(|g| g.name.clone())
            .collect()
    };
    Some(GradeEstimate {
        estimate,
        limiting,
        parameters,
        note: "an estimate from published proportion ranges, not a laboratory grade",
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeMap;

    fn with(preset: &str, sets: &[(&str, f64)]) -> Cut {
        let c = crate::io::load_cut(preset).unwrap();
        let m: BTreeMap<String, f64> = sets.iter().map(|(k, v)| (k.to_string(), *v)).collect();
        c.with_params(&m).unwrap()
    }

    #[test]
    fn reference_cuts_estimate_excellent() {
        for name in ["gia-reference", "tolkowsky", "ags-ideal"] {
            let g = estimate(&with(name, &[])).unwrap();
            assert_eq!(g.estimate, Grade::Excellent, "{name}: {g:?}");
            assert!(g.limiting.is_empty());
            assert_eq!(g.parameters.len(), 8);
        }
    }

    #[test]
    fn a_steep_pavilion_is_named() {
        let g = estimate(&with("gia-reference", &[("pavilion_angle", 43.0)])).unwrap();
        assert!(g.estimate > Grade::VeryGood, "{g:?}");
        assert_eq!(g.limiting, vec!["pavilion_angle".to_string()]);
        // A 30° crown is Very good (26.5–38.5), not Excellent.
        let g = estimate(&with("gia-reference", &[("crown_angle", 30.0)])).unwrap();
        assert_eq!(g.estimate, Grade::VeryGood);
        assert_eq!(g.limiting, vec!["crown_angle".to_string()]);
    }

    #[test]
    fn grades_follow_the_ranges_and_names_round_trip() {
        let at = |n: &str, v: f64| grade_parameter(n, v).unwrap().grade;
        assert_eq!(at("pavilion_angle", 40.6), Grade::Excellent);
        assert_eq!(at("pavilion_angle", 40.59), Grade::VeryGood);
        assert_eq!(at("pavilion_angle", 42.5), Grade::Good);
        assert_eq!(at("pavilion_angle", 43.5), Grade::Fair);
        assert_eq!(at("pavilion_angle", 45.0), Grade::Poor);
        assert_eq!(at("table", 75.0), Grade::Poor);
        assert!(grade_parameter("colour", 1.0).is_none());
        for g in Grade::ALL {
            assert_eq!(Grade::parse(g.name()), Some(g));
        }
        assert!(estimate(&crate::io::load_cut("princess").unwrap()).is_none());
    }
}
