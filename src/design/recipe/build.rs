//! Cutting a recipe tier by tier from a block: the depth each placement asks for, the errors
//! a faceter understands, the steps and findings.

use super::expr::{eval_angle, names};
use super::index::symmetric_indices;
use super::{Angle, Place, Recipe, RecipeTier, Side, SMALL_FACET};
use crate::cut::{Cut, GemcadRecord};
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, outline_size, Block, DVec3, FacetPlane, Plane, Polyhedron};
use std::collections::BTreeMap;

/// One tier at the machine: what the cutting sheet prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The tier's name.
    pub tier: String,
    /// Its angle as GemCad writes it: negative on the pavilion, 90 the girdle, 0 table/culet.
    pub angle: f64,
    /// Its indices on the gear after the symmetry (GemCad's order).
    pub indices: Vec<f64>,
    /// Its facets' distance from the axis point, in widths of the finished stone.
    pub depth: f64,
    /// The instruction: `cut to centre point`, `meet G1-P1`, `level girdle`, ….
    pub instruction: String,
    /// The names of its facets on the cut.
    pub facets: Vec<String>,
}

/// What a faceter should hear about a recipe that builds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FindingKind {
    /// A facet smaller than [`SMALL_FACET`] of the width: too small to cut and see.
    SmallFacet,
    /// A pavilion tier flatter than the critical angle: light from the table leaks through it.
    BelowCritical,
}

/// A finding about one tier, with its one-line message (and the fix, where obvious).
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// The tier.
    pub tier: String,
    /// What kind of finding.
    pub kind: FindingKind,
    /// One line naming the tier.
    pub message: String,
}

/// A built recipe: the cut (width 1), one step per tier, the findings.
#[derive(Clone, Debug)]
pub struct Built {
    /// The solid as a cut, with the recipe's gear, symmetry, index and instructions as its
    /// GemCad record.
    pub cut: Cut,
    /// The tiers in cutting order.
    pub steps: Vec<Step>,
    /// Facets too small, tiers below the critical angle.
    pub findings: Vec<Finding>,
}

/// A tier resolved: its side, tilt and facet planes' normals.
#[derive(Clone, Debug)]
pub(super) struct Resolved {
    pub tilt: f64,
    /// `None` for a girdle tier (90°).
    pub side: Option<Side>,
    pub indices: Vec<f64>,
    pub normals: Vec<DVec3>,
}

impl Resolved {
    /// The angle as GemCad writes it.
    pub fn signed(&self) -> f64 {
        match self.side {
            Some(Side::Pavilion) if self.tilt > 0.0 => -self.tilt,
            _ => self.tilt,
        }
    }
}

/// The state after some tiers: the block, every plane cut with its tier, each tier's planes.
#[derive(Clone)]
pub(super) struct Carved {
    pub block: Block,
    pub planes: Vec<Plane>,
    pub tier_of: Vec<usize>,
    pub resolved: Vec<Resolved>,
    pub depths: Vec<f64>,
    /// Each plane's face area after the last tier.
    pub areas: Vec<f64>,
}

fn tier_err(name: &str, msg: impl Into<String>) -> Error {
    Error::invalid(format!("tier {name}"), msg)
}

fn area(poly: &[DVec3], n: DVec3) -> f64 {
    let mut a = DVec3::ZERO;
    for i in 0..poly.len() {
        a += poly[i].cross(poly[(i + 1) % poly.len()]);
    }
    0.5 * a.dot(n)
}

/// Whether a tilt is a girdle's (90°).
fn is_girdle_tilt(t: f64) -> bool {
    (t - 90.0).abs() < 1e-12
}

impl Carved {
    pub fn new() -> Carved {
        Carved {
            block: Block::new(),
            planes: Vec::new(),
            tier_of: Vec::new(),
            resolved: Vec::new(),
            depths: Vec::new(),
            areas: Vec::new(),
        }
    }

    /// Real points of every face, with the plane they came from.
    pub fn points(&self) -> Vec<(usize, DVec3)> {
        let mut out = Vec::new();
        for (k, f) in self.block.faces().into_iter().enumerate() {
            for p in f {
                if !Block::on_box(*p) {
                    out.push((k, *p));
                }
            }
        }
        out
    }

