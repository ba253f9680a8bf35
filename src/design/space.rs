//! A design as a cut space: its tier angles are the parameters, its depths are solved so that
//! its meets are kept ([`DesignSpace`]), so that a faceter's design can be scored at other
//! angles, swept and optimized exactly as a family is.
//!
//! ```
//! use facetlab::cut::CutSpace;
//! use facetlab::design::{DesignSpace, OpenMeets, MEET_TOL};
//! use std::collections::BTreeMap;
//!
//! let cut = facetlab::io::load_cut("tolkowsky").unwrap();
//! let space = DesignSpace::new(&cut, MEET_TOL, OpenMeets::Refuse).unwrap();
//! // One parameter per tier that has an angle to turn (not the girdle, table or culet).
//! assert!(space.keys().contains(&"pavilion-main"));
//! let mains = space.range("pavilion-main").unwrap().default;
//! assert!((mains - 40.75).abs() < 1e-9);
//! // Mains and lower halves turned together keep every meet: the design stays itself.
//! let half = space.range("lower-half").unwrap().default;
//! let turned = BTreeMap::from([
//!     ("pavilion-main".to_string(), 41.25),
//!     ("lower-half".to_string(), half + 0.5),
//! ]);
//! let cut = space.build("t", &turned).unwrap();
//! assert_eq!(cut.solid.facets().len(), space.base().solid.facets().len());
//! ```

use super::meets::Meet;
use super::reangle::{adjacency_over, Reangled, TierModel};
use super::tie_key::{Tie, TieKind};
use super::tiers::{fixed, ANGLE_DECIMALS};
use crate::cut::{Cut, CutSpace, ParamRange, Unit};
use crate::error::{shown, Error, Result};
use crate::geometry::Polyhedron;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;

/// A meet of an adopted design is kept when its planes pass within this distance (of W) of one
/// point: exact up to the rounding of the solve.
pub const KEPT: f64 = 1e-9;

/// What a design space does with a meet that the asked angles cannot keep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpenMeets {
    /// The cut is refused (an error naming the meet and its tiers): the design stays itself.
    Refuse,
    /// The meet opens; [`DesignSpace::gaps`] says by how much.
    Allow,
}

impl OpenMeets {
    /// The config word: `refuse` or `allow`.
    pub fn name(self) -> &'static str {
        match self {
            OpenMeets::Refuse => "refuse",
            OpenMeets::Allow => "allow",
        }
    }
    /// From the config word.
    pub fn parse(s: &str) -> Option<OpenMeets> {
        match s {
            "refuse" => Some(OpenMeets::Refuse),
            "allow" => Some(OpenMeets::Allow),
            _ => None,
        }
    }
}

/// A design whose tier angles are parameters ([`CutSpace`]): each tier that can turn (every
/// tier but the girdle, the table and a culet) is a key named as the design names the tier
/// (`P1`, `C2`, `pavilion-main`), its value the tier's angle to the girdle plane in degrees.
/// The depths are solved ([`TierModel::reangled`]) so that the meets stay meets, the girdle
/// holding the scale.
///
/// The space starts from the design as it **adopts its meets**: the first solve snaps every
/// meet found within the tolerance to an exact point ([`DesignSpace::base`]), so a rounded file
/// and the solid it means are one design. Every cut built has the base's facets and facet
/// adjacency (else it is refused: a facet that would vanish, an edge that would appear; edges
/// shorter than the meet tolerance, a meet's rounding, are not counted), and
/// angles on GemCad's grid ([`ANGLE_DECIMALS`]), so the `.asc` written of it is the cut scored.
///
/// Tiers can also be **tied** ([`Tie`]): a key `P1+P2` turns both by its value (a change of
/// angle, 0 at the design), `C1=C2` sets both to its value; see `ties.rs`.
#[derive(Clone, Debug)]
pub struct DesignSpace {
    pub(super) name: String,
    pub(super) base: Cut,
    pub(super) model: TierModel,
    /// The tiers that are keys, in tier order.
    pub(super) key_tiers: Vec<usize>,
    /// The base's angle of every tier.
    pub(super) angles: Vec<f64>,
    pub(super) open: OpenMeets,
    pub(super) adjacency: BTreeSet<(String, String)>,
}

