//! The cost function: free parameters → cut → scores → cost.
//!
//! `cost = −(w_b·brilliance + w_f·fire + w_s·scintillation) + penalty · Σ violation / 0.01`
//!
//! Lower is better. Each constraint's violation is measured in the constraint's own units
//! (fractions of the girdle diameter, or of the rough's volume), so one percentage point over a
//! limit costs `penalty` (default 1, as much as a whole unit of score): the penalty is exact
//! (linear), so winners sit on a binding constraint rather than slightly past it.
//!
//! A cut that cannot be built (the planes do not make a solid), whose proportions no cutter
//! would cut ([`crate::cut::plausible`]: deeper than wide or flatter than 0.3 W, a table over
//! 85 % of the width), or that the evaluator refuses gets the finite cost [`FAILED_COST`], never an error or NaN: argmin's Nelder–Mead unwraps its
//! first cost calls, and a NaN would poison the simplex ordering.
//!
//! Two argmin problems share this: [`BoxProblem`] (particle swarm; the point is the free
//! parameters themselves, kept in the box by the solver) and [`SigmoidProblem`] (Nelder–Mead;
//! the point `u` is unbounded and mapped to `x = lo + (hi − lo)·sigmoid(u)`).

use super::config::{Config, Constraints, SearchBox, Weights};
use super::evaluator::Evaluator;
use super::guard::Tracker;
use super::score_set::ScoreSet;
use crate::cut::Cut;
use crate::error::Result;
use crate::metrics::ScoreName;
use argmin::core::{CostFunction, Error as ArgminError};
use serde::Serialize;
use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The cost of a cut that could not be built or scored. Far above any real cost (scores are
/// about [0, 1] per unit weight), finite so every solver keeps working.
pub const FAILED_COST: f64 = 100.0;

/// One percentage point: the unit in which constraint violations are charged.
pub const POINT: f64 = 0.01;

/// Weight retention from a round rough: the cut's volume over the volume of the smallest
/// upright cylinder around the stone's axis (the z axis through the girdle centre) that
/// contains it: radius = the largest distance of a vertex from the axis, height = the total
/// depth.
pub fn weight_retention(cut: &Cut) -> f64 {
    let s = &cut.solid;
    let (lo, hi) = s.bounding_box();
    let r = s.max_radius();
    let cyl = PI * r * r * (hi.z - lo.z);
    if cyl > 0.0 {
        s.volume() / cyl
    } else {
        0.0
    }
}

/// One configured constraint, measured on a cut.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ConstraintCheck {
    /// `total_depth`, `crown_height`, `girdle` or `weight_retention`.
    pub name: String,
    /// The measured value.
    pub value: f64,
    /// The allowed range, as text (`[0.56, 0.64]`, `>= 0.12`).
    pub limit: String,
    /// How far outside the limit, in the value's units (0 when satisfied).
    pub violation: f64,
    /// Whether the constraint holds.
    pub ok: bool,
}

/// Measure every configured constraint on `cut`.
pub fn check_constraints(cut: &Cut, c: &Constraints) -> Vec<ConstraintCheck> {
    let mut out = Vec::new();
    let any = c.total_depth.is_some()
        || c.min_crown_height.is_some()
        || c.min_girdle.is_some()
        || c.min_weight_retention.is_some()
        || c.grade.is_some();
    if !any {
        return out;
    }
    let p = cut.proportions();
    if let Some([lo, hi]) = c.total_depth {
        let v = p.total_depth;
        out.push(ConstraintCheck {
            name: "total_depth".into(),
            value: v,
            limit: format!("[{lo}, {hi}]"),
            violation: (lo - v).max(v - hi).max(0.0),
            ok: (lo..=hi).contains(&v),
        });
    }
    let mut min = |name: &str, v: f64, lo: Option<f64>| {
        if let Some(lo) = lo {
            out.push(ConstraintCheck {
                name: name.into(),
                value: v,
                limit: format!(">= {lo}"),
                violation: (lo - v).max(0.0),
                ok: v >= lo,
            });
        }
    };
    min("crown_height", p.crown_height, c.min_crown_height);
    min("girdle", p.girdle, c.min_girdle);
    if c.min_weight_retention.is_some() {
        min(
            "weight_retention",
            weight_retention(cut),
            c.min_weight_retention,
        );
    }
    if let (Some(target), Some(est)) = (c.grade, crate::cut::grade::estimate(cut)) {
        // Each parameter graded worse than the target, by how far it is outside the target
        // grade's range: percentage points and degrees both count as points (0.01).
        for g in &est.parameters {
            let Some(r) = crate::cut::grade::range(&g.name, target) else {
                continue;
            };
            let off = (r[0] - g.value).max(g.value - r[1]).max(0.0);
            out.push(ConstraintCheck {
                name: format!("grade.{}", g.name),
                value: g.value,
                limit: format!("[{}, {}] ({})", r[0], r[1], target.name()),
                violation: off * POINT,
                ok: g.grade <= target,
            });
        }
    }
    out
}

