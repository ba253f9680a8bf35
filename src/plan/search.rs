//! The search: for each family, the orientation (three angles) and the proportions (the free
//! parameters within the config's bounds) that maximise the objective, the containment program
//! ([`super::fit`]) giving the largest copy at each.
//!
//! The orientation is a rotation vector `ω` (the cut turned by `|ω|` about `ω/|ω|`) taken in
//! the rough's own frame (its vertices' centroid and principal axes, the axes' signs set by
//! the third moments), so that turning or moving the rough turns and moves the plans with it.
//! A free parameter is `lo + (hi − lo)·sigmoid(u)`, so Nelder–Mead runs unbounded. Start 0 has
//! the cut's table across the rough's thinnest principal direction and the free parameters in
//! the middle of their bounds; the other starts are seeded random orientations and parameter
//! positions. The starts run in parallel and are gathered in start order, so the answer is
//! the same on any number of threads.

use super::ball::enclosing_ball;
use super::config::{Bound, Objective, PlanConfig};
use super::fit::Containment;
use super::rough::Rough;
use crate::cut::grade::{estimate, Grade};
use crate::cut::{family, Cut, CutSpace};
use crate::error::{Error, Result};
use crate::geometry::{DVec3, FacetPlane, Plane, Polyhedron};
use crate::metrics::{score, ScoreConfig};
use crate::optics::Material;
use argmin::core::{CostFunction, Executor};
use argmin::solver::neldermead::NelderMead;
use glam::{DMat3, DQuat};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::collections::{BTreeMap, HashMap};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

/// Grams per cubic millimetre per (g/cm³), times carats per gram.
const CARATS_PER_MM3_PER_DENSITY: f64 = 1e-3 * 5.0;

/// When the starts find fewer distinct plans than asked for, the further plans keep their
/// tables at least this far (degrees) from every better plan's and its images under the
/// rough's symmetries.
pub const ALTERNATIVE_DEG: f64 = 20.0;

/// The cost of a point whose cut cannot be built or placed (every real cost is ≤ 0).
const FAILED: f64 = 1.0;

/// One plan: a cut of a family, placed in the rough.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The cut as its family builds it (width W = 1, girdle frame).
    pub cut: Cut,
    /// Rotation from the cut's frame to the rough's.
    pub rotation: DQuat,
    /// Scale: the cut's width W in mm.
    pub scale: f64,
    /// Translation (mm): a point `v` of the cut goes to `scale·rotation·v + shift`.
    pub shift: DVec3,
    /// Volume in mm³.
    pub volume_mm3: f64,
    /// Weight in carats.
    pub carats: f64,
    /// Cut volume / rough (hull) volume.
    pub yield_fraction: f64,
    /// Grade estimate (round brilliants).
    pub grade: Option<Grade>,
    /// The objective's value (carats, the price, or the face-up colour's chroma C*).
    pub objective: f64,
    /// The face-up colour of a coloured stone, when the objective ranks by it
    /// ([`super::colour`]).
    pub colour: Option<crate::render::ColourStats>,
}

impl Plan {
    /// The cut's facet planes in the rough's coordinates (mm).
    pub fn placed_planes(&self) -> Vec<FacetPlane> {
        self.cut
            .solid
            .facet_planes()
            .into_iter()
            .map(|mut f| {
                let n = self.rotation * f.plane.normal;
                f.plane = Plane {
                    normal: n,
                    offset: self.scale * f.plane.offset + n.dot(self.shift),
                };
                f
            })
            .collect()
    }

    /// The placed cut as a solid in the rough's coordinates (mm).
    pub fn placed_solid(&self) -> Result<Polyhedron> {
        Polyhedron::from_planes(&self.placed_planes())
    }

    /// The placed cut's vertices in the rough's coordinates (mm).
    pub fn placed_vertices(&self) -> Vec<DVec3> {
        self.cut
            .solid
            .vertices()
            .iter()
            .map(|v| self.scale * (self.rotation * *v) + self.shift)
            .collect()
    }

    /// Where the cut's table faces in the rough (unit vector).
    pub fn up(&self) -> DVec3 {
        self.rotation * DVec3::Z
    }