/// One meet a set of free tiers cannot keep.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenedMeet {
    /// Index of the meet in [`DesignSpace::meets`].
    pub meet: usize,
    /// A description: its tiers and point (`P1·P2·G1 at (0.500, 0.000, −0.021)`).
    pub name: String,
    /// The free tiers that open it when turned alone; empty when only turning several of them
    /// independently does.
    pub by: Vec<String>,
}

impl DesignSpace {
    /// The space of `cut`'s tier angles, its meets found within `tol` (of W) and adopted.
    pub fn new(cut: &Cut, tol: f64, open: OpenMeets) -> Result<DesignSpace> {
        let first = TierModel::of_cut(cut, tol)?;
        let none = vec![None; first.names.len()];
        let snapped = first.reangled(&none)?;
        let solid = Polyhedron::from_planes(&snapped.planes)
            .map_err(|e| e.context(&format!("{}: adopting its meets", cut.name)))?;
        let mut model = TierModel::new(solid.clone(), first.tier_of, first.names, tol)?;
        // Adopted, the meets are exact: from here a meet is kept only when it stays exact,
        // or (a meet the file's rounding left over-determined) as close as it is now.
        model.tol = f64::INFINITY;
        let replay = model.reangled(&none)?;
        model.tol = KEPT;
        model.slack = replay.gaps.iter().map(|g| 10.0 * g).collect();
        let angles = model.angles();
        let key_tiers = (0..model.names.len())
            .filter(|&t| !model.held[t] && turnable(&model, t))
            .collect();
        let adjacency = adjacency_over(&solid, tol);
        let base = Cut {
            name: cut.name.clone(),
            family: None,
            params: BTreeMap::new(),
            solid,
            record: Some(cut.record.clone().unwrap_or_default()),
        };
        let mut space = DesignSpace {
            name: cut.name.clone(),
            base,
            model,
            key_tiers,
            angles,
            open,
            adjacency,
        };
        space.base.params = space.defaults();
        Ok(space)
    }

    /// The design as it adopted its meets (its params are its tier angles).
    pub fn base(&self) -> &Cut {
        &self.base
    }

    /// The tier model (tiers, depths, meets) of the base.
    pub fn model(&self) -> &TierModel {
        &self.model
    }

    /// The design's meets.
    pub fn meets(&self) -> &[Meet] {
        &self.model.meets
    }

    /// What the space does with meets the angles cannot keep.
    pub fn open_meets(&self) -> OpenMeets {
        self.open
    }

    /// Every key at its base angle.
    pub fn defaults(&self) -> BTreeMap<String, f64> {
        self.key_tiers
            .iter()
            .map(|&t| (self.model.names[t].clone(), self.angles[t]))
            .collect()
    }

    /// A meet described by its tiers and point: `P1·P2·G1 at (0.500, 0.000, -0.021)`.
    pub fn describe(&self, m: usize) -> String {
        let meet = &self.model.meets[m];
        let p = meet.point;
        format!(
            "{} at ({:.3}, {:.3}, {:.3})",
            self.model.meet_tiers(meet).join("·"),
            p.x,
            p.y,
            p.z
        )
    }