/// Measure the configured limits on a coloured stone's colour scores (`max_extinction`,
/// `max_windowing`) on its `scores`; a score the evaluator did not give counts as 0.
pub fn check_score_constraints(scores: &ScoreSet, c: &Constraints) -> Vec<ConstraintCheck> {
    [
        (ScoreName::Extinction, c.max_extinction),
        (ScoreName::Windowing, c.max_windowing),
    ]
    .into_iter()
    .filter_map(|(name, hi)| {
        let hi = hi?;
        let v = scores.get(name).filter(|v| v.is_finite()).unwrap_or(0.0);
        Some(ConstraintCheck {
            name: name.to_string(),
            value: v,
            limit: format!("<= {hi}"),
            violation: (v - hi).max(0.0),
            ok: v <= hi,
        })
    })
    .collect()
}

/// The penalty for a set of checks: `penalty · Σ violation / 0.01`.
pub fn penalty(checks: &[ConstraintCheck], c: &Constraints) -> f64 {
    c.penalty * checks.iter().map(|k| k.violation / POINT).sum::<f64>()
}

/// The weighted score `Σ weight · score`, the colour scores' weights included (a colour
/// score the evaluator did not give counts as 0, as in the colour constraints).
pub fn weighted(s: &ScoreSet, w: &Weights) -> f64 {
    // A score weighed 0 may not have been computed (NaN): it takes no part.
    let main: f64 = [
        (w.brilliance, s.brilliance),
        (w.fire, s.fire),
        (w.scintillation, s.scintillation),
    ]
    .iter()
    .filter(|(w, _)| *w != 0.0)
    .map(|(w, x)| w * x)
    .sum();
    let colour: f64 = ScoreName::COLOUR
        .into_iter()
        .zip(w.colour)
        .filter(|(_, w)| *w != 0.0)
        .map(|(name, w)| w * s.get(name).filter(|v| v.is_finite()).unwrap_or(0.0))
        .sum();
    main + colour
}

/// The objective of a built and scored cut as a sweep maps it: the weighted score less the
/// penalty of the cut's constraints (the score constraints are not charged).
pub fn objective_of(config: &Config, cut: &Cut, s: &ScoreSet) -> f64 {
    let checks = check_constraints(cut, &config.constraints);
    weighted(s, &config.weights) - penalty(&checks, &config.constraints)
}

/// Everything known about one evaluated point.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// The free parameters.
    pub x: Vec<f64>,
    /// The cost (finite).
    pub cost: f64,
    /// The weighted score (0 when the cut failed).
    pub score: f64,
    /// The constraint penalty.
    pub penalty: f64,
    /// The scores, when the cut was built and scored.
    pub scores: Option<ScoreSet>,
    /// The constraints as measured.
    pub checks: Vec<ConstraintCheck>,
    /// The cut, when it could be built.
    pub cut: Option<Cut>,
    /// Why the cut failed, when it did.
    pub error: Option<String>,
}

/// The objective of a search: maps a point of its box to a cost. It holds what it evaluates:
/// the box (the free parameters and the space that builds their cuts), the scorer, and the
/// weights and constraints that make the cost.
pub struct Objective<'a> {
    /// The box: a point's cut.
    pub space: SearchBox<'a>,
    /// The scorer.
    pub evaluator: &'a dyn Evaluator,
    /// The weights of the scores.
    pub weights: &'a Weights,
    /// The constraints and their penalty.
    pub constraints: &'a Constraints,
}