    /// The size of what is cut so far (for tolerances).
    pub fn size(&self) -> f64 {
        self.points()
            .iter()
            .map(|(_, p)| p.abs().max_element())
            .fold(1e-3, f64::max)
    }

    pub fn tol(&self) -> f64 {
        1e-9 * self.size()
    }

    /// How many planes of tier `t` pass through `p`.
    pub fn on_tier(&self, t: usize, p: DVec3, tol: f64) -> usize {
        self.planes
            .iter()
            .zip(&self.tier_of)
            .filter(|(pl, &ti)| ti == t && pl.distance(p).abs() <= tol)
            .count()
    }
}

impl Recipe {
    /// Cut the recipe's tiers in order and return the stone; see the module documentation.
    pub fn build(&self) -> Result<Built> {
        self.check_design()?;
        let carved = self.carve(self.tiers.len(), None)?;
        self.finish(carved)
    }

    /// The design-level checks: gear, symmetry, index, names.
    fn check_design(&self) -> Result<()> {
        if !(3..=1000).contains(&self.gear) {
            return Err(Error::invalid(
                "gear",
                format!("{} teeth; a gear has 3–1000 teeth (96 usual)", self.gear),
            ));
        }
        if self.symmetry == 0 || !self.gear.is_multiple_of(self.symmetry) {
            return Err(Error::invalid(
                "symmetry",
                format!(
                    "{}-fold does not divide the {} gear; the symmetry is a divisor of the gear's teeth",
                    self.symmetry, self.gear
                ),
            ));
        }
        if !(self.offset.is_finite() && self.offset.abs() <= f64::from(self.gear)) {
            return Err(Error::invalid(
                "offset",
                format!(
                    "{} is beyond one turn of the {} gear",
                    self.offset, self.gear
                ),
            ));
        }
        if !(self.index.is_finite() && self.index > 1.0 && self.index < 5.0) {
            return Err(Error::invalid(
                "index",
                format!("{}: a refractive index is between 1 and 5", self.index),
            ));
        }
        if self.tiers.is_empty() {
            return Err(Error::invalid("tier", "the recipe has no tiers"));
        }
        for (i, t) in self.tiers.iter().enumerate() {
            if t.name.trim().is_empty() || t.name.chars().any(char::is_whitespace) {
                return Err(Error::invalid(
                    format!("tier {}", i + 1),
                    format!("name `{}`: a tier's name is one word", t.name),
                ));
            }
            if self.tiers[..i].iter().any(|u| u.name == t.name) {
                return Err(tier_err(&t.name, "is named twice; tier names are unique"));
            }
        }
        Ok(())
    }