    /// The optic axis of the cut, for a stone whose c-axis lies along `c_axis` in the rough:
    /// its angle from the table's normal (0–90°) toward an azimuth in the cut's own frame
    /// (degrees from +x, in [−180, 180]; 0 when the axis is the table's normal), both to
    /// 0.01°.
    pub fn optic_axis(&self, c_axis: DVec3) -> crate::optics::OpticAxis {
        let mut c = (self.rotation.inverse() * c_axis).normalize();
        if c.z < 0.0 {
            c = -c;
        }
        // Rounded to 0.01°, so that the note written in the plan's design gives its scores
        // again.
        let round = |x: f64| (x * 100.0).round() / 100.0 + 0.0;
        let tilt_deg = round(c.z.clamp(-1.0, 1.0).acos().to_degrees());
        let azimuth_deg = if tilt_deg == 0.0 {
            0.0
        } else {
            round(c.y.atan2(c.x).to_degrees())
        };
        crate::optics::OpticAxis {
            tilt_deg,
            azimuth_deg,
        }
    }
}

/// The planner for one rough.
pub struct Planner<'a> {
    rough: &'a Rough,
    containment: Containment,
    frame: DQuat,
    /// The rough's centroid and symmetries about it (distinct plans).
    centre: DVec3,
    symmetries: Vec<DMat3>,
    density: f64,
    config: &'a PlanConfig,
    /// Raised to stop: the starts not begun are skipped and the rest end at once, and
    /// [`Planner::plan_family`] returns no plans.
    stop: Option<&'a AtomicBool>,
    /// A screening search ([`Planner::screening`]).
    screening: bool,
}

/// The rough's frame: vertices' centroid and principal axes (largest spread first), each
/// axis's sign chosen so that the vertices' third moment along it is positive.
pub(crate) fn principal_frame(pts: &[DVec3]) -> DQuat {
    let n = pts.len() as f64;
    let c = pts.iter().copied().sum::<DVec3>() / n;
    let mut m = [[0.0; 3]; 3];
    for p in pts {
        let d = (*p - c).to_array();
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += d[i] * d[j] / n;
            }
        }
    }
    // Jacobi rotations.
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if m[p][q].abs() < 1e-300 {
                continue;
            }
            let theta = 0.5 * (2.0 * m[p][q]).atan2(m[q][q] - m[p][p]);
            let (s, co) = theta.sin_cos();
            // M ← Jᵀ M J: columns p and q, then rows p and q.
            for row in &mut m {
                let (a, b) = (row[p], row[q]);
                row[p] = co * a - s * b;
                row[q] = s * a + co * b;
            }
            let (mp, mq) = (m[p], m[q]);
            for (k, (a, b)) in mp.iter().zip(&mq).enumerate() {
                m[p][k] = co * a - s * b;
                m[q][k] = s * a + co * b;
            }
            for row in &mut v {
                let (a, b) = (row[p], row[q]);
                row[p] = co * a - s * b;
                row[q] = s * a + co * b;
            }
        }
    }
    let mut axes: Vec<(f64, DVec3)> = (0..3)
        .map(|k| (m[k][k], DVec3::new(v[0][k], v[1][k], v[2][k]).normalize()))
        .collect();
    axes.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut e: Vec<DVec3> = axes
        .iter()
        .map(|(_, a)| {
            let third: f64 = pts.iter().map(|p| (*p - c).dot(*a).powi(3)).sum();
            if third < 0.0 {
                -*a
            } else {
                *a
            }
        })
        .collect();
    if e[0].cross(e[1]).dot(e[2]) < 0.0 {
        e[2] = -e[2];
    }
    DQuat::from_mat3(&DMat3::from_cols(e[0], e[1], e[2]))
}

/// The cost function of one family's search.
struct Problem<'p> {
    planner: &'p Planner<'p>,
    space: &'static crate::cut::Family,
    fixed: BTreeMap<String, f64>,
    free: Vec<(String, f64, f64)>,
    /// The cut and its grade when no parameter is free.
    built: Option<(Cut, Option<Grade>)>,
    /// With a minimum brilliance: the score settings (brilliance only), the minimum, and the
    /// brilliance of each parameter set met so far (by the bits of its values).
    brilliance: Option<BrillianceCheck>,
    /// Table directions (in the rough's frame) to keep at least [`ALTERNATIVE_DEG`] from:
    /// a plan there keeps 1 % of its objective.
    avoid: Vec<DVec3>,
}