impl<'a> Objective<'a> {
    /// A config's objective: its box, weights and constraints, scored by `evaluator`.
    pub fn new(config: &'a Config, evaluator: &'a dyn Evaluator) -> Objective<'a> {
        Objective {
            space: config.search_box(),
            evaluator,
            weights: &config.weights,
            constraints: &config.constraints,
        }
    }

    /// The cut at free parameters `x`.
    pub fn cut_at(&self, x: &[f64]) -> Result<Cut> {
        self.space.cut_at(x)
    }

    /// Build, score (for the search: [`Evaluator::evaluate_for_search`]) and charge the cut
    /// at `x`.
    pub fn evaluate(&self, x: &[f64]) -> Evaluation {
        self.evaluate_with(x, false)
    }

    /// [`Objective::evaluate`] with every score ([`Evaluator::evaluate`]): for the cuts a run
    /// reports.
    pub fn evaluate_full(&self, x: &[f64]) -> Evaluation {
        self.evaluate_with(x, true)
    }

    fn evaluate_with(&self, x: &[f64], full: bool) -> Evaluation {
        let failed = |e: String, cut: Option<Cut>| Evaluation {
            x: x.to_vec(),
            cost: FAILED_COST,
            score: 0.0,
            penalty: 0.0,
            scores: None,
            checks: Vec::new(),
            cut,
            error: Some(e),
        };
        if x.iter().any(|v| !v.is_finite()) {
            return failed("a parameter is not a finite number".into(), None);
        }
        let cut = match self.cut_at(x) {
            Ok(c) => c,
            Err(e) => return failed(e.to_string(), None),
        };
        // Proportions no cutter would cut are refused like a cut that cannot be built.
        if let Some(why) = crate::cut::plausible::implausible(&cut).first() {
            return failed(format!("implausible proportions: {why}"), Some(cut));
        }
        let scored = if full {
            self.evaluator.evaluate(&cut)
        } else {
            self.evaluator.evaluate_for_search(&cut)
        };
        let scores = match scored {
            Ok(s) => s,
            Err(e) => return failed(e.to_string(), Some(cut)),
        };
        let score = weighted(&scores, self.weights);
        let mut checks = check_constraints(&cut, self.constraints);
        checks.extend(check_score_constraints(&scores, self.constraints));
        let pen = penalty(&checks, self.constraints);
        let cost = -score + pen;
        if !cost.is_finite() {
            return failed(
                format!("the evaluator returned a non-finite score ({scores:?})"),
                Some(cut),
            );
        }
        Evaluation {
            x: x.to_vec(),
            cost,
            score,
            penalty: pen,
            scores: Some(scores),
            checks,
            cut: Some(cut),
            error: None,
        }
    }

    /// Only the cost.
    pub fn cost(&self, x: &[f64]) -> f64 {
        self.evaluate(x).cost
    }
}

/// `1 / (1 + e^−u)`.
pub fn sigmoid(u: f64) -> f64 {
    1.0 / (1.0 + (-u).exp())
}

/// The inverse of [`sigmoid`], for `f` in (0, 1).
pub fn logit(f: f64) -> f64 {
    (f / (1.0 - f)).ln()
}

/// The particle swarm's problem: the point is the free parameters; argmin keeps it in the box.
pub struct BoxProblem<'a> {
    objective: &'a Objective<'a>,
    tracker: &'a Tracker<'a>,
}

impl<'a> BoxProblem<'a> {
    /// Wrap an objective; each evaluation is reported to `tracker`.
    pub fn new(objective: &'a Objective<'a>, tracker: &'a Tracker<'a>) -> Self {
        BoxProblem { objective, tracker }
    }
}

impl CostFunction for BoxProblem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, x: &Vec<f64>) -> std::result::Result<f64, ArgminError> {
        let c = self.objective.cost(x);
        self.tracker.evaluated(c);
        Ok(c)
    }
}

/// One logged evaluation: the iteration it belongs to (0 = building the simplex), the point
/// in parameter space and its cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Logged {
    /// Iteration (0 = the initial simplex).
    pub iteration: u64,
    /// Free parameters.
    pub x: Vec<f64>,
    /// Cost.
    pub cost: f64,
}

/// Nelder–Mead's problem: the point `u` is unbounded, each coordinate mapped into its bounds by
/// `x = lo + (hi − lo)·sigmoid(u)`. Every evaluation is logged in order (Nelder–Mead is
/// sequential, so the log is deterministic).
pub struct SigmoidProblem<'a> {
    objective: &'a Objective<'a>,
    tracker: &'a Tracker<'a>,
    iteration: &'a AtomicU64,
    log: Mutex<Vec<Logged>>,
}