    /// The tilt (degrees, ≥ 0) and side of tier `i` given the tiers before it.
    pub(super) fn resolve(
        &self,
        i: usize,
        before: &[Resolved],
        tilt_override: Option<f64>,
    ) -> Result<Resolved> {
        let t = &self.tiers[i];
        let lookup = |n: &str| {
            self.tiers[..i]
                .iter()
                .position(|u| u.name == n)
                .map(|j| before[j].tilt)
        };
        let (mut tilt, mut side) = match &t.angle {
            Angle::Degrees(a) => {
                if !a.is_finite() || a.abs() > 90.0 {
                    return Err(tier_err(
                        &t.name,
                        format!("angle {a}: an angle is −90…90 degrees (negative: pavilion)"),
                    ));
                }
                let s = if *a < 0.0 || (*a == 0.0 && a.is_sign_negative()) {
                    Some(Side::Pavilion)
                } else {
                    None
                };
                if s == Some(Side::Pavilion) && t.side == Some(Side::Crown) {
                    return Err(tier_err(
                        &t.name,
                        format!("angle {a} is a pavilion angle but side = \"crown\""),
                    ));
                }
                (a.abs(), s.or(t.side))
            }
            Angle::Expr(e) => {
                let v =
                    eval_angle(e, &lookup).map_err(|m| tier_err(&t.name, format!("angle {m}")))?;
                let first = names(e).first().and_then(|n| {
                    self.tiers[..i]
                        .iter()
                        .position(|u| &u.name == n)
                        .and_then(|j| before[j].side)
                });
                if !(0.0..=90.0).contains(&v) {
                    return Err(tier_err(
                        &t.name,
                        format!("angle `{e}` is {v:.4}°; a tier's tilt is 0–90°"),
                    ));
                }
                (v, t.side.or(first))
            }
        };
        if let Some(o) = tilt_override {
            tilt = o.clamp(0.0, 90.0);
        }
        if is_girdle_tilt(tilt) {
            side = None;
        } else if side.is_none() {
            side = Some(Side::Crown);
        }
        let crown = side != Some(Side::Pavilion);
        if tilt == 0.0 {
            let n = if crown { DVec3::Z } else { DVec3::NEG_Z };
            return Ok(Resolved {
                tilt,
                side,
                indices: vec![f64::from(self.gear)],
                normals: vec![n],
            });
        }
        if t.indices.is_empty() {
            return Err(tier_err(
                &t.name,
                "has no indices; give the indices it is cut at (e.g. indices = [3, 93])",
            ));
        }
        let g = f64::from(self.gear);
        for &x in &t.indices {
            if !((self.fractional || x.fract() == 0.0) && (0.0..=g).contains(&x)) {
                let hint = if x.is_finite() && (0.0..=g).contains(&x) {
                    format!(" (nearest: {} or {})", x.floor(), x.ceil())
                } else {
                    String::new()
                };
                return Err(tier_err(
                    &t.name,
                    format!(
                        "index {x} is off the {} gear: indices are whole numbers 0–{}{hint} (or set fractional = true in [design])",
                        self.gear, self.gear
                    ),
                ));
            }
        }
        let indices = symmetric_indices(
            &t.indices,
            self.gear,
            self.offset,
            self.symmetry,
            self.mirror,
        );
        let normals = indices
            .iter()
            .map(|&x| {
                let az = -90.0 + 360.0 * (x - self.offset) / g;
                let mut n = facet_normal(tilt, az, crown);
                if is_girdle_tilt(tilt) {
                    n.z = 0.0;
                    n = n.normalize();
                }
                n
            })
            .collect();
        Ok(Resolved {
            tilt,
            side,
            indices,
            normals,
        })
    }

    /// Cut tiers `0..upto`, tier `over.0`'s tilt replaced by `over.1` when given.
    pub(super) fn carve(&self, upto: usize, over: Option<(usize, f64)>) -> Result<Carved> {
        let mut c = Carved::new();
        for i in 0..upto {
            let r = self.resolve(i, &c.resolved, over.filter(|o| o.0 == i).map(|o| o.1))?;
            let d = self.depth(i, &r, &c)?;
            self.cut_tier(i, r, d, &mut c, over)?;
        }
        Ok(c)
    }

