//! Cutting a recipe tier by tier from a block: the depth each placement asks for, the errors
//! a faceter understands, the steps and findings.

use super::expr::{eval_angle, names};
use super::index::symmetric_indices;
use super::{Angle, Place, Recipe, Side};
use crate::cut::Cut;
use crate::error::{Error, Result};
use crate::geometry::{facet_normal, Block, DVec3, Plane};

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
    /// A facet smaller than [`SMALL_FACET`](super::SMALL_FACET) of the width: too small to cut and see.
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

pub(super) fn tier_err(name: &str, msg: impl Into<String>) -> Error {
    Error::invalid(format!("tier {name}"), msg)
}

pub(super) fn area(poly: &[DVec3], n: DVec3) -> f64 {
    let mut a = DVec3::ZERO;
    for i in 0..poly.len() {
        a += poly[i].cross(poly[(i + 1) % poly.len()]);
    }
    0.5 * a.dot(n)
}

/// Whether a tilt is a girdle's (90°).
pub(super) fn is_girdle_tilt(t: f64) -> bool {
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
}

/// The name of facet `j` of `n` of a tier: the tier's own when it has one facet.
pub(super) fn facet_name(tier: &str, j: usize, n: usize) -> String {
    if n == 1 {
        tier.to_string()
    } else {
        format!("{tier}-{}", j + 1)
    }
}

pub(super) fn shown(x: f64) -> String {
    let t = format!("{x:.6}");
    t.trim_end_matches('0').trim_end_matches('.').to_string()
}