impl<'a> SigmoidProblem<'a> {
    /// Wrap an objective. `iteration` is set by the solver guard before each iteration.
    pub fn new(
        objective: &'a Objective<'a>,
        tracker: &'a Tracker<'a>,
        iteration: &'a AtomicU64,
    ) -> Self {
        SigmoidProblem {
            objective,
            tracker,
            iteration,
            log: Mutex::new(Vec::new()),
        }
    }

    /// Parameters at `u`.
    pub fn to_x(&self, u: &[f64]) -> Vec<f64> {
        self.objective
            .space
            .free
            .iter()
            .zip(u)
            .map(|(f, &u)| f.at(sigmoid(u)))
            .collect()
    }

    /// `u` at parameters `x` (strictly inside the bounds); the inverse of `to_x` (tests).
    #[cfg(test)]
    pub fn to_u(&self, x: &[f64]) -> Vec<f64> {
        self.objective
            .space
            .free
            .iter()
            .zip(x)
            .map(|(f, &x)| logit(f.unit_of(x)))
            .collect()
    }

    /// The evaluations so far, in order.
    pub fn take_log(&self) -> Vec<Logged> {
        match self.log.lock() {
            Ok(mut g) => std::mem::take(&mut *g),
            Err(p) => std::mem::take(&mut *p.into_inner()),
        }
    }
}