    /// Cut tier `i` (resolved as `r`) at depth `d` into `c`: an error when it never touches
    /// the stone or cuts an earlier tier's facets away.
    pub(super) fn cut_tier(
        &self,
        i: usize,
        r: Resolved,
        d: f64,
        c: &mut Carved,
        over: Option<(usize, f64)>,
    ) -> Result<()> {
        let t = &self.tiers[i];
        let first = c.planes.len();
        let before = c.areas.clone();
        for n in &r.normals {
            let p = Plane {
                normal: *n,
                offset: d,
            };
            c.block.cut(p);
            c.planes.push(p);
            c.tier_of.push(i);
        }
        c.resolved.push(r);
        c.depths.push(d);
        let now: Vec<f64> = c
            .block
            .faces()
            .iter()
            .zip(&c.planes)
            .map(|(f, p)| if f.len() >= 3 { area(f, p.normal) } else { 0.0 })
            .collect();
        c.areas = now.clone();
        let tiny = 1e-12 * c.size().powi(2);
        let missing: Vec<usize> = (first..now.len()).filter(|&k| now[k] <= tiny).collect();
        if !missing.is_empty() {
            let how = match &t.place {
                Place::Meet(m) => format!(
                    " (cut to meet {} it only touches the stone there)",
                    m.join("-")
                ),
                Place::Centre => " (cut to the centre point it only touches it there)".into(),
                _ => format!(" at depth {}", shown(d)),
            };
            let what = if missing.len() == now.len() - first {
                format!("never touches the stone cut so far{how}")
            } else {
                format!(
                    "facets {} never touch the stone cut so far{how}",
                    self.facet_list(i, c, &missing)
                )
            };
            let fix = self.suggest(i, i, over);
            return Err(tier_err(&t.name, format!("{what}{fix}")));
        }
        let lost: Vec<usize> = (0..before.len())
            .filter(|&k| before[k] > tiny && now[k] <= tiny)
            .collect();
        if let Some(&k0) = lost.first() {
            let victim = c.tier_of[k0];
            let whole = (0..before.len())
                .filter(|&k| c.tier_of[k] == victim)
                .all(|k| now[k] <= tiny);
            let vname = &self.tiers[victim].name;
            let what = if whole {
                format!(
                    "tier {vname} is cut away entirely by {}, cut after it",
                    t.name
                )
            } else {
                let mine: Vec<usize> = lost
                    .iter()
                    .copied()
                    .filter(|&k| c.tier_of[k] == victim)
                    .collect();
                format!(
                    "facets {} of tier {vname} are cut away by {}, cut after it",
                    self.facet_list(victim, c, &mine),
                    t.name
                )
            };
            let fix = self.suggest(i, i, over);
            return Err(tier_err(&t.name, format!("{what}{fix}")));
        }
        Ok(())
    }