    /// The meets the `free` keys (key, lower and upper bound; a tier or a [`Tie`]) cannot
    /// keep: each free key is turned alone to a point of its bounds, then all of them together
    /// to different points of theirs, and every meet that opens is listed with the keys that
    /// open it alone.
    pub fn unkeepable(&self, free: &[(String, f64, f64)]) -> Result<Vec<OpenedMeet>> {
        let mut out: Vec<OpenedMeet> = Vec::new();
        let mut note = |meets: Vec<usize>, by: Option<&str>| {
            for m in meets {
                match out.iter_mut().find(|o| o.meet == m) {
                    Some(o) => o.by.extend(by.map(str::to_string)),
                    None => out.push(OpenedMeet {
                        meet: m,
                        name: self.describe(m),
                        by: by.map(str::to_string).into_iter().collect(),
                    }),
                }
            }
        };
        // Probe points: away from the start by a share of the box that differs per key, so
        // that keys turned together are turned independently.
        let probe = |k: usize, lo: f64, hi: f64, start: f64| -> f64 {
            let f = 0.5 + 0.41 * ((k as f64 + 1.0) * 0.618_033_988_75).fract() - 0.2;
            let v = lo + (hi - lo) * f;
            if (v - start).abs() < 1e-3 * (hi - lo) {
                lo + (hi - lo) * 0.9
            } else {
                v
            }
        };
        let mut together = vec![None; self.model.names.len()];
        for (k, (key, lo, hi)) in free.iter().enumerate() {
            let (tiers, kind) = self.resolve(key)?;
            let start = self.range(key).map_or(0.0, |r| r.default);
            let v = probe(k, *lo, *hi, start);
            let mut alone = vec![None; self.model.names.len()];
            for &t in &tiers {
                alone[t] = Some(match kind {
                    Some(TieKind::Together) => self.angles[t] + v,
                    _ => v,
                });
                together[t] = alone[t];
            }
            note(self.opened(&self.model.reangled(&alone)?), Some(key));
        }
        note(self.opened(&self.model.reangled(&together)?), None);
        out.sort_by_key(|o| o.meet);
        Ok(out)
    }

    /// How far each of the design's meets is from kept in `cut` (a cut of this space: its
    /// facets by name), in W: 0 where kept.
    pub fn gaps(&self, cut: &Cut) -> Vec<f64> {
        gaps_in(&self.model, &cut.solid)
    }

    fn tier(&self, key: &str) -> Result<usize> {
        self.key_tiers
            .iter()
            .copied()
            .find(|&t| self.model.names[t] == key)
            .ok_or_else(|| {
                Error::invalid(
                    key,
                    format!(
                        "{} has no tier `{key}` whose angle can turn; its tiers: {} (or a tie of them: `A+B` turned by one change of angle, `A=B` set to one angle)",
                        self.name,
                        self.keys().join(", ")
                    ),
                )
            })
    }

    /// The names of the tiers a key turns: a tier key its own, a tie ([`Tie`]) its tiers.
    pub fn tiers_of(&self, key: &str) -> Result<Vec<&str>> {
        let (tiers, _) = self.resolve(key)?;
        Ok(tiers
            .iter()
            .map(|&t| self.model.names[t].as_str())
            .collect())
    }

    /// A key's tiers, and the tie it is (`None`: one tier).
    pub(super) fn resolve(&self, key: &str) -> Result<(Vec<usize>, Option<TieKind>)> {
        if let Ok(t) = self.tier(key) {
            return Ok((vec![t], None));
        }
        let Some(tie) = Tie::parse(key) else {
            return Err(self.tier(key).unwrap_err());
        };
        let mut tiers = Vec::new();
        for name in &tie.tiers {
            let t = self.tier(name).map_err(|e| match e {
                Error::Invalid { message, .. } => Error::invalid(key, message),
                other => other,
            })?;
            if tiers.contains(&t) {
                return Err(Error::invalid(
                    key,
                    format!("tier {name} is tied twice; name each tier once"),
                ));
            }
            tiers.push(t);
        }
        Ok((tiers, Some(tie.kind)))
    }