/// A minimum brilliance: the score settings, the minimum, and the brilliance of each
/// parameter set met so far (keyed by the bits of its values).
type BrillianceCheck = (ScoreConfig, f64, Mutex<HashMap<Vec<u64>, f64>>);

fn sigmoid(u: f64) -> f64 {
    1.0 / (1.0 + (-u).exp())
}

impl Problem<'_> {
    fn params(&self, x: &[f64]) -> BTreeMap<String, f64> {
        let mut p = self.fixed.clone();
        for (k, (key, lo, hi)) in self.free.iter().enumerate() {
            p.insert(key.clone(), lo + (hi - lo) * sigmoid(x[3 + k]));
        }
        p
    }

    fn rotation(&self, x: &[f64]) -> DQuat {
        self.planner.frame * DQuat::from_scaled_axis(DVec3::new(x[0], x[1], x[2]))
    }

    fn plan(&self, x: &[f64]) -> Option<Plan> {
        let cut = match &self.built {
            Some((c, _)) => c.clone(),
            None => self.space.build(self.space.name, &self.params(x)).ok()?,
        };
        self.planner.place(&cut, self.rotation(x))
    }

    fn cost_at(&self, x: &[f64]) -> Option<f64> {
        if self.planner.stopped() {
            return None;
        }
        let rotation = self.rotation(x);
        let built;
        let (cut, grade) = match &self.built {
            Some((cut, grade)) => (cut, *grade),
            None => {
                built = self.space.build(self.space.name, &self.params(x)).ok()?;
                let grade = estimate(&built).map(|g| g.estimate);
                (&built, grade)
            }
        };
        let (_, _, objective, grade) = self.planner.measure(cut, grade, rotation)?;
        let mut value = self.planner.penalised(objective, grade);
        let up = rotation * DVec3::Z;
        if self
            .avoid
            .iter()
            .any(|a| up.angle_between(*a) < ALTERNATIVE_DEG.to_radians())
        {
            value *= 0.01;
        }
        if let Some((cfg, min, seen)) = &self.brilliance {
            let key: Vec<u64> = cut.params.values().map(|v| v.to_bits()).collect();
            let known = seen.lock().ok().and_then(|m| m.get(&key).copied());
            let b = known.unwrap_or_else(|| {
                let b = score(&cut.solid, cfg).brilliance;
                if let Ok(mut m) = seen.lock() {
                    m.insert(key, b);
                }
                b
            });
            if b < *min {
                value *= 0.01;
            }
        }
        Some(-value)
    }
}

impl CostFunction for &Problem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, x: &Vec<f64>) -> std::result::Result<f64, argmin::core::Error> {
        Ok(self.cost_at(x).unwrap_or(FAILED))
    }
}