impl CostFunction for SigmoidProblem<'_> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, u: &Vec<f64>) -> std::result::Result<f64, ArgminError> {
        let x = self.to_x(u);
        let c = self.objective.cost(&x);
        self.tracker.evaluated(c);
        let row = Logged {
            iteration: self.iteration.load(Ordering::SeqCst),
            x,
            cost: c,
        };
        match self.log.lock() {
            Ok(mut g) => g.push(row),
            Err(p) => p.into_inner().push(row),
        }
        Ok(c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimize::config::Config;
    use std::collections::BTreeMap;

    fn cfg(extra: &str) -> Config {
        let text = format!(
            "[cut]\nfamily = \"round-brilliant\"\n[free]\ncrown_angle = [25.0, 40.0]\ntable = [0.45, 0.7]\n{extra}"
        );
        Config::from_str(&text, "t.toml").unwrap()
    }

    fn crown(cut: &Cut) -> Result<ScoreSet> {
        Ok(ScoreSet::new(cut.params["crown_angle"] / 100.0, 0.25, 0.5))
    }

    #[test]
    fn cost_is_minus_weighted_score_plus_penalty() {
        let c = cfg("[objective]\nbrilliance = 1.0\nfire = 2.0\n");
        let o = Objective::new(&c, &crown);
        let e = o.evaluate(&[0.57, 34.0]);
        assert!((e.cost - -(0.34 + 0.5)).abs() < 1e-12, "{}", e.cost);
        assert!(e.error.is_none() && e.checks.is_empty());

        // Total depth of the GIA-like default cut is about 0.6; demand at most 0.55.
        let c = cfg("[constraints]\ntotal_depth = [0.5, 0.55]\npenalty = 2.0\n");
        let o = Objective::new(&c, &crown);
        let e = o.evaluate(&[0.57, 34.0]);
        let d = e.cut.as_ref().unwrap().proportions().total_depth;
        assert_eq!(e.checks.len(), 1);
        assert!((e.checks[0].violation - (d - 0.55)).abs() < 1e-12);
        assert!((e.penalty - 2.0 * (d - 0.55) / 0.01).abs() < 1e-9);
        assert!((e.cost - (-0.34 + e.penalty)).abs() < 1e-12);
    }

    /// `max_extinction` and `max_windowing` limit a coloured stone's colour scores with the
    /// same penalty per percentage point; without a body colour they are refused.
    #[test]
    fn colour_limits_cost_their_violation() {
        let c = cfg(
            "[score]\nmaterial = \"ruby\"\n[constraints]\nmax_extinction = 0.15\nmax_windowing = 0.1\npenalty = 2.0\n",
        );
        let dark = |cut: &Cut| -> Result<ScoreSet> {
            let mut s = crown(cut)?;
            s.extra = vec![
                (crate::metrics::ScoreName::Extinction, 0.35),
                (crate::metrics::ScoreName::Windowing, 0.05),
            ];
            Ok(s)
        };
        let o = Objective::new(&c, &dark);
        let e = o.evaluate(&[0.57, 34.0]);
        let ext = e.checks.iter().find(|k| k.name == "extinction").unwrap();
        let win = e.checks.iter().find(|k| k.name == "windowing").unwrap();
        assert!(!ext.ok && win.ok);
        assert!((ext.violation - 0.2).abs() < 1e-12);
        assert!((e.penalty - 2.0 * 0.2 / 0.01).abs() < 1e-9, "{}", e.penalty);
        let text = "[cut]\nfamily = \"round-brilliant\"\n[free]\ntable = [0.45, 0.7]\n[constraints]\nmax_extinction = 0.15\n";
        let err = Config::from_str(text, "t.toml").unwrap_err().to_string();
        assert!(
            err.contains("constraints.max_extinction") && err.contains("no body colour"),
            "{err}"
        );
    }

    /// `[objective]` weighs a coloured stone's colour scores: the cost moves by −weight ×
    /// score for each (a negative weight on extinction raises the cost of a dark stone); a
    /// colourless config naming one is refused with one line.
    #[test]
    fn colour_weights_move_the_objective_by_weight_times_score() {
        let coloured = |cut: &Cut| -> Result<ScoreSet> {
            let mut s = crown(cut)?;
            s.extra = vec![
                (crate::metrics::ScoreName::ColourL, 41.0),
                (crate::metrics::ScoreName::ColourC, 23.5),
                (crate::metrics::ScoreName::Extinction, 0.35),
                (crate::metrics::ScoreName::Windowing, 0.05),
            ];
            Ok(s)
        };
        let plain = cfg("[score]\nmaterial = \"ruby\"\n[objective]\nbrilliance = 1.0\n");
        let base = Objective::new(&plain, &coloured)
            .evaluate(&[0.57, 34.0])
            .cost;
        assert!((base - -0.34).abs() < 1e-12, "{base}");
        for (key, w, score) in [
            ("colour_l", 0.01, 41.0),
            ("colour_c", 0.02, 23.5),
            ("extinction", -0.5, 0.35),
            ("windowing", -2.0, 0.05),
        ] {
            let c = cfg(&format!(
                "[score]\nmaterial = \"ruby\"\n[objective]\nbrilliance = 1.0\n{key} = {w}\n"
            ));
            assert!(c.weights.weighs_colour());
            let cost = Objective::new(&c, &coloured).evaluate(&[0.57, 34.0]).cost;
            assert!((cost - (base - w * score)).abs() < 1e-12, "{key}: {cost}");
            // The weight survives the config written back.
            let again = Config::from_str(&c.as_used_toml(), "again.toml").unwrap();
            assert_eq!(again.weights, c.weights, "{key}");
        }
        // A colour weight alone is an objective (brilliance then defaults to 0).
        let c = cfg("[score]\nmaterial = \"ruby\"\n[objective]\nextinction = -1.0\n");
        let cost = Objective::new(&c, &coloured).evaluate(&[0.57, 34.0]).cost;
        assert!((cost - 0.35).abs() < 1e-12, "{cost}");
        let text = "[cut]\nfamily = \"round-brilliant\"\n[free]\ntable = [0.45, 0.7]\n[objective]\nbrilliance = 1.0\nwindowing = -1.0\n";
        let err = Config::from_str(text, "t.toml").unwrap_err().to_string();
        assert!(
            err.contains("objective.windowing")
                && err.contains("no body colour")
                && !err.contains('\n'),
            "{err}"
        );
    }

    #[test]
    fn failures_cost_a_finite_penalty() {
        let c = cfg("");
        let o = Objective::new(&c, &crown);
        // Out of the family's range (the solver never proposes it, but the map must hold).
        let e = o.evaluate(&[0.57, 80.0]);
        assert_eq!(e.cost, FAILED_COST);
        assert!(e.error.as_deref().unwrap().contains("crown_angle"));
        let e = o.evaluate(&[0.57, f64::NAN]);
        assert_eq!(e.cost, FAILED_COST);
        let refuse = |_: &Cut| -> Result<ScoreSet> { Err(crate::Error::Geometry("no".into())) };
        let o = Objective::new(&c, &refuse);
        assert_eq!(o.cost(&[0.57, 34.0]), FAILED_COST);
        let nan = |_: &Cut| -> Result<ScoreSet> { Ok(ScoreSet::new(f64::NAN, 0.0, 0.0)) };
        let o = Objective::new(&c, &nan);
        assert_eq!(o.cost(&[0.57, 34.0]), FAILED_COST);
        // A stone deeper than it is wide (a 59.9° pavilion: 103 % deep) is refused the same
        // way, naming why; at 45° (a deep but cuttable 70 %) it is scored.
        let text = "[cut]\nfamily = \"round-brilliant\"\n[free]\npavilion_angle = [40.0, 60.0]\n";
        let deep = Config::from_str(text, "t.toml").unwrap();
        let o = Objective::new(&deep, &crown);
        let e = o.evaluate(&[59.9]);
        assert_eq!(e.cost, FAILED_COST);
        assert!(
            e.error
                .as_deref()
                .unwrap()
                .contains("implausible proportions: total depth"),
            "{:?}",
            e.error
        );
        assert!(o.evaluate(&[45.0]).error.is_none());
    }

    #[test]
    fn weight_retention_of_a_cylinder_like_cut() {
        // A tall flat-topped cut retains less than 1 and more than a cone would.
        let cut = Cut::from_family("r", "round-brilliant", &BTreeMap::new()).unwrap();
        let w = weight_retention(&cut);
        assert!(w > 0.3 && w < 0.6, "{w}");
        let c = cfg("[constraints]\nmin_weight_retention = 0.9\n");
        let checks = check_constraints(&cut, &c.constraints);
        assert_eq!(checks[0].name, "weight_retention");
        assert!((checks[0].violation - (0.9 - w)).abs() < 1e-12);
        assert!(!checks[0].ok);
    }

    /// `[constraints] grade` penalises each parameter outside the grade's range by its
    /// distance (points and degrees alike), names it, and keeps a cut inside at no cost.
    #[test]
    fn grade_constraint_names_and_penalises_what_is_outside() {
        let c = cfg("[constraints]\ngrade = \"excellent\"\npenalty = 2\n");
        let o = Objective::new(&c, &crown);
        // Table 57 %, crown 34°: inside; crown 30°: 1.5° under Excellent's 31.5°.
        let e = o.evaluate(&[0.57, 34.0]);
        assert!(
            e.checks.iter().all(|k| k.ok) && e.penalty == 0.0,
            "{:?}",
            e.checks
        );
        let e = o.evaluate(&[0.57, 30.0]);
        let bad: Vec<&ConstraintCheck> = e.checks.iter().filter(|k| !k.ok).collect();
        assert_eq!(bad.len(), 1, "{bad:?}");
        assert_eq!(bad[0].name, "grade.crown_angle");
        assert!((e.penalty - 2.0 * 1.5).abs() < 1e-9, "{}", e.penalty);
        // Only for round brilliants, and only real grades.
        let text = "[cut]\nfamily = \"princess\"\n[free]\ntable = [0.5, 0.7]\n[constraints]\ngrade = \"excellent\"\n";
        let err = Config::from_str(text, "p.toml").unwrap_err().to_string();
        assert!(err.contains("constraints.grade"), "{err}");
        let text = "[cut]\nfamily = \"round-brilliant\"\n[free]\ntable = [0.5, 0.7]\n[constraints]\ngrade = \"ideal\"\n";
        let err = Config::from_str(text, "r.toml").unwrap_err().to_string();
        assert!(
            err.contains("constraints.grade") && err.contains("very-good"),
            "{err}"
        );
    }

    #[test]
    fn sigmoid_map_stays_in_bounds() {
        let c = cfg("");
        let o = Objective::new(&c, &crown);
        let t = Tracker::new(None, None, 0);
        let it = AtomicU64::new(0);
        let p = SigmoidProblem::new(&o, &t, &it);
        for u in [-1e6, -30.0, -1.0, 0.0, 2.0, 40.0, 1e6] {
            let x = p.to_x(&[u, u]);
            assert!((0.45..=0.7).contains(&x[0]) && (25.0..=40.0).contains(&x[1]));
        }
        let x = [0.6, 31.0];
        let back = p.to_x(&p.to_u(&x));
        assert!((back[0] - 0.6).abs() < 1e-12 && (back[1] - 31.0).abs() < 1e-12);
    }
}