    /// Each tier's angle at `values` (completed by [`CutSpace::complete`]): tier keys first,
    /// then `=` ties set their tiers, then `+` ties turn theirs. An angle outside (0, 90) is
    /// an error naming its key.
    fn targets(&self, values: &BTreeMap<String, f64>) -> Result<Vec<f64>> {
        let mut target = self.angles.clone();
        let mut ties = Vec::new();
        for (k, &v) in values {
            let (tiers, kind) = self.resolve(k)?;
            match kind {
                None => target[tiers[0]] = v,
                Some(kind) => ties.push((k, v, tiers, kind)),
            }
        }
        // `=` ties first (a tier is in one tie at most: `complete` checks it).
        for (_, v, tiers, kind) in &ties {
            if *kind == TieKind::Equal {
                for &t in tiers {
                    target[t] = *v;
                }
            }
        }
        for (k, v, tiers, kind) in &ties {
            if *kind == TieKind::Together {
                for &t in tiers {
                    target[t] += v;
                    if !(target[t] > 0.0 && target[t] < 90.0) {
                        return Err(Error::invalid(
                            k.as_str(),
                            format!(
                                "turns tier {} to {:.4}°, outside (0, 90) degrees",
                                self.model.names[t], target[t]
                            ),
                        ));
                    }
                }
            }
        }
        Ok(target)
    }

    /// The range of a resolved key: a tier's angle (0, 90); a `+` tie's change of angle that
    /// keeps each of its tiers in (0, 90), default 0; a `=` tie's angle (0, 90), default its
    /// tiers' mean angle on GemCad's grid.
    fn range_of(&self, tiers: &[usize], kind: Option<TieKind>) -> ParamRange {
        let (default, min, max) = match kind {
            None => (self.angles[tiers[0]], 0.0, 90.0),
            Some(TieKind::Together) => (
                0.0,
                tiers
                    .iter()
                    .map(|&t| -self.angles[t])
                    .fold(f64::MIN, f64::max),
                tiers
                    .iter()
                    .map(|&t| 90.0 - self.angles[t])
                    .fold(f64::MAX, f64::min),
            ),
            Some(TieKind::Equal) => {
                let mean = tiers.iter().map(|&t| self.angles[t]).sum::<f64>() / tiers.len() as f64;
                (on_grid(mean), 0.0, 90.0)
            }
        };
        ParamRange {
            default,
            min,
            max,
            open: true,
            unit: Unit::Degrees,
        }
    }

    pub(super) fn opened(&self, r: &Reangled) -> Vec<usize> {
        (0..r.gaps.len())
            .filter(|&m| r.gaps[m] > self.model.tol + self.model.slack[m])
            .collect()
    }

    /// The footnote a changed design carries: which tiers turned, from what to what.
    fn footnote(&self, values: &BTreeMap<String, f64>) -> Option<String> {
        let mut out = String::new();
        for &t in &self.key_tiers {
            let name = &self.model.names[t];
            let (was, now) = (self.angles[t], values[name]);
            if fixed(was, 2) != fixed(now, 2) {
                let sep = if out.is_empty() { "" } else { ", " };
                let _ = write!(out, "{sep}{name} {} (was {})", fixed(now, 2), fixed(was, 2));
            }
        }
        (!out.is_empty()).then(|| format!("Angles changed by facetlab, meets kept: {out}"))
    }
}

/// How far each of `model`'s meets is from kept in `solid` (its facets found by name), in W.
fn gaps_in(model: &TierModel, solid: &Polyhedron) -> Vec<f64> {
    let index: BTreeMap<&str, usize> = solid
        .facets()
        .iter()
        .enumerate()
        .map(|(i, f)| (f.name.as_str(), i))
        .collect();
    model
        .meets
        .iter()
        .map(|m| {
            let planes: Vec<_> = m
                .facets
                .iter()
                .filter_map(|&f| index.get(model.solid.facets()[f].name.as_str()))
                .map(|&i| {
                    let p = solid.facets()[i].plane;
                    (p.normal, p.offset)
                })
                .collect();
            match super::meets::least_squares_point(&planes) {
                Some(p) if planes.len() == m.facets.len() => planes
                    .iter()
                    .map(|(n, d)| (n.dot(p) - d).abs())
                    .fold(0.0, f64::max),
                _ => f64::INFINITY,
            }
        })
        .collect()
}