impl<'a> Planner<'a> {
    /// A planner for `rough` under `config`; `density` in g/cm³ (the material's).
    pub fn new(rough: &'a Rough, config: &'a PlanConfig, density: f64) -> Planner<'a> {
        Planner {
            rough,
            containment: Containment::new(&rough.solid),
            frame: principal_frame(rough.solid.vertices()),
            centre: rough.solid.centroid(),
            symmetries: rough.symmetries(),
            density,
            config,
            stop: None,
            screening: false,
        }
    }

    /// The planner as a screen (ranking a layout's saw candidates): each start restarted
    /// once, not twice (none ranked too coarsely: a sawn layout 1.3 % lighter).
    pub fn screening(mut self) -> Self {
        self.screening = true;
        self
    }

    /// The planner, stopped when `stop` is raised (Ctrl-C): a family being planned then ends
    /// within a few evaluations and gives no plans.
    pub fn with_stop(mut self, stop: &'a AtomicBool) -> Self {
        self.stop = Some(stop);
        self
    }

    /// Whether the stop flag is raised.
    pub fn stopped(&self) -> bool {
        self.stop.is_some_and(|s| s.load(Ordering::SeqCst))
    }

    /// The largest copy of `cut` turned by `rotation`: the fit, its carats and objective, and
    /// the grade passed in.
    fn measure(
        &self,
        cut: &Cut,
        grade: Option<Grade>,
        rotation: DQuat,
    ) -> Option<(super::Fit, f64, f64, Option<Grade>)> {
        let verts: Vec<DVec3> = cut.solid.vertices().iter().map(|v| rotation * *v).collect();
        let fit = match self.rough.ball {
            // In a ball: the cut's smallest enclosing ball scaled to the rough's.
            Some(ball) => {
                let around = enclosing_ball(&verts);
                let scale = ball.radius / around.radius;
                super::Fit {
                    scale,
                    shift: ball.centre - scale * around.centre,
                    steps: 0,
                }
            }
            None => self.containment.largest_copy(&verts)?,
        };
        if fit.scale.is_nan() || fit.scale <= 0.0 {
            return None;
        }
        let carats =
            cut.solid.volume() * fit.scale.powi(3) * self.density * CARATS_PER_MM3_PER_DENSITY;
        let objective = match &self.config.objective {
            // The colour ranks the plans the weight search finds (super::colour).
            Objective::Weight | Objective::Colour(_) => carats,
            Objective::Value(t) => t.value(carats, grade),
        };
        Some((fit, carats, objective, grade))
    }

    /// The largest copy of `cut` turned by `rotation` (cut frame → rough frame), with its
    /// weight, yield, grade and objective; `None` if the program fails.
    pub fn place(&self, cut: &Cut, rotation: DQuat) -> Option<Plan> {
        let grade = estimate(cut).map(|g| g.estimate);
        let (fit, carats, objective, grade) = self.measure(cut, grade, rotation)?;
        let volume_mm3 = cut.solid.volume() * fit.scale.powi(3);
        Some(Plan {
            cut: cut.clone(),
            rotation,
            scale: fit.scale,
            shift: fit.shift,
            volume_mm3,
            carats,
            yield_fraction: volume_mm3 / self.rough.volume(),
            grade,
            objective,
            colour: None,
        })
    }

    /// The objective, cut to a hundredth per grade step below the config's grade.
    fn penalised(&self, objective: f64, grade: Option<Grade>) -> f64 {
        match (self.config.grade, grade) {
            (Some(want), Some(got)) if got > want => {
                objective * 0.01 / (got as u8 - want as u8) as f64
            }
            _ => objective,
        }
    }

    /// Whether a plan meets the config's grade (cuts without a grade estimate always do).
    pub fn meets_grade(&self, p: &Plan) -> bool {
        match (self.config.grade, p.grade) {
            (Some(want), Some(got)) => got <= want,
            _ => true,
        }
    }

    /// The start points of a family's search: `3 + free` coordinates each.
    pub fn start_points(&self, free: usize) -> Vec<Vec<f64>> {
        let mut rng = SmallRng::seed_from_u64(self.config.seed);
        (0..self.config.starts)
            .map(|k| {
                let mut x = vec![0.0; 3 + free];
                if k > 0 {
                    let w = random_turn(&mut rng).to_scaled_axis();
                    x[..3].copy_from_slice(&w.to_array());
                    for u in &mut x[3..] {
                        *u = rng.random_range(-1.5..1.5);
                    }
                }
                x
            })
            .collect()
    }

    /// Plan one family: every start's best, best first, distinct plans only
    /// ([`Planner::same_plan`]), at most the config's `top`; when the starts find fewer, further
    /// rounds with the table kept [`ALTERNATIVE_DEG`] from the plans found. `done` is called
    /// after each start of the first round (progress).
    pub fn plan_family(&self, name: &str, done: &(dyn Fn() + Sync)) -> Result<Vec<Plan>> {
        let space = family(name)?;
        let settings = self.config.params.get(name).cloned().unwrap_or_default();
        let mut fixed = BTreeMap::new();
        let mut free = Vec::new();
        for key in space.keys() {
            match settings.get(key) {
                Some(Bound::Fixed(v)) => {
                    fixed.insert(key.to_string(), *v);
                }
                Some(Bound::Free(lo, hi)) => free.push((key.to_string(), *lo, *hi)),
                None => {}
            }
        }
        let built = if free.is_empty() {
            let cut = space.build(name, &fixed)?;
            let grade = estimate(&cut).map(|g| g.estimate);
            Some((cut, grade))
        } else {
            None
        };
        let brilliance = match self.config.min_brilliance {
            Some(min) => {
                let mut cfg = ScoreConfig::fast();
                cfg.material = Material::by_name(&self.config.material)?;
                cfg.parts.fire = false;
                cfg.parts.scintillation = false;
                Some((cfg, min, Mutex::new(HashMap::new())))
            }
            None => None,
        };
        let problem = Problem {
            planner: self,
            space,
            fixed,
            free,
            built,
            brilliance,
            avoid: Vec::new(),
        };
        let mut problem = problem;
        let mut out: Vec<Plan> = Vec::new();
        for (_, p) in self.search_round(&problem, done) {
            if out.len() >= self.config.top {
                break;
            }
            if !out.iter().any(|q| self.same_plan(q, &p)) {
                out.push(p);
            }
        }
        // In a ball every orientation is as good: the plans are stood upright.
        if self.rough.ball.is_some() {
            out = out
                .iter()
                .map(|p| {
                    self.place(&p.cut, DQuat::IDENTITY)
                        .unwrap_or_else(|| p.clone())
                })
                .collect();
        }
        // Too few distinct plans (the starts met in copies of one optimum, as in a symmetric
        // rough): search again with the table kept off every plan's so far, turned by every
        // symmetry of the rough, each round adding its best plan. Not in a ball, where a pose
        // is no choice.
        let apart = ALTERNATIVE_DEG.to_radians();
        while !out.is_empty()
            && out.len() < self.config.top
            && self.rough.ball.is_none()
            && !self.stopped()
        {
            problem.avoid = out
                .iter()
                .flat_map(|p| self.symmetries.iter().map(move |g| *g * p.up()))
                .collect();
            let next = self
                .search_round(&problem, &|| {})
                .into_iter()
                .map(|(_, p)| p)
                .find(|p| {
                    problem
                        .avoid
                        .iter()
                        .all(|a| p.up().angle_between(*a) >= apart - 1e-9)
                        && !out.iter().any(|q| self.same_plan(q, p))
                });
            match next {
                Some(p) => out.push(p),
                None => break,
            }
        }
        // A later round, kept from more tables, can still beat an earlier one whose search
        // stopped short: best first by the objective under the grade (every pair stays 20°
        // apart either way).
        if out.len() > 1 {
            let value = |p: &Plan| self.penalised(p.objective, p.grade);
            out.sort_by(|a, b| value(b).total_cmp(&value(a)));
        }
        if self.stopped() {
            return Ok(Vec::new());
        }
        if out.is_empty() {
            return Err(Error::invalid(
                "ROUGH",
                format!(
                    "no {name} fits in the rough {} at the config's bounds",
                    self.rough.name
                ),
            ));
        }
        Ok(out)
    }

    /// Every start's best plan, best first. `done` is called after each start.
    fn search_round(&self, problem: &Problem<'_>, done: &(dyn Fn() + Sync)) -> Vec<(f64, Plan)> {
        let starts = self.start_points(problem.free.len());
        let finals: Vec<Option<(f64, Vec<f64>)>> = starts
            .par_iter()
            .map(|x0| {
                if self.stopped() {
                    return None;
                }
                let r = self.run_start(problem, x0);
                done();
                r
            })
            .collect();
        let mut plans: Vec<(f64, Plan)> = finals
            .into_iter()
            .flatten()
            .filter_map(|(c, x)| Some((c, problem.plan(&x)?)))
            .collect();
        plans.sort_by(|a, b| a.0.total_cmp(&b.0));
        plans
    }

    /// One start: Nelder–Mead from `x0`, then restarted twice from its best with smaller
    /// simplices (the objective has kinks where the constraints that bind change, at which a
    /// collapsed simplex stalls).
    fn run_start(&self, problem: &Problem<'_>, x0: &[f64]) -> Option<(f64, Vec<f64>)> {
        let mut best = self.nelder_mead(problem, x0, 1.0)?;
        let restarts: &[f64] = if self.screening { &[0.1] } else { &[0.1, 0.01] };
        for &step in restarts {
            let next = self.nelder_mead(problem, &best.1, step)?;
            if next.0 <= best.0 {
                best = next;
            }
        }
        Some(best)
    }

    fn nelder_mead(&self, problem: &Problem<'_>, x0: &[f64], step: f64) -> Option<(f64, Vec<f64>)> {
        let mut simplex = vec![x0.to_vec()];
        for i in 0..x0.len() {
            let mut x = x0.to_vec();
            x[i] += step * if i < 3 { 0.4 } else { 1.0 };
            simplex.push(x);
        }
        let solver = NelderMead::new(simplex).with_sd_tolerance(1e-12).ok()?;
        let res = Executor::new(problem, solver)
            .configure(|s| s.max_iters(self.config.max_iterations))
            .run()
            .ok()?;
        let x = res.state.best_param.clone()?;
        Some((res.state.best_cost, x))
    }
}