    /// The names of the facets `ks` (plane numbers) of tier `i`.
    fn facet_list(&self, i: usize, c: &Carved, ks: &[usize]) -> String {
        let first = c.tier_of.iter().position(|&t| t == i).unwrap_or(0);
        let n = c.tier_of.iter().filter(|&&t| t == i).count();
        ks.iter()
            .map(|&k| facet_name(&self.tiers[i].name, k - first, n))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// ", steepen X to A° to keep it" when turning tier `i` (a plain angle) by up to 20° lets
    /// the tiers through `upto` be cut; else empty.
    fn suggest(&self, i: usize, upto: usize, over: Option<(usize, f64)>) -> String {
        if over.is_some() {
            return String::new();
        }
        let Angle::Degrees(a) = self.tiers[i].angle else {
            return String::new();
        };
        let tilt = a.abs();
        for step in 1..=200 {
            for sign in [1.0, -1.0] {
                let t = tilt + sign * 0.1 * f64::from(step);
                if !(0.0 < t && t < 90.0) {
                    continue;
                }
                let t = (t * 10.0).round() / 10.0;
                if self.carve(upto + 1, Some((i, t))).is_ok() {
                    let verb = if t > tilt { "steepen" } else { "flatten" };
                    return format!("; {verb} {} to {t:.1}° to keep it", self.tiers[i].name);
                }
            }
        }
        String::new()
    }

    /// The depth tier `i` is cut to.
    pub(super) fn depth(&self, i: usize, r: &Resolved, c: &Carved) -> Result<f64> {
        let t = &self.tiers[i];
        let name = &t.name;
        let d = match &t.place {
            Place::Depth(d) | Place::Scale(d) => {
                if !d.is_finite() {
                    return Err(tier_err(name, "depth must be a finite number"));
                }
                *d
            }
            Place::Centre => {
                let Some(side) = r.side else {
                    return Err(tier_err(
                        name,
                        "a girdle tier has no centre point; place it by depth",
                    ));
                };
                let down = side == Side::Pavilion;
                let bounds: Vec<f64> = c
                    .planes
                    .iter()
                    .filter(|p| {
                        if down {
                            p.normal.z < -1e-12
                        } else {
                            p.normal.z > 1e-12
                        }
                    })
                    .map(|p| p.offset / p.normal.z)
                    .collect();
                let z = if bounds.is_empty() {
                    if i == 0 {
                        if down {
                            -1.0
                        } else {
                            1.0
                        }
                    } else {
                        return Err(tier_err(
                            name,
                            format!(
                                "there is no centre point on the {} yet (nothing cut there meets the axis); place {name} by depth or scale",
                                side.name()
                            ),
                        ));
                    }
                } else if down {
                    bounds.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                } else {
                    bounds.iter().copied().fold(f64::INFINITY, f64::min)
                };
                let p = DVec3::new(0.0, 0.0, z);
                r.normals
                    .iter()
                    .map(|n| n.dot(p))
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Meet(tiers) => {
                if i == 0 {
                    return Err(tier_err(
                        name,
                        "is cut first and has nothing to meet: anchor it with depth, scale or centre = true",
                    ));
                }
                if tiers.is_empty() {
                    return Err(tier_err(name, "meet names no tiers"));
                }
                let mut want: BTreeMap<usize, usize> = BTreeMap::new();
                for m in tiers {
                    match self.tiers[..i].iter().position(|u| &u.name == m) {
                        Some(j) => *want.entry(j).or_default() += 1,
                        None => {
                            return Err(tier_err(
                                name,
                                format!("meet names {m}, which is not a tier cut before {name}"),
                            ))
                        }
                    }
                }
                let tol = c.tol();
                let v: Vec<DVec3> = c
                    .points()
                    .into_iter()
                    .map(|(_, p)| p)
                    .filter(|p| want.iter().all(|(&j, &m)| c.on_tier(j, *p, tol) >= m))
                    .collect();
                if v.is_empty() {
                    let first = *want.keys().next().unwrap_or(&0);
                    let mut meets: Vec<&str> = Vec::new();
                    for (_, p) in c.points() {
                        if c.on_tier(first, p, tol) == 0 {
                            continue;
                        }
                        for (j, u) in self.tiers[..i].iter().enumerate() {
                            if j != first
                                && c.on_tier(j, p, tol) > 0
                                && !meets.contains(&u.name.as_str())
                            {
                                meets.push(&u.name);
                            }
                        }
                    }
                    let hint = if meets.is_empty() {
                        String::new()
                    } else {
                        format!(
                            " ({} meets {} there)",
                            self.tiers[first].name,
                            meets.join(", ")
                        )
                    };
                    return Err(tier_err(
                        name,
                        format!(
                            "meet {}: these tiers do not meet on the stone cut so far{hint}",
                            tiers.join("-")
                        ),
                    ));
                }
                r.normals
                    .iter()
                    .map(|n| {
                        v.iter()
                            .map(|p| n.dot(*p))
                            .fold(f64::NEG_INFINITY, f64::max)
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Girdle(th) => {
                let Some(side) = r.side.filter(|_| r.tilt > 0.0) else {
                    return Err(tier_err(
                        name,
                        "a girdle thickness places a sloping crown or pavilion tier, not a girdle, table or culet",
                    ));
                };
                if !(th.is_finite() && *th >= 0.0 && *th < 1.0) {
                    return Err(tier_err(
                        name,
                        format!("girdle {th}: a thickness is a fraction of the width, 0 to 1"),
                    ));
                }
                let tol = c.tol();
                let girdle: Vec<usize> = (0..c.planes.len())
                    .filter(|&k| c.planes[k].normal.z.abs() < 1e-12)
                    .collect();
                if girdle.is_empty() {
                    return Err(tier_err(
                        name,
                        format!("a girdle thickness needs a girdle tier (90°) cut before {name}"),
                    ));
                }
                let pts: Vec<DVec3> = c
                    .points()
                    .into_iter()
                    .filter(|(k, _)| girdle.contains(k))
                    .map(|(_, p)| p)
                    .collect();
                let other: Vec<f64> = pts
                    .iter()
                    .filter(|p| {
                        c.planes.iter().any(|pl| {
                            let facing = if side == Side::Crown {
                                pl.normal.z < -1e-12
                            } else {
                                pl.normal.z > 1e-12
                            };
                            facing && pl.distance(**p).abs() <= tol
                        })
                    })
                    .map(|p| p.z)
                    .collect();
                if other.is_empty() {
                    let o = if side == Side::Crown {
                        "pavilion"
                    } else {
                        "crown"
                    };
                    return Err(tier_err(
                        name,
                        format!("a girdle thickness is measured from the {o}; cut the {o} before {name}"),
                    ));
                }
                let w = outline_size(&pts).1;
                let target = if side == Side::Crown {
                    other.iter().copied().fold(f64::NEG_INFINITY, f64::max) + th * w
                } else {
                    other.iter().copied().fold(f64::INFINITY, f64::min) - th * w
                };
                r.normals
                    .iter()
                    .map(|n| {
                        let m = pts
                            .iter()
                            .map(|p| n.x * p.x + n.y * p.y)
                            .fold(f64::NEG_INFINITY, f64::max);
                        target * n.z + m
                    })
                    .fold(f64::NEG_INFINITY, f64::max)
            }
            Place::Table(w) => {
                if !(r.tilt == 0.0 && r.side == Some(Side::Crown)) {
                    return Err(tier_err(
                        name,
                        "a table width places a flat crown tier (angle 0)",
                    ));
                }
                if !(w.is_finite() && *w > 0.0 && *w < 1.0) {
                    return Err(tier_err(
                        name,
                        format!(
                            "table {w}: a table width is a fraction of the width, between 0 and 1"
                        ),
                    ));
                }
                table_height(name, *w, c)?
            }
        };
        Ok(d)
    }

    fn finish(&self, c: Carved) -> Result<Built> {
        let mut open = c.block.open();
        // A stone open at the side is told so first (it is open above or below too).
        open.sort_by(|a, b| a.z.abs().total_cmp(&b.z.abs()));
        if let Some(n) = open.first() {
            let msg = if n.z > 0.5 {
                "the stone is open above: no tier closes the crown (add a table, or cut a crown tier to the centre point)"
            } else if n.z < -0.5 {
                "the stone is open below: no tier closes the pavilion (cut a pavilion tier to the centre point, or add a culet)"
            } else {
                "the stone is open at the side: the tiers do not close the outline (a girdle or tier whose indices do not go all around?)"
            };
            return Err(Error::invalid("design", msg));
        }
        let mut planes = Vec::new();
        let mut steps = Vec::new();
        let mut k = 0;
        for (i, r) in c.resolved.iter().enumerate() {
            let n = r.normals.len();
            let mut facets = Vec::new();
            for j in 0..n {
                let f = facet_name(&self.tiers[i].name, j, n);
                planes.push(FacetPlane {
                    plane: c.planes[k],
                    name: f.clone(),
                    tier: self.tiers[i].name.clone(),
                });
                facets.push(f);
                k += 1;
            }
            steps.push((i, facets));
        }
        let solid = Polyhedron::from_planes(&planes).map_err(|e| e.context("design"))?;
        let w = outline_size(solid.vertices()).1;
        if !(w.is_finite() && w > 1e-12) {
            return Err(Error::invalid("design", "the stone has no width"));
        }
        let solid = solid.scaled(1.0 / w);
        let steps: Vec<Step> = steps
            .into_iter()
            .map(|(i, facets)| {
                let r = &c.resolved[i];
                let depth = c.depths[i] / w;
                Step {
                    tier: self.tiers[i].name.clone(),
                    angle: r.signed(),
                    indices: r.indices.clone(),
                    depth,
                    instruction: instruction(&self.tiers[i], r, depth),
                    facets,
                }
            })
            .collect();
        let findings = self.findings(&solid, &c);
        let record = GemcadRecord {
            ri: Some(self.index),
            title: std::iter::once(self.name.clone())
                .chain(self.title.iter().cloned())
                .filter(|t| !t.is_empty())
                .collect(),
            footnotes: self.notes.clone(),
            gear: f64::from(self.gear),
            gear_offset: self.offset,
            symmetry: self.symmetry,
            mirror: self.mirror,
            instructions: steps
                .iter()
                .filter_map(|s| Some((s.facets.first()?.clone(), s.instruction.clone())))
                .collect(),
            scale: w,
        };
        Ok(Built {
            cut: Cut {
                name: self.name.clone(),
                family: None,
                params: BTreeMap::new(),
                solid,
                record: Some(record),
            },
            steps,
            findings,
        })
    }

    fn findings(&self, solid: &Polyhedron, c: &Carved) -> Vec<Finding> {
        let mut out = Vec::new();
        for (i, t) in self.tiers.iter().enumerate() {
            let mut smallest: Option<(f64, &str)> = None;
            for (fi, f) in solid.facets().iter().enumerate() {
                if f.tier != t.name {
                    continue;
                }
                let poly = solid.facet_polygon(fi);
                let mut dia: f64 = 0.0;
                for a in &poly {
                    for b in &poly {
                        dia = dia.max(a.distance(*b));
                    }
                }
                if dia < SMALL_FACET && smallest.is_none_or(|(s, _)| dia < s) {
                    smallest = Some((dia, &f.name));
                }
            }
            if let Some((dia, f)) = smallest {
                out.push(Finding {
                    tier: t.name.clone(),
                    kind: FindingKind::SmallFacet,
                    message: format!(
                        "tier {}: facet {f} is {:.2} % of the width, under the {:.0} % a faceter can cut and see",
                        t.name,
                        dia * 100.0,
                        SMALL_FACET * 100.0
                    ),
                });
            }
            let r = &c.resolved[i];
            let critical = (1.0 / self.index).asin().to_degrees();
            if r.side == Some(Side::Pavilion) && r.tilt > 0.0 && r.tilt < critical {
                let fix = (critical * 10.0).floor() / 10.0 + 0.1;
                out.push(Finding {
                    tier: t.name.clone(),
                    kind: FindingKind::BelowCritical,
                    message: format!(
                        "tier {}: {:.2}° is below the critical angle {critical:.2}° for RI {}: light from the table leaks through it; steepen {} to {fix:.1}° or more",
                        t.name, r.tilt, self.index, t.name
                    ),
                });
            }
        }
        out
    }
}

/// The height of a table plane that leaves a table `w` of the width.
fn table_height(name: &str, w: f64, c: &Carved) -> Result<f64> {
    if c.block.open().iter().any(|n| n.z > 0.5) {
        return Err(tier_err(
            name,
            format!(
                "a table width needs the crown closed above it; cut the crown tiers before {name}"
            ),
        ));
    }
    let pts = c.points();
    if pts.is_empty() {
        return Err(tier_err(name, "there is no stone yet to cut a table on"));
    }
    let all: Vec<DVec3> = pts.iter().map(|(_, p)| *p).collect();
    let (lo, hi) = all.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(a, b), p| (a.min(*p), b.max(*p)),
    );
    let along_x = hi.x - lo.x <= hi.y - lo.y;
    let full = if along_x { hi.x - lo.x } else { hi.y - lo.y };
    let girdle_top = pts
        .iter()
        .filter(|(k, _)| c.planes[*k].normal.z.abs() < 1e-12)
        .map(|(_, p)| p.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let z_lo = if girdle_top.is_finite() {
        girdle_top
    } else {
        lo.z
    };
    let width = |h: f64| table_width(c, h, along_x, full);
    let most = width(z_lo);
    if w > most {
        return Err(tier_err(
            name,
            format!(
                "a table of {:.1} % of the width does not fit above the girdle (at most {:.1} %)",
                w * 100.0,
                most * 100.0
            ),
        ));
    }
    let (mut a, mut b) = (z_lo, hi.z);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if width(m) > w {
            a = m;
        } else {
            b = m;
        }
    }
    Ok(0.5 * (a + b))
}

/// The width of a table cut at height `h` on `c`, along x (else y), as a fraction of `full`.
fn table_width(c: &Carved, h: f64, along_x: bool, full: f64) -> f64 {
    let mut b = c.block.clone();
    let k = b.cut(Plane {
        normal: DVec3::Z,
        offset: h,
    });
    let f = b.face(k);
    if f.len() < 3 {
        return 0.0;
    }
    let (a, z) = f
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, z), p| {
            let v = if along_x { p.x } else { p.y };
            (a.min(v), z.max(v))
        });
    (z - a) / full
}

/// The table width (a fraction of the width) a flat crown plane at height `h` leaves on `c`.
pub(super) fn table_fraction(c: &Carved, h: f64) -> f64 {
    let pts = c.points();
    let (lo, hi) = pts.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(a, b), (_, p)| (a.min(*p), b.max(*p)),
    );
    let along_x = hi.x - lo.x <= hi.y - lo.y;
    let full = if along_x { hi.x - lo.x } else { hi.y - lo.y };
    table_width(c, h, along_x, full)
}

/// The name of facet `j` of `n` of a tier: the tier's own when it has one facet.
pub(super) fn facet_name(tier: &str, j: usize, n: usize) -> String {
    if n == 1 {
        tier.to_string()
    } else {
        format!("{tier}-{}", j + 1)
    }
}

fn shown(x: f64) -> String {
    let t = format!("{x:.6}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// The instruction a cutter reads for tier `t` (`depth` in widths).
fn instruction(t: &RecipeTier, r: &Resolved, depth: f64) -> String {
    let girdle = r.side.is_none();
    let what = match &t.place {
        Place::Centre => "cut to centre point".to_string(),
        Place::Meet(m) => format!("meet {}", m.join("-")),
        Place::Depth(_) if girdle => "level girdle".to_string(),
        Place::Depth(_) => format!("cut to depth {:.4} W", depth),
        Place::Scale(_) if girdle => "level girdle (sets the size)".to_string(),
        Place::Scale(_) => format!("cut to depth {:.4} W (sets the size)", depth),
        Place::Girdle(th) => format!("leave a girdle of {:.2} % of the width", th * 100.0),
        Place::Table(w) => format!("cut the table to {:.2} % of the width", w * 100.0),
    };
    match &t.note {
        Some(n) if !n.trim().is_empty() => format!("{what}; {}", n.trim()),
        _ => what,
    }
}

impl Built {
    /// The cutting sheet's steps of the built recipe: the recipe's own order and
    /// instructions (a depth in mm at a width of `size_mm` when given), with the sheet's
    /// sections, short names and indices ([`crate::design::sheet_steps`]).
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/cuts/recipes/brilliant.toml");
    /// let text = std::fs::read_to_string(path).unwrap();
    /// let built = facetlab::io::recipe::parse(&text, path, "b").unwrap().build().unwrap();
    /// let steps = built.sheet_steps(Some(6.5));
    /// let names: Vec<&str> = steps.iter().map(|s| s.tier.as_str()).collect();
    /// assert_eq!(names, ["P1", "G1", "P2", "C1", "C2", "C3", "T"]);
    /// assert_eq!(steps[2].instruction, "meet P1-G1");
    /// ```
    pub fn sheet_steps(&self, size_mm: Option<f64>) -> Vec<crate::design::SheetStep> {
        let mut sheet = crate::design::sheet_steps(&self.cut, size_mm);
        let mut out = Vec::new();
        for s in &self.steps {
            let Some(k) = sheet.iter().position(|t| t.tier == s.tier) else {
                continue;
            };
            let mut step = sheet.remove(k);
            step.instruction = match (s.instruction.starts_with("cut to depth"), size_mm) {
                (true, Some(mm)) => {
                    format!("cut to depth {:.2} mm at {} mm", s.depth * mm, shown(mm))
                }
                _ => s.instruction.clone(),
            };
            out.push(step);
        }
        // Tiers the sheet groups apart (none for a recipe's own tiers) keep their place.
        out.extend(sheet);
        // Sections in the recipe's order: the preform (CAM) is the tiers up to the first
        // girdle tier when they are cut to the centre point or are the girdle; then each
        // tier's side.
        use crate::design::Section;
        let preform = self
            .steps
            .iter()
            .position(|s| s.angle.abs() == 90.0)
            .filter(|&g| {
                self.steps[..g]
                    .iter()
                    .all(|s| s.instruction.starts_with("cut to centre point"))
            });
        for (k, step) in out.iter_mut().enumerate() {
            let a = step.angle;
            step.section = if preform.is_some_and(|g| k <= g) {
                Section::Preform
            } else if a.abs() == 90.0 {
                Section::Girdle
            } else if a < 0.0 || (a == 0.0 && step.depth < 0.0) {
                Section::Pavilion
            } else if a == 0.0 {
                Section::Table
            } else {
                Section::Crown
            };
        }
        out
    }
}