/// Whether tier `t` has an azimuth to turn about (not a table or culet).
fn turnable(model: &TierModel, t: usize) -> bool {
    model
        .tier_of
        .iter()
        .zip(model.solid.facets())
        .any(|(&ft, f)| ft == t && f.plane.normal.x.hypot(f.plane.normal.y) > 1e-12)
}

/// `x` on GemCad's angle grid: what the `.asc` writer writes, read back.
fn on_grid(x: f64) -> f64 {
    fixed(x, ANGLE_DECIMALS).parse().unwrap_or(x)
}

impl CutSpace for DesignSpace {
    fn name(&self) -> &str {
        &self.name
    }

    fn keys(&self) -> Vec<&str> {
        self.key_tiers
            .iter()
            .map(|&t| self.model.names[t].as_str())
            .collect()
    }

    fn range(&self, key: &str) -> Option<ParamRange> {
        let (tiers, kind) = self.resolve(key).ok()?;
        Some(self.range_of(&tiers, kind))
    }

    fn complete(&self, values: &BTreeMap<String, f64>) -> Result<BTreeMap<String, f64>> {
        let mut out = self.defaults();
        let mut given: Vec<Option<&str>> = vec![None; self.model.names.len()];
        for (k, &v) in values {
            let (tiers, kind) = self.resolve(k)?;
            let r = self.range_of(&tiers, kind);
            if !(v.is_finite() && r.contains(v)) {
                let what = match kind {
                    Some(TieKind::Together) => format!(
                        "{} is not a change of angle that keeps every tier of the tie in (0, 90) degrees; allowed ({:.4}, {:.4})",
                        shown(v),
                        r.min, r.max
                    ),
                    _ => format!("{} is not an angle in (0, 90) degrees", shown(v)),
                };
                return Err(Error::invalid(k.as_str(), what));
            }
            // A tier in two ties is ambiguous (a tier key beside a tie is not: a `+` tie
            // turns it from its value, a `=` tie sets it).
            for &t in tiers.iter().filter(|_| kind.is_some()) {
                if let Some(other) = given[t].replace(k) {
                    return Err(Error::invalid(
                        k.as_str(),
                        format!(
                            "tier {} is also in `{other}`; give each tier in one key",
                            self.model.names[t]
                        ),
                    ));
                }
            }
            out.insert(k.clone(), v);
        }
        Ok(out)
    }

    fn build(&self, name: &str, values: &BTreeMap<String, f64>) -> Result<Cut> {
        self.build_at(name, values, true)
    }
}