/// What a finished plan should tell its user besides its plans: a family none of whose plans
/// falls in a priced band of a value objective (every plan worth 0, so the search had nothing
/// to climb and its plans are chance).
pub fn plan_warnings(config: &PlanConfig, all: &[(String, Vec<Plan>)]) -> Vec<String> {
    let Objective::Value(table) = &config.objective else {
        return Vec::new();
    };
    all.iter()
        .filter(|(_, plans)| !plans.is_empty() && plans.iter().all(|p| p.objective <= 0.0))
        .map(|(fam, plans)| {
            let heaviest = plans.iter().map(|p| p.carats).fold(0.0, f64::max);
            format!(
                "{fam}: no plan falls in a priced band (the heaviest weighs {heaviest:.3} ct; the price table's first priced band starts at {} ct), so every plan is worth 0 and the search had nothing to climb: its plans are chance",
                crate::error::shown(table.first_priced())
            )
        })
        .collect()
}

/// A seeded turn: a normalised quaternion of four uniform numbers in [−1, 1).
pub(crate) fn random_turn(rng: &mut SmallRng) -> DQuat {
    DQuat::from_xyzw(
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
        rng.random_range(-1.0..1.0),
    )
    .normalize()
}

/// The largest distance from a point of either set to the nearest point of the other.
fn hausdorff(a: &[DVec3], b: &[DVec3]) -> f64 {
    let one_way = |a: &[DVec3], b: &[DVec3]| {
        a.iter()
            .map(|p| {
                b.iter()
                    .map(|q| p.distance(*q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a))
}

impl Planner<'_> {
    /// Whether two plans are copies of one plan (the top K keeps the first): their weights
    /// agree within 1 % and a symmetry of the rough ([`Rough::symmetries`], the identity
    /// first) carries the one's placed vertices onto the other's within 2 % of the rough's
    /// size, compared as sets so that the cut's own symmetries count too (the identity alone
    /// catches starts that stopped near one optimum), or carries the one onto the other turned
    /// about its table axis: the same proportions and width, its girdle centre within 2 % of
    /// the rough's size and its table axis within 1° (a turn by the cut's own symmetry, or by
    /// one that its fit cannot tell apart: a round brilliant turned 22.5° keeps its girdle's
    /// 16 points on the same circle, and its weight). In a ball, where every turn and mirror
    /// about the centre is a symmetry, the vertices' sorted distances from the centre are
    /// compared instead.
    pub fn same_plan(&self, a: &Plan, b: &Plan) -> bool {
        if (a.carats - b.carats).abs() >= 0.01 * a.carats.max(b.carats) {
            return false;
        }
        let tol = 0.02 * self.rough.size();
        let (pa, pb) = (a.placed_vertices(), b.placed_vertices());
        if let Some(ball) = self.rough.ball {
            let radii = |p: &[DVec3]| {
                let mut r: Vec<f64> = p.iter().map(|x| x.distance(ball.centre)).collect();
                r.sort_by(f64::total_cmp);
                r
            };
            let (ra, rb) = (radii(&pa), radii(&pb));
            return ra.len() == rb.len() && ra.iter().zip(&rb).all(|(x, y)| (x - y).abs() < tol);
        }
        let c = self.centre;
        // The same proportions, width, place and table axis (after a symmetry of the rough):
        // the one is the other turned about its table axis — by a turn of the cut's own
        // symmetry, or one its outline cannot tell apart (a round brilliant turned 22.5°
        // fits the same girdle circle at the same weight).
        let same_cut = a.cut.params.len() == b.cut.params.len()
            && a.cut.params.iter().all(|(k, v)| {
                b.cut
                    .params
                    .get(k)
                    .is_some_and(|w| (v - w).abs() <= 1e-3 * v.abs().max(1.0))
            })
            && (a.scale - b.scale).abs() < 0.01 * a.scale.max(b.scale);
        self.symmetries.iter().any(|g| {
            let moved: Vec<DVec3> = pa.iter().map(|x| c + *g * (*x - c)).collect();
            let turned = same_cut
                && (c + *g * (a.shift - c)).distance(b.shift) < tol
                && (*g * a.up()).angle_between(b.up()) < 1f64.to_radians();
            turned || hausdorff(&moved, &pb) < tol
        })
    }
}

#[cfg(test)]
mod tests;