impl DesignSpace {
    /// [`CutSpace::build`]; `suggest`: a refusal of one turned key names the tie that would
    /// keep its meets ([`DesignSpace::tie_for`], a few dozen depth solves).
    pub(super) fn build_at(
        &self,
        name: &str,
        values: &BTreeMap<String, f64>,
        suggest: bool,
    ) -> Result<Cut> {
        let completed = self.complete(values)?;
        let target = self.targets(&completed)?;
        let mut angles = vec![None; self.model.names.len()];
        let mut used = BTreeMap::new();
        for &t in &self.key_tiers {
            let key = &self.model.names[t];
            let v = target[t];
            if v != self.angles[t] {
                let g = on_grid(v);
                angles[t] = Some(g);
                used.insert(key.clone(), g);
            } else {
                used.insert(key.clone(), v);
            }
        }
        let r = self.model.reangled(&angles)?;
        let opened = self.opened(&r);
        if self.open == OpenMeets::Refuse {
            if let Some(&m) = opened.first() {
                let tiers = self.model.meet_tiers(&self.model.meets[m]);
                // The keys that turn something, and of them the one in the meet (else the
                // first).
                let turned: Vec<&String> = completed
                    .iter()
                    .filter(|(k, _)| {
                        self.resolve(k)
                            .is_ok_and(|(ts, _)| ts.iter().any(|&t| angles[t].is_some()))
                    })
                    .map(|(k, _)| k)
                    .collect();
                let key = turned
                    .iter()
                    .find(|k| {
                        self.resolve(k).is_ok_and(|(ts, _)| {
                            ts.iter()
                                .any(|&t| tiers.contains(&self.model.names[t].as_str()))
                        })
                    })
                    .or(turned.first())
                    .map(|k| k.as_str())
                    .unwrap_or_default();
                let tie = match turned.as_slice() {
                    [one] if suggest => {
                        let v = completed[*one];
                        self.tie_for(one, v)
                            .and_then(|t| Some((t, self.change_of(one, v).ok()?.1)))
                    }
                    _ => None,
                };
                let advice = match tie {
                    Some((t, d)) => format!(
                        "tie it: `{t}`, its tiers turned by one change of angle (here {d:+.2}°), keeps every meet"
                    ),
                    None => "turn its tiers together".to_string(),
                };
                return Err(Error::invalid(
                    key,
                    format!(
                        "these angles open the meet {} by {:.2e} W; {advice}",
                        self.describe(m),
                        r.gaps[m]
                    ),
                ));
            }
        }
        let solid = Polyhedron::from_planes(&r.planes)
            .map_err(|e| e.context(&format!("{name}: the design at these angles")))?;
        // Same design: the same edges, except (where allowed) around the opened meets.
        let now = adjacency_over(&solid, self.model.meet_tol());
        let free: BTreeSet<&str> = opened
            .iter()
            .flat_map(|&m| &self.model.meets[m].facets)
            .map(|&f| self.model.solid.facets()[f].name.as_str())
            .collect();
        let changed = self
            .adjacency
            .symmetric_difference(&now)
            .find(|(a, b)| !(free.contains(a.as_str()) && free.contains(b.as_str())));
        if let Some((a, b)) = changed {
            let what = if now.contains(&(a.clone(), b.clone())) {
                "a new edge appears between"
            } else {
                "the edge vanishes between"
            };
            return Err(Error::Geometry(format!(
                "{name}: not the same design at these angles: {what} facets {a} and {b}"
            )));
        }
        let mut record = self.base.record.clone().unwrap_or_default();
        record.footnotes.extend(self.footnote(&used));
        Ok(Cut {
            name: name.to_string(),
            family: None,
            params: used,
            solid,
            record: Some(record),
        })
    }
}

/// The setting that sets a cut's parameter or turns a design's tier (`KEY=VALUE`), named in
/// the errors of [`with_set`] and in `info`'s text, for each face to spell
/// ([`crate::error::setting`]).
pub const CUT_PARAMETER: &str = crate::error::Setting::CutParameter.name();

/// `cut` with `changes` applied: a family cut's parameters, or a design's tier angles (by
/// [`DesignSpace`], refusing angles that open a meet). The `--set KEY=VALUE` of the command
/// line.
///
/// Changes that make no solid are refused naming the setting `cut parameter` and the
/// changes (`A=89.9: …`), not as the geometry's own error.
pub fn with_set(cut: &Cut, changes: &BTreeMap<String, f64>) -> Result<Cut> {
    let unmade = |e: Error| match e {
        Error::Geometry(m) => Error::invalid(
            CUT_PARAMETER,
            format!(
                "{} makes no solid: {m}",
                changes
                    .iter()
                    .map(|(k, v)| format!("`{k}={}`", crate::error::shown(*v)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        ),
        other => other,
    };
    if changes.is_empty() || cut.family.is_some() {
        return cut.with_params(changes).map_err(unmade);
    }
    let space = DesignSpace::new(cut, super::MEET_TOL, OpenMeets::Refuse)?;
    space.build(&cut.name, changes).map_err(unmade)
}
